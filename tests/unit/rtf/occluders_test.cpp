// The bouncing step's lamp through the posed objects (issue 14, session 18):
// PosedOccluders' world segments through an object posed in its own frame (occluders.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gi/rtf/occluders.hpp"

namespace bounce::gi::rtf {
namespace {

render::LightGpu pointLight(glm::vec3 position, glm::vec3 intensity) {
  render::LightGpu l{};
  l.positionType = glm::vec4(position, float(render::LightType::Point));
  l.directionRange = glm::vec4(0.0f, 0.0f, -1.0f, 0.0f);
  l.radiance = glm::vec4(intensity, 0.0f);
  l.cone = glm::vec4(0.0f, 1.0f, 0.0f, 0.0f);
  l.shadow = glm::vec4(-1.0f);
  return l;
}

// An axis-aligned box [lo, hi] as a closed triangle mesh (the shadow rays' occluder).
ref::SceneDesc boxScene(glm::vec3 lo, glm::vec3 hi) {
  ref::SceneDesc s;
  s.materials.push_back({});
  ref::RefMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  m.normals.assign(8, glm::vec3(0.0f, 1.0f, 0.0f));
  m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
  s.meshes.push_back(std::move(m));
  return s;
}

// A unit box posed by a rotation, a scale of 0.2 and a translation blocks exactly the world rays through
// its posed volume: t is the world's (the direction is not renormalised in its frame), tMax ends the
// segment before it, its own index is left out, and a box with no triangles blocks nothing.
TEST(RtfOccluders, PosedBoxBlocksTheWorldSegmentsThroughIt) {
  std::vector<ref::SceneDesc> scenes = {boxScene(glm::vec3(-0.5f), glm::vec3(0.5f)), ref::SceneDesc{}};
  const PosedOccluders occ(std::move(scenes));
  ASSERT_EQ(occ.size(), 2u);
  const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 2.0f, 0.0f)) *
                          glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0.0f, 1.0f, 0.0f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.2f));
  const std::optional<PosedOccluders::Pose> p = occ.pose(0, world);
  ASSERT_TRUE(p.has_value());
  EXPECT_FALSE(occ.pose(1, world).has_value());  // no triangles: nothing to pose
  const std::vector<PosedOccluders::Pose> poses = {*p};
  const glm::vec3 o(1.0f, 0.0f, 0.0f), up(0.0f, 1.0f, 0.0f);  // the box spans y 1.9..2.1 above o
  EXPECT_TRUE(occ.occluded(poses, 99, o, up, 5.0f));
  EXPECT_TRUE(occ.occluded(poses, 99, o, up, std::numeric_limits<float>::infinity()));
  EXPECT_FALSE(occ.occluded(poses, 99, o, up, 1.85f));  // the segment ends 5 cm short of it
  EXPECT_TRUE(occ.occluded(poses, 99, o, up, 1.95f));
  EXPECT_FALSE(occ.occluded(poses, 0, o, up, 5.0f));  // its own rays: left out
  EXPECT_FALSE(occ.occluded(poses, 99, o + glm::vec3(0.2f, 0.0f, 0.0f), up, 5.0f));  // beside it (bounding sphere 0.173 m)
  EXPECT_FALSE(occ.occluded({}, 99, o, up, 5.0f));
}

}  // namespace
}  // namespace bounce::gi::rtf
