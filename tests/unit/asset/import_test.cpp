// Known values from real sample assets (Box, Duck, BoxTextured) and a generated
// KHR_lights_punctual file.
#include "engine/core/log.hpp"
#include "tests/unit/asset/test_util.hpp"

#include <cmath>

namespace bounce::asset::test {
namespace {

// Box.gltf positions are exact small binary fractions (±0.5); float reads them exactly.
constexpr float kExact = 0.0f;
// Unit-length check for normals read from a file or generated: float rounding of a normalise.
constexpr float kUnitTolerance = 1e-5f;

TEST(Import, BoxHasTwelveTrianglesAndKnownBounds) {
  const CookedAsset a = cook(assets() / "Box/glTF/Box.gltf", geometryOnly());
  EXPECT_EQ(a.triangleCount(), 12u);
  ASSERT_EQ(a.meshes.size(), 1u);
  ASSERT_EQ(a.meshes[0].primitives.size(), 1u);
  const Primitive& p = a.meshes[0].primitives[0];
  EXPECT_EQ(p.positions.size(), 24u);
  EXPECT_EQ(p.normals.size(), 24u);
  EXPECT_TRUE(p.uv0.empty());
  EXPECT_EQ(p.material, 0);
  EXPECT_NEAR(a.meshes[0].bounds.min.x, -0.5f, kExact);
  EXPECT_NEAR(a.meshes[0].bounds.min.y, -0.5f, kExact);
  EXPECT_NEAR(a.meshes[0].bounds.min.z, -0.5f, kExact);
  EXPECT_NEAR(a.meshes[0].bounds.max.x, 0.5f, kExact);
  EXPECT_NEAR(a.meshes[0].bounds.max.y, 0.5f, kExact);
  EXPECT_NEAR(a.meshes[0].bounds.max.z, 0.5f, kExact);
  for (const auto& n : p.normals) EXPECT_NEAR(glm::length(n), 1.0f, kUnitTolerance);
  // Hierarchy: root 0 (Z-up to Y-up matrix) → child 1 holding the mesh.
  ASSERT_EQ(a.nodes.size(), 2u);
  EXPECT_EQ(a.rootNodes, std::vector<std::int32_t>{0});
  EXPECT_EQ(a.nodes[0].children, std::vector<std::int32_t>{1});
  EXPECT_TRUE(a.nodes[0].hasMatrix);
  EXPECT_EQ(a.nodes[0].matrix[1][2], -1.0f);  // column 1, row 2 (glTF column-major)
  EXPECT_EQ(a.nodes[0].matrix[2][1], 1.0f);
  EXPECT_EQ(a.nodes[1].mesh, 0);
  ASSERT_EQ(a.materials.size(), 1u);
  EXPECT_EQ(a.materials[0].name, "Red");
  EXPECT_FLOAT_EQ(a.materials[0].baseColorFactor.r, 0.8f);
  EXPECT_EQ(a.materials[0].alphaMode, AlphaMode::Opaque);
}

TEST(Import, GeneratedNormalsMatchBoxFaceNormals) {
  // Strip the NORMAL attribute: area-weighted normals of the box (vertices split per face) must
  // equal the face normals the file stored.
  const fs::path dir = scratch();
  copyFolder(assets() / "Box/glTF", dir);
  auto doc = readJson(dir / "Box.gltf");
  doc["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
  writeJson(dir / "NoNormals.gltf", doc);
  const CookedAsset original = cook(assets() / "Box/glTF/Box.gltf", geometryOnly());
  const CookedAsset generated = cook(dir / "NoNormals.gltf", geometryOnly());
  const auto& a = original.meshes[0].primitives[0].normals;
  const auto& b = generated.meshes[0].primitives[0].normals;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(glm::dot(a[i], b[i]), 1.0f, kUnitTolerance) << "vertex " << i;
}

TEST(Import, DuckMaterialHasDecodedSrgbBaseColorTexture) {
  const CookedAsset a = cook(assets() / "Duck/glTF-Binary/Duck.glb");
  EXPECT_EQ(a.triangleCount(), 4212u);
  ASSERT_EQ(a.materials.size(), 1u);
  const TextureRef& t = a.materials[0].baseColorTexture;
  ASSERT_EQ(t.texture, 0);
  EXPECT_EQ(t.uvSet, 0);
  ASSERT_EQ(a.textures.size(), 1u);
  const Texture& tex = a.textures[0];
  EXPECT_TRUE(tex.srgb);
  EXPECT_EQ(tex.width, 512u);
  EXPECT_EQ(tex.height, 512u);
  EXPECT_EQ(tex.pixels.size(), 512u * 512u * 4u);
  EXPECT_EQ(a.meshes[0].primitives[0].uv0.size(), a.meshes[0].primitives[0].positions.size());
  // The duck is yellow: the mean red and green exceed the mean blue.
  double r = 0, g = 0, b = 0;
  for (std::size_t i = 0; i < tex.pixels.size(); i += 4) r += tex.pixels[i], g += tex.pixels[i + 1], b += tex.pixels[i + 2];
  EXPECT_GT(r, b);
  EXPECT_GT(g, b);
}

TEST(Import, EmbeddedBinaryAndSeparateVariantsAgree) {
  const CookedAsset sep = cook(assets() / "Duck/glTF/Duck.gltf", geometryOnly());
  const CookedAsset glb = cook(assets() / "Duck/glTF-Binary/Duck.glb", geometryOnly());
  const CookedAsset emb = cook(assets() / "Duck/glTF-Embedded/Duck.gltf", geometryOnly());
  EXPECT_EQ(sep.meshes, glb.meshes);
  EXPECT_EQ(sep.meshes, emb.meshes);
  EXPECT_EQ(sep.nodes, glb.nodes);
  EXPECT_EQ(sep.cameras.size(), 1u);
}

TEST(Import, LightsPunctualFromGeneratedFile) {
  const fs::path dir = scratch();
  copyFolder(assets() / "Box/glTF", dir);
  auto doc = readJson(dir / "Box.gltf");
  doc["extensionsUsed"] = {"KHR_lights_punctual"};
  doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 20.0}, {"range", 5.0}, {"name", "bulb"}},
      {{"type", "spot"}, {"intensity", 3.0}, {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}},
      {{"type", "directional"}}};
  doc["nodes"].push_back({{"name", "lamp"}, {"translation", {0, 2, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  doc["scenes"][0]["nodes"].push_back(2);
  writeJson(dir / "Lights.gltf", doc);
  const CookedAsset a = cook(dir / "Lights.gltf", geometryOnly());
  ASSERT_EQ(a.lights.size(), 3u);
  EXPECT_EQ(a.lights[0].type, LightType::Point);
  EXPECT_EQ(a.lights[0].name, "bulb");
  EXPECT_EQ(a.lights[0].color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(a.lights[0].intensity, 20.0f);
  EXPECT_EQ(a.lights[0].range, 5.0f);
  EXPECT_EQ(a.lights[1].type, LightType::Spot);
  EXPECT_EQ(a.lights[1].innerConeAngle, 0.25f);
  EXPECT_EQ(a.lights[1].outerConeAngle, 0.5f);
  EXPECT_EQ(a.lights[2].type, LightType::Directional);
  EXPECT_EQ(a.lights[2].color, glm::vec3(1.0f));
  ASSERT_EQ(a.nodes.size(), 3u);
  EXPECT_EQ(a.nodes[2].light, 1);
  EXPECT_EQ(a.nodes[2].translation, glm::vec3(0, 2, 0));
  EXPECT_EQ(a.rootNodes, (std::vector<std::int32_t>{0, 2}));
}

TEST(Import, StripsAndFansBecomeTriangleLists) {
  // Conformance Mesh_PrimitiveMode: 00-06 are points, lines, line loop, line strip, triangles,
  // triangle strip, triangle fan of the same 2-triangle quad.
  const fs::path dir = assets() / "conformance/Positive/Mesh_PrimitiveMode";
  const std::size_t before = log::warningCount();
  const CookedAsset points = cook(dir / "Mesh_PrimitiveMode_00.gltf", geometryOnly());
  EXPECT_EQ(points.triangleCount(), 0u);
  EXPECT_EQ(log::warningCount(), before + 1);  // "skipped 1 point/line primitives"
  for (const char* f : {"Mesh_PrimitiveMode_04.gltf", "Mesh_PrimitiveMode_05.gltf", "Mesh_PrimitiveMode_06.gltf"}) {
    const CookedAsset a = cook(dir / f, geometryOnly());
    EXPECT_EQ(a.triangleCount(), 2u) << f;
    // Same winding as the plain triangle list: every generated normal faces +Z.
    for (const auto& n : a.meshes[0].primitives[0].normals) EXPECT_GT(n.z, 0.99f) << f;
  }
}

TEST(Import, SkinsAndAnimationsAreKept) {
  const CookedAsset a = cook(assets() / "RiggedSimple/glTF/RiggedSimple.gltf", geometryOnly());
  ASSERT_EQ(a.skins.size(), 1u);
  EXPECT_EQ(a.skins[0].joints.size(), a.skins[0].inverseBindMatrices.size());
  EXPECT_FALSE(a.skins[0].joints.empty());
  ASSERT_EQ(a.animations.size(), 1u);
  EXPECT_FALSE(a.animations[0].channels.empty());
  const Primitive& p = a.meshes[0].primitives[0];
  EXPECT_EQ(p.joints.size(), p.positions.size());
  EXPECT_EQ(p.weights.size(), p.positions.size());
  for (const auto& w : p.weights) EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-3f);  // glTF: weights sum to 1 (stored as float)
}

}  // namespace
}  // namespace bounce::asset::test
