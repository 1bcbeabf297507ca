// bounce cook FILE...: cook glTF/glb files, or every asset a level uses, into the content cache.
#include <chrono>
#include <cstdio>
#include <set>

#include "engine/asset/cook.hpp"
#include "engine/core/progress.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/scene/components.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"

namespace bounce::game {

int runCook(const cli::Args& args) {
  const std::filesystem::path out = args.has("--out") ? std::filesystem::path(args.str("--out")) : cookCacheDir();
  std::vector<std::filesystem::path> files;
  for (const auto& p : args.positional) {
    std::filesystem::path path(p);
    if (path.extension() == ".json") {
      scene::Level level = scene::loadLevel(path);
      std::set<std::filesystem::path> assets;
      for (const auto& e : level.entities)
        if (e.mesh) assets.insert(e.mesh->asset);
      files.insert(files.end(), assets.begin(), assets.end());
    } else {
      files.push_back(path);
    }
  }
  const auto start = std::chrono::steady_clock::now();
  std::size_t triangles = 0;
  Progress progress("cook", files.size());
  for (const auto& f : files) {
    triangles += asset::loadOrCook(f, out, {}).triangleCount();
    progress.advance();
  }
  progress.finish();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("cooked %zu file(s), %zu triangles, into %s in %.2f s\n", files.size(), triangles, out.c_str(), s);
  return 0;
}

}  // namespace bounce::game
