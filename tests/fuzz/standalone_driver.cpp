// Standalone replacement for libFuzzer's main (used when BOUNCE_FUZZ is off): runs every seed,
// then a fixed number of deterministic mutations of the seeds (std::mt19937_64 with a fixed
// seed: the same inputs on every run), and fails on the first exception that escapes the target.
//
//   fuzz_gltf_import [--iterations N] asset-path...   (paths relative to BOUNCE_SHARED_DIR)
//   fuzz_gltf_import --write-seeds DIR asset-path...  writes the seeds as DIR/seed-N (a libFuzzer
//                                                     corpus, see CMakeLists.txt) and exits
#include "tests/fuzz/fuzz_target.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace {

// One random edit: flip a bit, overwrite a byte with an "interesting" value, cut the tail,
// duplicate or delete a run of bytes, or overwrite 4 bytes with a boundary integer.
void mutate(std::vector<std::uint8_t>& b, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? std::size_t(0) : std::size_t(rng() % n); };
  const int kinds = 6;
  switch (rng() % kinds) {
    case 0:
      if (!b.empty()) b[pick(b.size())] ^= std::uint8_t(1u << (rng() % 8));
      break;
    case 1: {
      static const std::uint8_t interesting[] = {0, 1, 0x7F, 0x80, 0xFF, '"', '{', '}', '[', ']', ',', ':', '-', '9'};
      if (!b.empty()) b[pick(b.size())] = interesting[pick(sizeof interesting)];
      break;
    }
    case 2:
      b.resize(pick(b.size() + 1));
      break;
    case 3: {
      const std::size_t at = pick(b.size()), len = std::min<std::size_t>(pick(64) + 1, b.size() - at);
      b.insert(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + len));
      break;
    }
    case 4: {
      const std::size_t at = pick(b.size()), len = std::min<std::size_t>(pick(64) + 1, b.size() - at);
      b.erase(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + len));
      break;
    }
    default: {
      static const std::uint32_t values[] = {0u, 1u, 0x7FFFFFFFu, 0x80000000u, 0xFFFFFFFFu, 0xFFFFu, 4096u};
      if (b.size() >= 4) {
        const std::uint32_t v = values[pick(sizeof values / sizeof values[0])];
        const std::size_t at = pick(b.size() - 3);
        for (int k = 0; k < 4; ++k) b[at + std::size_t(k)] = std::uint8_t(v >> (8 * k));
      }
    }
  }
}

bool run(const std::vector<std::uint8_t>& input, const std::string& what) {
  try {
    LLVMFuzzerTestOneInput(input.data(), input.size());
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FAIL %s: exception escaped: %s\n", what.c_str(), e.what());
  } catch (...) {
    std::fprintf(stderr, "FAIL %s: unknown exception escaped\n", what.c_str());
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t iterations = 2000;
  std::vector<std::string> paths;
  std::filesystem::path seedDir;
  const char* env = std::getenv("BOUNCE_SHARED_DIR");
  const std::filesystem::path shared = env && *env ? env : BOUNCE_SHARED_DIR;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--iterations" && i + 1 < argc) iterations = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--write-seeds" && i + 1 < argc) seedDir = argv[++i];
    else paths.push_back((shared / a).string());
  }
  std::vector<std::vector<std::uint8_t>> seeds;
  try {
    seeds = fuzzSeeds(paths);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cannot make seeds: %s\n", e.what());
    return 1;
  }
  if (seeds.empty()) {
    std::fprintf(stderr, "no seeds given\n");
    return 1;
  }
  if (!seedDir.empty()) {
    std::filesystem::create_directories(seedDir);
    for (std::size_t s = 0; s < seeds.size(); ++s) {
      std::ofstream f(seedDir / ("seed-" + std::to_string(s)), std::ios::binary | std::ios::trunc);
      f.write(reinterpret_cast<const char*>(seeds[s].data()), std::streamsize(seeds[s].size()));
      if (!f) {
        std::fprintf(stderr, "cannot write %s\n", (seedDir / ("seed-" + std::to_string(s))).c_str());
        return 1;
      }
    }
    std::printf("wrote %zu seeds to %s\n", seeds.size(), seedDir.c_str());
    return 0;
  }
  for (std::size_t s = 0; s < seeds.size(); ++s)
    if (!run(seeds[s], "seed " + std::to_string(s))) return 1;
  std::mt19937_64 rng(0xB0C4CE);  // fixed: every run replays the same inputs
  for (std::size_t i = 0; i < iterations; ++i) {
    std::vector<std::uint8_t> input = seeds[i % seeds.size()];
    const int edits = 1 + int(rng() % 4);
    for (int e = 0; e < edits; ++e) mutate(input, rng);
    if (!run(input, "iteration " + std::to_string(i))) return 1;
  }
  std::printf("%zu seeds and %zu mutated inputs ran without escaping exceptions\n", seeds.size(), iterations);
  return 0;
}
