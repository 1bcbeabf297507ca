// bounce vlm-make (LEVEL.json | ASSET.gltf|glb) --out FILE.gltf [--triangles N] [--offset M] [--node NAME]:
// subtractive VLM creation (thesis §3.7; engine/gi/vlm/make.hpp). Needs no Vulkan device.
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/core/error.hpp"
#include "engine/gi/vlm/make.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"

namespace bounce::game {
namespace {

constexpr const char* kWhat = "bounce vlm-make";

float offsetOption(const cli::Args& args) {
  if (!args.has("--offset")) return gi::vlm::MakeOptions{}.offset;
  const std::string text = args.str("--offset");
  char* end = nullptr;
  const double m = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(m) || m < 0.0 || m > 1e3)
    throwInputError(kWhat, "--offset", "'" + text + "'", "a distance in metres in [0, 1000]");
  return float(m);
}

std::string lowerExtension(const std::filesystem::path& p) {
  std::string e = p.extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

}  // namespace

int runVlmMake(const cli::Args& args) {
  const std::filesystem::path input = args.positional[0];
  if (!args.has("--out")) throwInputError(kWhat, "--out", "missing", "--out FILE.gltf");
  const std::filesystem::path out = args.str("--out");
  if (lowerExtension(out) != ".gltf")
    throwInputError(kWhat, "--out", "'" + out.string() + "' does not end in .gltf", "an output file name ending in .gltf");
  gi::vlm::MakeOptions options;
  options.triangles = std::size_t(args.positiveInt("--triangles", int(options.triangles)));
  options.offset = offsetOption(args);
  const std::string ext = lowerExtension(input);
  const bool isLevel = ext == ".json";
  if (!isLevel && ext != ".gltf" && ext != ".glb")
    throwInputError(kWhat, "INPUT", "'" + input.string() + "'", "a level .json or a .gltf/.glb asset");
  if (isLevel && args.has("--node"))
    throwInputError(kWhat, "--node", "only for a glTF asset input", "no --node with a level");

  const auto start = std::chrono::steady_clock::now();
  std::vector<gi::vlm::MakeSource> sources;
  std::size_t skipped = 0;
  std::filesystem::path levelDir;
  if (isLevel) {
    const scene::Level level = scene::loadLevel(input);
    levelDir = level.source.parent_path();
    sources = gi::vlm::sourcesFromLevel(level, cookCacheDir(), &skipped);
  } else {
    std::optional<std::string> node;
    if (args.has("--node")) node = args.str("--node");
    sources = gi::vlm::sourcesFromAsset(input, node, cookCacheDir());
  }
  gi::vlm::MakeResult r = gi::vlm::makeVlm(sources, options, kWhat);
  r.skippedDynamic = skipped;
  if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
  gi::vlm::writeVlmGltf(r, out);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("vlm-make: %zu source meshes, %zu -> %zu triangles (budget %zu), offset %g m behind the surface, "
              "%.1f ms; wrote %s\n",
              r.meshes.size(), r.inputTriangles, r.outputTriangles, options.triangles, double(options.offset), ms,
              out.c_str());
  if (skipped) std::printf("skipped %zu dynamic entities (attach their VLMs by hand, parented to them)\n", skipped);
  const std::string asSeen = isLevel ? std::filesystem::relative(std::filesystem::absolute(out), levelDir).generic_string()
                                     : out.generic_string();
  std::fputs(gi::vlm::levelSnippet(r, asSeen).c_str(), stdout);
  return 0;
}

}  // namespace bounce::game
