// Issue 12's bad input for skins and animations, each made from RiggedSimple at run time: one line
// "file: /json/pointer: what (expected …)", an InputError (exit 2), nothing cooked.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/asset/cook.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/log.hpp"

namespace bounce::asset {
namespace {

namespace fs = std::filesystem;

fs::path assets() {
  const char* env = std::getenv("BOUNCE_SHARED_DIR");
  return fs::path(env && *env ? env : BOUNCE_SHARED_DIR) / "assets";
}

// RiggedSimple.gltf + .bin in a fresh folder; accessors: 1 JOINTS_0 (u16), 4 WEIGHTS_0 (float),
// 5 key times, 6/7/8 translation/rotation/scale outputs, 9 inverse bind matrices.
struct Rig {
  fs::path dir;
  nlohmann::json doc;
  std::vector<std::uint8_t> bin;

  Rig() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::path(BOUNCE_TEST_OUT) / "anim-checks" / info->name();
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path src = assets() / "RiggedSimple/glTF";
    doc = nlohmann::json::parse(readFileText(src / "RiggedSimple.gltf"));
    bin = readFileBytes(src / "RiggedSimple0.bin");
  }
  std::size_t offset(int accessor, std::size_t element, std::size_t elementBytes) const {
    const auto& a = doc["accessors"][accessor];
    const auto& bv = doc["bufferViews"][a["bufferView"].get<int>()];
    return bv.value("byteOffset", std::size_t(0)) + a.value("byteOffset", std::size_t(0)) +
           element * bv.value("byteStride", elementBytes);
  }
  void setFloat(int accessor, std::size_t element, std::size_t component, float v, std::size_t elementBytes) {
    std::memcpy(bin.data() + offset(accessor, element, elementBytes) + 4 * component, &v, 4);
  }
  std::string cook() {
    writeFileAtomic(dir / "RiggedSimple0.bin", bin);
    writeFileAtomic(dir / "Rig.gltf", doc.dump());
    try {
      (void)asset::cook(dir / "Rig.gltf", {false, {}});
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
  std::string file() const { return "Rig.gltf"; }  // the cooker names the file without its folder
};

TEST(SkinChecks, TheUnmodifiedRigCooks) { EXPECT_EQ(Rig().cook(), "(no error)"); }

TEST(SkinChecks, JointIndexBeyondTheSkin) {
  Rig r;
  r.doc["skins"][0]["joints"] = {3};  // vertices still use joint 1
  EXPECT_EQ(r.cook(), r.file() + ": /meshes/0/primitives/0/attributes/JOINTS_0: vertex 2 uses joint 1 of skin 0 (node 2) "
                                 "(expected a joint index < 1)");
}

TEST(SkinChecks, NegativeNaNAndAllZeroWeights) {
  {
    Rig r;
    r.setFloat(4, 7, 0, -0.25f, 16);
    EXPECT_EQ(r.cook(), r.file() + ": /meshes/0/primitives/0/attributes/WEIGHTS_0: vertex 7 has a negative weight -0.250000 "
                                   "(expected weights >= 0)");
  }
  {
    Rig r;
    r.setFloat(4, 3, 1, std::nanf(""), 16);
    EXPECT_EQ(r.cook(), r.file() + ": /meshes/0/primitives/0/attributes/WEIGHTS_0: vertex 3 has a NaN/Inf weight "
                                   "(expected finite weights)");
  }
  {
    Rig r;
    for (int k = 0; k < 4; ++k) r.setFloat(4, 5, std::size_t(k), 0.0f, 16);
    EXPECT_EQ(r.cook(), r.file() + ": /meshes/0/primitives/0/attributes/WEIGHTS_0: vertex 5 has all weights zero "
                                   "(expected weights summing to 1)");
  }
}

TEST(SkinChecks, WeightsNotSummingToOneAreRenormalisedWithOneWarning) {
  Rig r;
  for (std::size_t v : {0, 1, 2}) {
    r.setFloat(4, v, 0, 0.5f, 16);
    for (std::size_t k = 1; k < 4; ++k) r.setFloat(4, v, k, 0.0f, 16);
  }
  writeFileAtomic(r.dir / "RiggedSimple0.bin", r.bin);
  writeFileAtomic(r.dir / "Rig.gltf", r.doc.dump());
  log::resetWarningCount();
  const CookedAsset a = cook(r.dir / "Rig.gltf", {false, {}});
  EXPECT_EQ(log::warningCount(), 1u);  // once per primitive, however many vertices
  for (std::size_t v : {0, 1, 2}) EXPECT_EQ(a.meshes[0].primitives[0].weights[v], glm::vec4(1, 0, 0, 0));
}

TEST(SkinChecks, InverseBindMatricesMustBeFiniteAndInvertible) {
  {
    Rig r;
    for (std::size_t k = 0; k < 16; ++k) r.setFloat(9, 1, k, 0.0f, 64);
    EXPECT_EQ(r.cook(), r.file() + ": /skins/0/inverseBindMatrices/1: matrix is not invertible (determinant 0.000000) "
                                   "(expected an invertible finite matrix)");
  }
  {
    Rig r;
    r.setFloat(9, 0, 5, std::nanf(""), 64);
    EXPECT_EQ(r.cook(), r.file() + ": /skins/0/inverseBindMatrices/0: matrix has NaN/Inf entries "
                                   "(expected an invertible finite matrix)");
  }
}

TEST(SkinChecks, SkeletonMustBeOneTree) {
  Rig r;
  r.doc["nodes"].push_back({{"name", "stray"}});  // node 5, a root outside the default scene
  r.doc["skins"][0]["joints"] = {3, 5};
  EXPECT_EQ(r.cook(), r.file() + ": /skins/0/joints/1: joint node 5 is outside the default scene's tree (skeleton is not "
                                 "a tree) (expected every joint a descendant of a scene root)");
  Rig s;
  s.doc["skins"][0]["skeleton"] = 4;  // joint 3 is Bone.001's parent, not under it
  EXPECT_EQ(s.cook(), s.file() + ": /skins/0/joints/0: joint node 3 is not a descendant of skeleton node 4 "
                                 "(expected every joint under the skin's skeleton root)");
}

TEST(SkinChecks, JointLimit) {
  Rig r;
  nlohmann::json joints = nlohmann::json::array();
  for (int i = 0; i < 257; ++i) {
    r.doc["nodes"][4]["children"].push_back(5 + i);
    r.doc["nodes"].push_back({{"name", "j" + std::to_string(i)}});
    joints.push_back(5 + i);
  }
  r.doc["skins"][0]["joints"] = joints;
  r.doc["skins"][0].erase("inverseBindMatrices");
  EXPECT_EQ(r.cook(), r.file() + ": /skins/0/joints: 257 joints (expected at most 256, the GPU skinning limit per skin)");
}

TEST(SkinChecks, SamplerTimesAndCounts) {
  {
    Rig r;
    float t0;
    std::memcpy(&t0, r.bin.data() + r.offset(5, 0, 4), 4);
    r.setFloat(5, 1, 0, t0, 4);
    EXPECT_EQ(r.cook(), r.file() + ": /animations/0/samplers/0/input: key times not strictly increasing at key 1 "
                                   "(expected increasing times)");
  }
  {
    Rig r;
    r.doc["accessors"][6]["count"] = 49;  // 147 values for 50 keys
    EXPECT_EQ(r.cook(), r.file() + ": /animations/0/samplers/0/output: 147 values do not divide into 50 keys "
                                   "(expected a whole number of values per key)");
  }
  {
    Rig r;
    r.doc["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE";  // needs 3 × 50 keys
    EXPECT_EQ(r.cook(), r.file() + ": /animations/0/channels/0: sampler has 1 values per key for path translation (expected 3)");
  }
}

TEST(SkinChecks, ChannelTargets) {
  {
    Rig r;
    r.doc["animations"][0]["channels"][0]["target"]["node"] = 99;
    EXPECT_EQ(r.cook(), r.file() + ": /animations/0/channels/0/target/node: node index 99 out of range (expected 0 ≤ index < 5)");
  }
  {
    Rig r;
    r.doc["animations"][0]["channels"][0]["target"] = {{"node", 2}, {"path", "weights"}};
    EXPECT_EQ(r.cook(), r.file() + ": /animations/0/channels/0/target: a weights channel on node 2, which has no morph "
                                   "targets (expected a node whose mesh has morph targets)");
  }
}

}  // namespace
}  // namespace bounce::asset
