// The "without" level of the object-effect metric: no dynamic entity, no child of one, every
// static entity unchanged and in order; the JSON form the tracer reads says the same.
#include <gtest/gtest.h>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "game/accuracy_level.hpp"

namespace bounce::game {
namespace {

std::filesystem::path cornell() { return std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json"; }

std::vector<std::string> ids(const scene::Level& level) {
  std::vector<std::string> out;
  for (const auto& e : level.entities) out.push_back(e.id);
  return out;
}

scene::EntityDesc entity(std::string id, bool dynamic = false, std::optional<std::string> parent = std::nullopt) {
  scene::EntityDesc e;
  e.id = std::move(id);
  e.dynamic = dynamic;
  e.parent = std::move(parent);
  return e;
}

TEST(WithoutDynamic, CornellKeepsEveryStaticEntityAndNoDynamicOne) {
  const scene::Level level = scene::loadLevel(cornell());
  const scene::Level without = withoutDynamicEntities(level);
  std::vector<std::string> expected;
  std::size_t dynamicCount = 0;
  for (const auto& e : level.entities) {
    if (e.dynamic) ++dynamicCount;
    else expected.push_back(e.id);
  }
  ASSERT_GT(dynamicCount, 0u) << "cornell-1 has a dynamic prop; the metric needs one";
  EXPECT_EQ(ids(without), expected);
  for (const auto& e : without.entities) EXPECT_FALSE(e.dynamic || e.motion) << e.id;
  // Static entities are copied unchanged.
  for (const auto& e : without.entities)
    for (const auto& o : level.entities)
      if (o.id == e.id) {
        EXPECT_EQ(e.mesh, o.mesh);
        EXPECT_EQ(e.light, o.light);
        EXPECT_EQ(e.parent, o.parent);
      }
  EXPECT_EQ(without.effects, level.effects);
  EXPECT_EQ(without.source, level.source);
}

TEST(WithoutDynamic, JsonFormLoadsAnywhereAndMatchesTheLevelCopy) {
  const scene::Level level = scene::loadLevel(cornell());
  // Saved far from the level file: asset paths must have been made absolute.
  const auto path = std::filesystem::path(BOUNCE_TEST_OUT) / "accuracy" / "json-form" / "cornell-static.json";
  writeFileAtomic(path, withoutDynamicEntitiesJson(level));
  const scene::Level fromJson = scene::loadLevel(path);
  const scene::Level copy = withoutDynamicEntities(level);
  EXPECT_EQ(ids(fromJson), ids(copy));
  ASSERT_EQ(fromJson.entities.size(), copy.entities.size());
  for (std::size_t i = 0; i < copy.entities.size(); ++i) {
    EXPECT_EQ(fromJson.entities[i].mesh, copy.entities[i].mesh) << copy.entities[i].id;
    EXPECT_EQ(fromJson.entities[i].light, copy.entities[i].light) << copy.entities[i].id;
    EXPECT_FALSE(fromJson.entities[i].dynamic) << copy.entities[i].id;
  }
  EXPECT_EQ(fromJson.effects, level.effects);
}

TEST(WithoutDynamic, ChildrenGoWithTheirDynamicAncestorWhateverTheFileOrder) {
  scene::Level level;
  // "grandchild" comes before its parent in the file; "moving" is dynamic through its motion.
  level.entities.push_back(entity("grandchild", false, "child"));
  level.entities.push_back(entity("static-root"));
  level.entities.push_back(entity("prop", true));
  level.entities.push_back(entity("child", false, "prop"));
  level.entities.push_back(entity("static-child", false, "static-root"));
  scene::EntityDesc moving = entity("moving");
  moving.motion = scene::Motion{};
  level.entities.push_back(moving);
  EXPECT_EQ(dynamicEntityIds(level), (std::set<std::string>{"grandchild", "prop", "child", "moving"}));
  EXPECT_EQ(ids(withoutDynamicEntities(level)), (std::vector<std::string>{"static-root", "static-child"}));
}

TEST(WithoutDynamic, CamerasStayButNotOnARemovedObject) {
  scene::Level level;
  scene::EntityDesc flyCam = entity("fly-cam", true);
  flyCam.camera = scene::Camera{};
  level.entities.push_back(flyCam);
  EXPECT_TRUE(dynamicEntityIds(level).empty()) << "a dynamic camera is the viewpoint, not an object";

  level.entities.push_back(entity("prop", true));
  scene::EntityDesc rider = entity("rider-cam", false, "prop");
  rider.camera = scene::Camera{};
  level.entities.push_back(rider);
  EXPECT_THROW(dynamicEntityIds(level), InputError);
}

}  // namespace
}  // namespace bounce::game
