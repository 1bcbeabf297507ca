// bounce level FILE.glb --out L.json: the level `bounce play FILE.glb` makes (viewer_level.hpp),
// written for the user to edit and play as any level.
#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"
#include "game/viewer_level.hpp"

namespace bounce::game {

int runLevel(const cli::Args& args) {
  const std::filesystem::path input = args.positional[0];
  if (!args.has("--out")) throwInputError("bounce level", "--out", "missing", "an output level file, e.g. --out my-level.json");
  if (!isGltfFile(input)) throwInputError(input.string(), "file", "not a glTF file", "a .gltf or .glb file");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(input, ec)) throwInputError(input.string(), "file", "not found", "an existing .gltf or .glb file");
  const std::filesystem::path out = args.str("--out");
  const auto dir = std::filesystem::absolute(out).parent_path();
  std::filesystem::create_directories(dir);
  writeFileAtomic(out, viewerLevelText(input, assetBounds(input, cookCacheDir()), dir));
  std::printf("wrote %s (play it with: bounce play %s)\n", out.c_str(), out.c_str());
  return 0;
}

}  // namespace bounce::game
