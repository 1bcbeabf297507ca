// Pose and skinning jobs: the two-bone closed form, 8 influences, morph targets, the rest pose of
// a real rig, and the rule that an unanimated node's local matrix is the static path's, bit for bit.
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "engine/anim/pose.hpp"
#include "engine/anim/skinning.hpp"
#include "engine/asset/cook.hpp"
#include "engine/scene/asset_instances.hpp"

namespace bounce::anim {
namespace {

// The closed forms below go through one 4×4 blend, one 3×3 inverse and a normalise: a few ulps.
constexpr float kClosedForm = 1e-6f;

std::filesystem::path assets() {
  const char* env = std::getenv("BOUNCE_SHARED_DIR");
  return std::filesystem::path(env && *env ? env : BOUNCE_SHARED_DIR) / "assets";
}

// Two bones at the origin under one root: bone A (node 1) fixed, bone B (node 2) rotated 90° about
// +Z by a one-key STEP clip; identity inverse bind matrices. Vertex 0 at (1, 0, 0) weighted
// 0.5/0.5 with JOINTS_0; vertex 1 the same split over JOINTS_0 and JOINTS_1 (4 × 0.25).
asset::CookedAsset twoBones() {
  asset::CookedAsset a;
  a.sourceName = "two-bones";
  a.nodes.resize(4);
  a.nodes[0].children = {1, 2, 3};
  a.nodes[3].mesh = 0;
  a.nodes[3].skin = 0;
  a.nodes[3].translation = {5, 5, 5};  // ignored: the spec drops the skinned node's own transform
  a.rootNodes = {0};
  asset::Skin skin;
  skin.joints = {1, 2};
  skin.inverseBindMatrices = {glm::mat4(1.0f), glm::mat4(1.0f)};
  a.skins = {skin};
  asset::Primitive p;
  p.positions = {{1, 0, 0}, {1, 0, 0}};
  p.normals = {{0, 1, 0}, {0, 1, 0}};
  p.indices = {0, 1, 0};
  p.joints = {{0, 1, 0, 0}, {0, 1, 0, 0}};
  p.weights = {{0.5f, 0.5f, 0, 0}, {0.25f, 0.25f, 0, 0}};
  p.joints1 = {{0, 0, 0, 0}, {0, 1, 0, 0}};
  p.weights1 = {{0, 0, 0, 0}, {0.25f, 0.25f, 0, 0}};
  asset::Mesh m;
  m.primitives = {p};
  a.meshes = {m};
  const float h = std::sqrt(0.5f);
  asset::AnimationSampler s;
  s.input = {0};
  s.output = {0, 0, h, h};
  s.components = 4;
  s.interpolation = asset::Interpolation::Step;
  asset::Animation clip;
  clip.samplers = {s};
  clip.channels = {{0, 2, asset::AnimationPath::Rotation}};
  a.animations = {clip};
  asset::validate(a, "two-bones");
  return a;
}

TEST(Skinning, TwoBonesHalfAndHalfLandWhereTheAlgebraSays) {
  const asset::CookedAsset a = twoBones();
  Pose pose;
  evaluatePose(a, 0, 0.0f, pose);
  std::vector<glm::vec3> pos, nrm;
  ASSERT_TRUE(posePrimitive(a, 3, 0, &pose, pos, nrm));
  // p = 0.5·(1, 0, 0) + 0.5·R_z(90°)(1, 0, 0) = (0.5, 0.5, 0).
  // S₃ = 0.5(I + R) = (1/√2)·R_z(45°) in the xy plane, so inverse-transpose(S₃)·n ∝ R_z(45°)·n:
  // n = (0, 1, 0) → (−1/√2, 1/√2, 0).
  for (int v = 0; v < 2; ++v) {
    SCOPED_TRACE(v);  // v = 1 takes half its weight from JOINTS_1/WEIGHTS_1
    EXPECT_NEAR(pos[v].x, 0.5f, kClosedForm);
    EXPECT_NEAR(pos[v].y, 0.5f, kClosedForm);
    EXPECT_NEAR(pos[v].z, 0.0f, kClosedForm);
    EXPECT_NEAR(nrm[v].x, -std::sqrt(0.5f), kClosedForm);
    EXPECT_NEAR(nrm[v].y, std::sqrt(0.5f), kClosedForm);
    EXPECT_NEAR(nrm[v].z, 0.0f, kClosedForm);
  }
  // The rest pose (no clip): both bones identity, the vertex stays put.
  ASSERT_TRUE(posePrimitive(a, 3, 0, nullptr, pos, nrm));
  EXPECT_EQ(pos[0], glm::vec3(1, 0, 0));
  EXPECT_EQ(nrm[0], glm::vec3(0, 1, 0));
}

TEST(Skinning, NonUniformJointScaleSkinsNormalsByTheInverseTranspose) {
  asset::CookedAsset a = twoBones();
  a.animations.clear();
  a.nodes[1].scale = {2, 1, 1};  // bone A stretches x; every weight on it
  a.meshes[0].primitives[0].weights = {{1, 0, 0, 0}, {1, 0, 0, 0}};
  a.meshes[0].primitives[0].weights1 = {{0, 0, 0, 0}, {0, 0, 0, 0}};
  a.meshes[0].primitives[0].normals = {glm::normalize(glm::vec3(1, 1, 0)), {0, 1, 0}};
  Pose pose;
  evaluatePose(a, -1, 0.0f, pose);
  std::vector<glm::vec3> pos, nrm;
  ASSERT_TRUE(posePrimitive(a, 3, 0, &pose, pos, nrm));
  EXPECT_EQ(pos[0], glm::vec3(2, 0, 0));
  // Scale (2, 1, 1): inverse transpose (1/2, 1, 1), n ∝ (0.5, 1, 0) → (1, 2, 0)/√5.
  EXPECT_NEAR(nrm[0].x, 1.0f / std::sqrt(5.0f), kClosedForm);
  EXPECT_NEAR(nrm[0].y, 2.0f / std::sqrt(5.0f), kClosedForm);
}

TEST(Skinning, MorphTargetsAddWeightedOffsets) {
  asset::Primitive p;
  p.positions = {{0, 0, 0}, {1, 0, 0}};
  p.normals = {{0, 0, 1}, {0, 0, 1}};
  p.targets.resize(2);
  p.targets[0].positions = {{0, 1, 0}, {0, 0, 0}};
  p.targets[1].positions = {{0, 0, 2}, {4, 0, 0}};
  const float w[2] = {0.5f, 0.25f};
  std::vector<glm::vec3> pos(2), nrm(2);
  ASSERT_TRUE((MorphJob{&p, w, pos, nrm}.run()));
  EXPECT_EQ(pos[0], glm::vec3(0, 0.5f, 0.5f));
  EXPECT_EQ(pos[1], glm::vec3(2, 0, 0));
  EXPECT_EQ(nrm[0], glm::vec3(0, 0, 1));  // targets without normals leave them
  std::vector<glm::vec3> wrong(1);
  EXPECT_FALSE((MorphJob{&p, w, wrong, nrm}.validate()));
}

TEST(Skinning, ValidateRejectsJointIndicesOutsideTheMatrices) {
  const asset::CookedAsset a = twoBones();
  const asset::Primitive& p = a.meshes[0].primitives[0];
  std::vector<glm::vec3> out(2), outN(2);
  const glm::mat4 one[1] = {glm::mat4(1.0f)};
  EXPECT_FALSE((SkinningJob{&p, one, p.positions, p.normals, out, outN}.validate()));  // joint 1 of 1 matrix
  const glm::mat4 two[2] = {glm::mat4(1.0f), glm::mat4(1.0f)};
  EXPECT_TRUE((SkinningJob{&p, two, p.positions, p.normals, out, outN}.validate()));
}

TEST(Pose, UnanimatedLocalsEqualTheStaticPathBitForBit) {
  const auto a = asset::loadOrCook(assets() / "CesiumMilkTruck/glTF/CesiumMilkTruck.gltf",
                                   std::filesystem::path(BOUNCE_TEST_OUT) / "anim-cook");
  Pose pose;
  evaluatePose(a, -1, 0.0f, pose);
  ASSERT_EQ(pose.local.size(), a.nodes.size());
  for (std::size_t n = 0; n < a.nodes.size(); ++n) {
    const glm::mat4 s = scene::nodeLocal(a.nodes[n]);
    EXPECT_EQ(std::memcmp(&s, &pose.local[n], sizeof s), 0) << "node " << n;
  }
}

TEST(Pose, RiggedSimpleRestPoseIsItsBindPose) {
  // The rig's rest pose is its bind pose: every joint matrix model(joint)·inverseBind(joint) is the
  // same rigid map (here the file's Z_UP root: the Armature and the skinned node's own transforms
  // are not part of it, as the spec says), so the skinned mesh is that map of the cooked vertices.
  // Within fp32 of the matrix chains (the file's matrices carry 1e-8-scale terms).
  constexpr float kChain = 2e-5f;  // metres, on a 9 m tall cylinder
  const auto a = asset::loadOrCook(assets() / "RiggedSimple/glTF/RiggedSimple.gltf",
                                   std::filesystem::path(BOUNCE_TEST_OUT) / "anim-cook");
  Pose pose;
  evaluatePose(a, -1, 0.0f, pose);
  const int meshNode = 2;
  ASSERT_TRUE(isSkinned(a, meshNode));
  const auto& joints = pose.joints[0];
  ASSERT_EQ(joints.size(), 2u);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(joints[1][c][r], joints[0][c][r], kChain) << c << "," << r;
  const glm::mat4 zUp = scene::nodeLocal(a.nodes[0]);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(joints[0][c][r], zUp[c][r], kChain) << c << "," << r;
  std::vector<glm::vec3> pos, nrm;
  ASSERT_TRUE(posePrimitive(a, meshNode, 0, &pose, pos, nrm));
  const auto& p = a.meshes[0].primitives[0];
  for (std::size_t v = 0; v < p.positions.size(); ++v) {
    const glm::vec3 expect = glm::vec3(zUp * glm::vec4(p.positions[v], 1.0f));
    EXPECT_NEAR(glm::distance(pos[v], expect), 0.0f, kChain) << "vertex " << v;
  }
  // And the clip bends it: some vertex moves by more than a centimetre one second in.
  Pose mid;
  evaluatePose(a, 0, 1.0f, mid);
  std::vector<glm::vec3> bent, bentN;
  posePrimitive(a, meshNode, 0, &mid, bent, bentN);
  float moved = 0.0f;
  for (std::size_t v = 0; v < pos.size(); ++v) moved = std::max(moved, glm::distance(pos[v], bent[v]));
  EXPECT_GT(moved, 0.01f);
}

TEST(Pose, BrainStemHoldsTogether) {
  // The symptom: BrainStem fell apart into scattered pieces. Skinned, its posed bounds stay
  // those of one figure: at every time within [1/2, 2] × the diagonal of its skinned rest pose (a
  // walking figure swings its limbs; a scattered one spans several times its height).
  constexpr float kMinRatio = 0.5f, kMaxRatio = 2.0f;
  const auto a = asset::loadOrCook(assets() / "BrainStem/glTF-Binary/BrainStem.glb",
                                   std::filesystem::path(BOUNCE_TEST_OUT) / "anim-cook", {false, {}});
  ASSERT_FALSE(a.animations.empty());
  auto diagonal = [&](int clip, float t) {
    Pose pose;
    evaluatePose(a, clip, t, pose);
    glm::vec3 lo(1e30f), hi(-1e30f);
    std::size_t skinned = 0;
    for (std::size_t n = 0; n < a.nodes.size(); ++n) {
      if (!isSkinned(a, int(n))) continue;
      std::vector<glm::vec3> pos, nrm;
      for (std::size_t pi = 0; pi < a.meshes[std::size_t(a.nodes[n].mesh)].primitives.size(); ++pi) {
        EXPECT_TRUE(posePrimitive(a, int(n), pi, &pose, pos, nrm));
        for (const auto& p : pos) {
          lo = glm::min(lo, p);
          hi = glm::max(hi, p);
        }
        ++skinned;
      }
    }
    EXPECT_GT(skinned, 10u);  // primitives
    return glm::distance(lo, hi);
  };
  const float rest = diagonal(-1, 0.0f);
  ASSERT_GT(rest, 0.0f);
  for (float t : {0.0f, 1.0f, 2.5f}) {
    const float d = diagonal(0, t);
    EXPECT_GE(d, kMinRatio * rest) << "t = " << t;
    EXPECT_LE(d, kMaxRatio * rest) << "t = " << t;
  }
}

}  // namespace
}  // namespace bounce::anim
