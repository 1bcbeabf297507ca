// loadOrBake on a real level: static-only scene, cache reuse, corrupt entries re-baked,
// deterministic bakes.
#include <gtest/gtest.h>

#include <filesystem>

#include "engine/core/file.hpp"
#include "engine/gi/probes/bake.hpp"

using namespace bounce;
using namespace bounce::gi::probes;
namespace fs = std::filesystem;

namespace {

const fs::path kLevel = fs::path(BOUNCE_SOURCE_DIR) / "tests/data/probes/room.json";

ProbeSettings small() {
  ProbeSettings s;
  s.spacing = 0.25f;  // 3×3×3 probes in the 0.56 m box
  s.rays = 64;
  s.bounces = 1;
  return s;
}

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::path(BOUNCE_TEST_OUT) / name;
  fs::remove_all(d);
  return d;
}

}  // namespace

TEST(ProbeCache, StaticLevelDropsDynamicEntitiesAndTheirChildren) {
  const scene::Level level = scene::loadLevel(kLevel);
  std::vector<std::string> ids;
  for (const auto& e : staticLevel(level).entities) ids.push_back(e.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"box", "camera", "lamp"}));
}

TEST(ProbeCache, ReusedWhenValidRebakedWhenCorruptAndDeterministic) {
  const scene::Level level = scene::loadLevel(kLevel);
  const fs::path cook = fs::path(BOUNCE_TEST_OUT) / "cooked", cache = freshDir("probe-cache");
  const LoadResult first = loadOrBake(level, cook, cache, small());
  EXPECT_FALSE(first.fromCache);
  EXPECT_EQ(first.volume.grid.count, glm::ivec3(3));
  EXPECT_EQ(first.stats.probes, 27u);
  ASSERT_TRUE(fs::exists(first.file));
  EXPECT_EQ(first.file.parent_path(), cache);

  const LoadResult second = loadOrBake(level, cook, cache, small());
  EXPECT_TRUE(second.fromCache);
  EXPECT_EQ(second.file, first.file);
  EXPECT_EQ(second.volume.sh, first.volume.sh);

  // Flip one byte in the middle of the SH data: the checksum catches it and the bake reruns,
  // giving bit-identical data (seeds come from probe indices, not threads).
  auto bytes = readFileBytes(first.file);
  bytes[bytes.size() / 2] ^= 0x01;
  writeFileAtomic(first.file, bytes);
  const LoadResult third = loadOrBake(level, cook, cache, small());
  EXPECT_FALSE(third.fromCache);
  EXPECT_EQ(third.volume.sh, first.volume.sh);
  EXPECT_EQ(third.volume.moments, first.volume.moments);
  EXPECT_EQ(third.volume.valid, first.volume.valid);

  // Other settings: another entry.
  ProbeSettings other = small();
  other.order = 2;
  const LoadResult fourth = loadOrBake(level, cook, cache, other);
  EXPECT_FALSE(fourth.fromCache);
  EXPECT_NE(fourth.file, first.file);
  EXPECT_EQ(fourth.volume.sh.size(), 27u * 4u);
}

TEST(ProbeCache, TheDynamicLightDoesNotReachTheBake) {
  // The level's only bright light rides the dynamic entity (intensity 5 vs 0.1): the baked
  // irradiance must be what the static lamp alone gives, i.e. the same as a level without them.
  scene::Level level = scene::loadLevel(kLevel);
  const fs::path cook = fs::path(BOUNCE_TEST_OUT) / "cooked";
  const LoadResult with = loadOrBake(level, cook, freshDir("probe-cache-a"), small());
  level.entities.resize(3);
  const LoadResult without = loadOrBake(level, cook, freshDir("probe-cache-b"), small());
  EXPECT_EQ(with.volume.sh, without.volume.sh);
}

// Issue 11: the key hashes the assets' content keys, not their absolute paths: the same level and
// asset in two folders (a moved or second checkout) name the same cache entry.
TEST(ProbeCache, KeyDoesNotDependOnWhereTheCheckoutIs) {
  const fs::path root = freshDir("probe-cache-moved");
  const std::string levelJson =
      R"({"bounce_level": 1, "effects": ["direct", "probes"], "probes": {"spacing": 1.0, "rays": 64},
          "entities": [{"id": "floor", "mesh": {"asset": "quad.gltf"}},
                       {"id": "lamp", "transform": {"translation": [0, 1, 0]},
                        "light": {"type": "point", "color": [1, 1, 1], "intensity": 1}}]})";
  std::vector<std::string> keys;
  for (const char* where : {"a/checkout", "b/moved/elsewhere"}) {
    const fs::path dir = root / where;
    fs::create_directories(dir);
    fs::copy_file(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/render/quad.gltf", dir / "quad.gltf");
    writeFileAtomic(dir / "level.json", levelJson);
    const scene::Level level = scene::loadLevel(dir / "level.json");
    keys.push_back(prepare(level, root / "cooked", settingsFrom(level)).key);
  }
  EXPECT_EQ(keys[0], keys[1]);
}
