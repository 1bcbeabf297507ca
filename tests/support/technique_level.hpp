#pragma once
// What the CPU tests of a technique component share (tests/unit/{rtf,sl}/technique_test.cpp): a
// level of a few entities written under the test's output folder, its one-line load error with the
// path shown as FILE, and the level loaded, instantiated and transformed for the technique's
// LevelContext. One copy: the two files had the same helpers written out twice.
#include <cstdlib>
#include <filesystem>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/technique.hpp"
#include "engine/scene/level.hpp"
#include "engine/scene/systems.hpp"

namespace bounce::testlevel {

// The cooked-asset cache the session would use (BOUNCE_COOK_CACHE, else the build's).
inline std::filesystem::path cookCache() {
  if (const char* env = std::getenv("BOUNCE_COOK_CACHE"); env && *env) return env;
  return cacheDir("cooked");
}

// The textured box (24 vertices): the tests' participant.
inline std::string boxAsset() {
  return (std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/src/BoxTextured/glTF-Draco-gltfpipeline/BoxTextured.gltf")
      .string();
}
inline std::string boxMesh() { return R"("mesh": {"asset": ")" + boxAsset() + R"("})"; }

// A level with `entities` (JSON object bodies, comma-separated) and `effects` (a JSON array),
// written to dir/<name>.json.
inline std::filesystem::path writeLevel(const std::filesystem::path& dir, const std::string& name,
                                        const std::string& entities, const std::string& effects) {
  const std::filesystem::path path = dir / (name + ".json");
  writeFileAtomic(path, R"({"bounce_level": 1, "effects": )" + effects + R"(, "entities": [)" + entities + "]}");
  return path;
}

// The InputError of loading and instantiating that level, its path replaced by "FILE", or "(no error)".
inline std::string loadError(const std::filesystem::path& dir, const std::string& name, const std::string& entities,
                             const std::string& effects) {
  const std::filesystem::path path = writeLevel(dir, name, entities, effects);
  try {
    ecs::Registry r;
    scene::instantiate(scene::loadLevel(path), r);
  } catch (const InputError& e) {
    std::string msg = e.what();
    const std::string prefix = path.string() + ": ";
    if (msg.rfind(prefix, 0) == 0) msg = "FILE: " + msg.substr(prefix.size());
    return msg;
  }
  return "(no error)";
}

// A level loaded, instantiated and its transforms resolved (t = 0), with the technique's view of it.
struct Loaded {
  scene::Level level;
  ecs::Registry registry;
  explicit Loaded(const std::filesystem::path& path) : level(scene::loadLevel(path)) {
    scene::instantiate(level, registry);
    scene::transformSystem(registry);
  }
  gi::LevelContext context() { return {level, registry, cookCache()}; }
};

}  // namespace bounce::testlevel
