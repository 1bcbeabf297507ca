// Fuzz target: bytes → glTF import, once as given (GLB when it starts with "glTF", else JSON) and
// once wrapped as the JSON chunk of a GLB. No base folder, so no external file is ever read.
#include "engine/asset/cook.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/log.hpp"
#include "tests/fuzz/fuzz_target.hpp"

#include <span>

namespace {

void importOnce(std::span<const std::uint8_t> bytes, const char* name) {
  bounce::asset::CookOptions options;
  options.decodeImages = true;
  try {
    (void)bounce::asset::cookFromMemory(bytes, name, {}, options);
  } catch (const bounce::InputError&) {
    // expected for most inputs
  }
}

std::vector<std::uint8_t> asGlbJsonChunk(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> out;
  auto put32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(std::uint8_t(v >> (8 * k)));
  };
  const std::size_t padded = (size + 3) / 4 * 4;
  put32(0x46546C67);
  put32(2);
  put32(std::uint32_t(20 + padded));
  put32(std::uint32_t(padded));
  put32(0x4E4F534A);
  out.insert(out.end(), data, data + size);
  out.resize(20 + padded, ' ');
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  bounce::log::setLevel(bounce::log::Level::Quiet);
  importOnce(std::span(data, size), "fuzz.gltf");
  if (size < (std::size_t(1) << 24)) importOnce(asGlbJsonChunk(data, size), "fuzz.glb");
  return 0;
}

std::vector<std::vector<std::uint8_t>> fuzzSeeds(const std::vector<std::string>& assetPaths) {
  std::vector<std::vector<std::uint8_t>> out;
  for (const auto& p : assetPaths) out.push_back(bounce::readFileBytes(p));
  return out;
}
