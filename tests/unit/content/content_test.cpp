// Every level and capture script shipped in content/ passes the validator, and the Cornell levels
// hold what README promises: the closed box, one point light, and 1/5/10 dynamic props.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

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

// cornell-rtf is the RTF multi-bounce level (README "RTF"): three boxes with rtf and dnrt
// components side by side, the gap between neighbours within one bounding radius of a box (the
// Box asset is the unit cube: half-size s/2 and bounding radius s·√3/2 at scale s), so their
// fields reach each other's surfaces and light bounces between them.
TEST(Content, CornellRtfBoxesStandWithinOneBoundingRadius) {
  auto level = scene::loadLevel(kContent / "levels" / "cornell-rtf.json");
  std::vector<const scene::EntityDesc*> boxes;
  for (const auto& e : level.entities)
    if (e.rtf && e.dnrt) boxes.push_back(&e);
  ASSERT_EQ(boxes.size(), 3u);
  std::sort(boxes.begin(), boxes.end(), [](auto* a, auto* b) { return a->transform.translation.x < b->transform.translation.x; });
  for (std::size_t i = 0; i + 1 < boxes.size(); ++i) {
    const float s = boxes[i]->transform.scale.x;
    const float gap = boxes[i + 1]->transform.translation.x - boxes[i]->transform.translation.x - s;
    EXPECT_GT(gap, 0.0f);                               // not overlapping
    EXPECT_LE(gap, s * std::sqrt(3.0f) / 2.0f) << i;    // within one bounding radius
    EXPECT_EQ(boxes[i]->transform.translation.y, boxes[i + 1]->transform.translation.y);
  }
  EXPECT_TRUE(level.effects.has(scene::Effect::Rtf));
}
