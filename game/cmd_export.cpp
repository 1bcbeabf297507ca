// bounce export LEVEL OUT.glb [--time T]: the composed level as one glTF 2.0 binary, for opening
// and cross-checking in other tools (engine/scene_export/export.hpp describes the file and the
// light-unit convention). Needs no Vulkan device.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/core/error.hpp"
#include "engine/scene_export/export.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"
#include "game/viewer_level.hpp"

namespace bounce::game {
namespace {

// --time: a finite number of seconds (any sign: motion scripts are defined for every time).
double timeOption(const cli::Args& args) {
  if (!args.has("--time")) return 0.0;
  const std::string text = args.str("--time");
  char* end = nullptr;
  const double t = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(t))
    throwInputError("bounce export", "--time", "'" + text + "' is not a number", "a finite time in seconds");
  return t;
}

}  // namespace

int runExport(const cli::Args& args) {
  const std::filesystem::path levelPath = levelPathFor(args.positional[0]);
  const std::filesystem::path out = args.positional[1];
  if (out.extension() != ".glb")
    throwInputError("bounce export", "OUT", "'" + out.string() + "' does not end in .glb", "an output file name ending in .glb");
  scene_export::ExportOptions options;
  options.timeSeconds = timeOption(args);
  options.cookCache = cookCacheDir();
  const scene::Level level = scene::loadLevel(levelPath);
  const auto s = scene_export::exportLevel(level, out, options);
  std::printf("wrote %s at t = %g s: %zu instances (%zu triangles), %zu meshes, %zu materials, %zu textures, "
              "%zu lights, %zu cameras, %zu bytes\n",
              out.c_str(), options.timeSeconds, s.instances, s.triangles, s.meshes, s.materials, s.textures, s.lights,
              s.cameras, s.bytes);
  return 0;
}

}  // namespace bounce::game
