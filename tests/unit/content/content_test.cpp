// Every level and capture script shipped in content/ passes the validator, and the Cornell levels
// hold what README promises: the closed box, one point light, and 1/5/10 dynamic props.
#include <gtest/gtest.h>

#include <filesystem>

#include "engine/ecs/registry.hpp"
#include "engine/scene/capture.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/level.hpp"

using namespace bounce;
namespace fs = std::filesystem;

namespace {
const fs::path kContent = fs::path(BOUNCE_SOURCE_DIR) / "content";
}

TEST(Content, EveryLevelLoads) {
  int count = 0;
  for (const auto& e : fs::directory_iterator(kContent / "levels")) {
    if (e.path().extension() != ".json") continue;
    EXPECT_NO_THROW(scene::loadLevel(e.path())) << e.path();
    ++count;
  }
  EXPECT_GE(count, 3);
}

TEST(Content, EveryCaptureScriptLoads) {
  int count = 0;
  for (const auto& e : fs::directory_iterator(kContent / "captures")) {
    if (e.path().extension() != ".json") continue;
    EXPECT_NO_THROW(scene::loadCaptureScript(e.path())) << e.path();
    ++count;
  }
  EXPECT_GE(count, 3);
}

TEST(Content, CornellLevelsHaveTheirDynamicProps) {
  for (int n : {1, 5, 10}) {
    auto level = scene::loadLevel(kContent / "levels" / ("cornell-" + std::to_string(n) + ".json"));
    ecs::Registry reg;
    scene::instantiate(level, reg);
    int dynamic = 0, lights = 0, cameras = 0;
    reg.view<scene::Dynamic>().each([&](ecs::Entity, scene::Dynamic&) { ++dynamic; });
    reg.view<scene::Light>().each([&](ecs::Entity, scene::Light& l) {
      ++lights;
      EXPECT_EQ(l.type, scene::LightType::Point);
    });
    reg.view<scene::Camera>().each([&](ecs::Entity, scene::Camera&) { ++cameras; });
    EXPECT_EQ(dynamic, n);
    EXPECT_EQ(lights, 1);
    EXPECT_EQ(cameras, 1);
    EXPECT_TRUE(level.effects.has(scene::Effect::Direct));
  }
}
