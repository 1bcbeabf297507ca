// extras.bounce_vlm on glTF nodes (README "Virtual Light Meshes"): exact parse, one-line errors
// for every bad value, and the cooked round trip.
#include "engine/asset/cooked_format.hpp"
#include "test_util.hpp"

namespace bounce::asset::test {
namespace {

// Box.gltf with `extras` on node `node` (1 has the mesh, 0 is its mesh-less parent), written as Vlm.gltf.
fs::path boxWith(const nlohmann::json& extras, int node = 1) {
  const fs::path dir = scratch();
  copyFolder(assets() / "Box/glTF", dir);
  auto doc = readJson(dir / "Box.gltf");
  doc["nodes"][node]["extras"]["bounce_vlm"] = extras;
  writeJson(dir / "Vlm.gltf", doc);
  return dir / "Vlm.gltf";
}

TEST(VlmExtras, ParsedExactlyAndKeptByTheCookedFormat) {
  const fs::path file = boxWith({{"tag", 3}, {"color", {1, 0.5, 0.25}}, {"intensity", 2}, {"reflectance", {0.5, 0.25, 0}}});
  const CookedAsset a = cook(file, geometryOnly());
  const NodeVlm& v = a.nodes[1].vlm;
  EXPECT_TRUE(v.present);
  EXPECT_EQ(v.tag, 3u);
  EXPECT_TRUE(v.hasColor && v.hasIntensity && v.hasReflectance);
  EXPECT_EQ(v.color, glm::vec3(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(v.intensity, 2.0f);
  EXPECT_EQ(v.reflectance, glm::vec3(0.5f, 0.25f, 0.0f));
  EXPECT_FALSE(a.nodes[0].vlm.present);
  EXPECT_EQ(parseCooked(serializeCooked(a), "vlm.bcook"), a);

  const CookedAsset onlyTag = cook(boxWith({{"tag", 16777216}}), geometryOnly());
  EXPECT_EQ(onlyTag.nodes[1].vlm, (NodeVlm{true, 16777216u, false, glm::vec3(1.0f), false, 1.0f, false, glm::vec3(1.0f)}));
}

TEST(VlmExtras, BadValuesAreOneLineErrors) {
  const std::string at = "Vlm.gltf: /nodes/1/extras/bounce_vlm";
  auto error = [&](const nlohmann::json& extras, int node = 1) {
    return expectInputError([&] { (void)cook(boxWith(extras, node), geometryOnly()); }, {});
  };
  EXPECT_EQ(error(7), at + ": not an object (expected {\"tag\": N, \"color\": [r, g, b], \"intensity\": x, \"reflectance\": [r, g, b]})");
  // (tinygltf drops an empty extras object, so "bounce_vlm": {} reads as no extras at all.)
  EXPECT_EQ(error({{"intensity", 1}}), at + ": missing required key \"tag\" (expected an integer id >= 1)");
  EXPECT_EQ(error({{"tag", 0}}), at + "/tag: out of range (expected an integer id in [1, 16777216])");
  EXPECT_EQ(error({{"tag", 1.5}}), at + "/tag: not an integer (expected an integer id in [1, 16777216])");
  EXPECT_EQ(error({{"tag", "1"}}), at + "/tag: not a number (expected an integer id in [1, 16777216])");
  EXPECT_EQ(error({{"tag", 1}, {"colour", {1, 1, 1}}}), at + "/colour: unknown key \"colour\" (expected one of: tag, color, intensity, reflectance)");
  EXPECT_EQ(error({{"tag", 1}, {"color", {1, 1}}}), at + "/color: not an array of 3 numbers (expected 3 numbers >= 0)");
  EXPECT_EQ(error({{"tag", 1}, {"color", {1, -1, 1}}}), at + "/color/1: out of range (expected 3 numbers >= 0)");
  EXPECT_EQ(error({{"tag", 1}, {"intensity", -2}}), at + "/intensity: out of range (expected a number in [0, 1e6])");
  EXPECT_EQ(error({{"tag", 1}, {"reflectance", {0.5, 1.5, 0}}}), at + "/reflectance/1: out of range (expected 3 numbers in [0, 1])");
  EXPECT_EQ(error({{"tag", 1}}, 0), "Vlm.gltf: /nodes/0/extras/bounce_vlm: a VLM on a node without a mesh "
                                    "(expected bounce_vlm on a node with a mesh)");
}

}  // namespace
}  // namespace bounce::asset::test
