// bounce export: the GLB container and JSON as written (what other tools read), every light type
// and lights inside assets, sheared instances, emissive above 1, and the error paths.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>

#include "engine/core/error.hpp"
#include "engine/scene_export/export.hpp"
#include "tests/unit/export/test_util.hpp"

namespace bounce::scene_export::test {
namespace {

// See export_test.cpp: float rounding of the same matrix products, a few ulps.
constexpr float kBoundsRel = 1e-5f;
constexpr float kPositionTol = 1e-6f;
constexpr float kDirectionTol = 1e-6f;
// Columns of a written node matrix must be orthogonal (decomposable into TRS, glTF 2.0 §3.5.3);
// float products of rotations and scales leave ~1e-7 of cosine.
constexpr double kOrthogonalCos = 1e-5;

constexpr float kDeg = float(M_PI / 180.0);

std::uint32_t u32(const std::vector<std::uint8_t>& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);  // GLB is little-endian, as this machine
  return v;
}

struct Glb {
  nlohmann::json doc;
  std::vector<std::uint8_t> bin;
};

// Splits a .glb per the glTF 2.0 binary container (§4.4), asserting its framing.
Glb readGlb(const fs::path& path) {
  const auto bytes = readFileBytes(path);
  Glb g;
  EXPECT_GE(bytes.size(), 28u);
  if (bytes.size() < 28) return g;
  EXPECT_EQ(std::memcmp(bytes.data(), "glTF", 4), 0);
  EXPECT_EQ(u32(bytes, 4), 2u);
  EXPECT_EQ(u32(bytes, 8), bytes.size());
  const std::uint32_t jsonLength = u32(bytes, 12);
  EXPECT_EQ(u32(bytes, 16), 0x4E4F534Au);  // "JSON"
  EXPECT_EQ(jsonLength % 4, 0u);
  g.doc = nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + jsonLength);
  const std::size_t binAt = 20 + jsonLength;
  if (binAt < bytes.size()) {
    const std::uint32_t binLength = u32(bytes, binAt);
    EXPECT_EQ(u32(bytes, binAt + 4), 0x004E4942u);  // "BIN\0"
    EXPECT_EQ(binLength % 4, 0u);
    EXPECT_EQ(binAt + 8 + binLength, bytes.size());
    g.bin.assign(bytes.begin() + std::ptrdiff_t(binAt + 8), bytes.end());
  }
  return g;
}

fs::path writeLevel(const std::string& name, const nlohmann::json& level) {
  const fs::path p = outDir() / name;
  writeFileAtomic(p, level.dump(1));
  return p;
}

std::string boxGlb() { return contentAsset("Box/glTF-Binary/Box.glb").string(); }

// A glTF with no mesh, one spot light on a node at (0, 0.1, 0) pointing down (−90° about X).
fs::path writeLampAsset() {
  const nlohmann::json lamp = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_lights_punctual"}},
      {"extensions",
       {{"KHR_lights_punctual",
         {{"lights",
           {{{"name", "bulb"}, {"type", "spot"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 3.0}, {"range", 2.0},
             {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}}}}}}}},
      {"nodes",
       {{{"name", "bulb-node"},
         {"translation", {0.0, 0.1, 0.0}},
         {"rotation", {-std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)}},
         {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  const fs::path p = outDir() / "lamp.gltf";
  writeFileAtomic(p, lamp.dump(1));
  return p;
}

// Every light type, a light inside an asset, an emissive override above 1, and a sheared instance.
fs::path writeLightsLevel() {
  writeLampAsset();
  const nlohmann::json level = {
      {"bounce_level", 1},
      {"effects", {"direct"}},
      {"entities",
       {{{"id", "sun"},
         {"transform", {{"rotation_euler_deg", {-90, 0, 0}}}},
         {"light", {{"type", "directional"}, {"color", {1, 1, 1}}, {"intensity", 3}}}},
        {{"id", "spot"},
         {"transform", {{"translation", {0, 1, 0}}}},
         {"light",
          {{"type", "spot"}, {"color", {0.5, 1, 0.25}}, {"intensity", 2}, {"range", 5}, {"inner_cone_deg", 10},
           {"outer_cone_deg", 30}}}},
        {{"id", "hot"},
         {"transform", {{"translation", {0.1, 0.2, 0.3}}}},
         {"light", {{"type", "point"}, {"color", {2, 1, 0.5}}, {"intensity", 1.5}, {"shadows", false}}}},
        {{"id", "lamp"},
         {"transform", {{"translation", {0.3, 0.2, 0}}, {"rotation_euler_deg", {0, 90, 0}}, {"scale", {2, 2, 2}}}},
         {"mesh", {{"asset", "lamp.gltf"}}}},
        {{"id", "glow"},
         {"transform", {{"translation", {0, 0.5, -0.5}}, {"scale", {0.1, 0.1, 0.1}}}},
         {"mesh", {{"asset", boxGlb()}}},
         {"material", {{"emissive", {4, 2, 0}}}}},
        {{"id", "squash"}, {"transform", {{"scale", {1, 3, 1}}}}},
        {{"id", "sheared"},
         {"parent", "squash"},
         {"transform", {{"rotation_euler_deg", {0, 0, 45}}, {"scale", {0.1, 0.1, 0.1}}}},
         {"mesh", {{"asset", boxGlb()}}}}}}};
  return writeLevel("lights-level.json", level);
}

TEST(ExportGlb, ContainerAndJsonAreWhatOtherToolsExpect) {
  ExportOptions o;
  o.cookCache = cookCache();
  const fs::path out = outDir() / "structure-cornell5.glb";
  const ExportStats stats = exportLevel(scene::loadLevel(level("cornell-5.json")), out, o);
  const Glb g = readGlb(out);
  const auto& doc = g.doc;
  EXPECT_EQ(stats.bytes, fs::file_size(out));
  EXPECT_EQ(doc["asset"]["version"], "2.0");
  // One buffer, the GLB's BIN chunk: no external or data: URIs anywhere.
  ASSERT_EQ(doc["buffers"].size(), 1u);
  EXPECT_FALSE(doc["buffers"][0].contains("uri"));
  EXPECT_LE(doc["buffers"][0]["byteLength"].get<std::size_t>(), g.bin.size());
  EXPECT_GT(doc["buffers"][0]["byteLength"].get<std::size_t>() + 4, g.bin.size());
  // Images: PNG inside the buffer.
  ASSERT_EQ(doc["images"].size(), stats.textures);
  for (const auto& image : doc["images"]) {
    EXPECT_FALSE(image.contains("uri"));
    EXPECT_EQ(image["mimeType"], "image/png");
    const auto& view = doc["bufferViews"][image["bufferView"].get<std::size_t>()];
    const std::size_t at = view.value("byteOffset", std::size_t(0));
    ASSERT_LE(at + 8, g.bin.size());
    const std::uint8_t png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    EXPECT_EQ(std::memcmp(g.bin.data() + at, png, 8), 0);
  }
  // Materials: diffuse (metallic 0, roughness 1 — the default, so absent or 1).
  ASSERT_EQ(doc["materials"].size(), stats.materials);
  for (const auto& m : doc["materials"]) {
    EXPECT_EQ(m["pbrMetallicRoughness"]["metallicFactor"].get<double>(), 0.0);
    EXPECT_EQ(m["pbrMetallicRoughness"].value("roughnessFactor", 1.0), 1.0);
  }
  // Every accessor 4-byte aligned in the buffer; POSITION accessors carry min and max.
  for (const auto& mesh : doc["meshes"])
    for (const auto& prim : mesh["primitives"]) {
      const auto& pos = doc["accessors"][prim["attributes"]["POSITION"].get<std::size_t>()];
      EXPECT_EQ(pos["min"].size(), 3u);
      EXPECT_EQ(pos["max"].size(), 3u);
      EXPECT_EQ(doc["accessors"][prim["indices"].get<std::size_t>()]["componentType"], 5125);  // uint32
    }
  for (const auto& view : doc["bufferViews"]) EXPECT_EQ(view.value("byteOffset", std::size_t(0)) % 4, 0u);
  // Node matrices decompose into TRS: orthogonal columns, last row (0, 0, 0, 1).
  for (const auto& node : doc["nodes"]) {
    if (!node.contains("matrix")) continue;
    const auto& m = node["matrix"];
    ASSERT_EQ(m.size(), 16u);
    EXPECT_EQ(m[3].get<double>(), 0.0);
    EXPECT_EQ(m[7].get<double>(), 0.0);
    EXPECT_EQ(m[11].get<double>(), 0.0);
    EXPECT_EQ(m[15].get<double>(), 1.0);
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) {
        double dot = 0, li = 0, lj = 0;
        for (int k = 0; k < 3; ++k) {
          dot += m[4 * i + k].get<double>() * m[4 * j + k].get<double>();
          li += m[4 * i + k].get<double>() * m[4 * i + k].get<double>();
          lj += m[4 * j + k].get<double>() * m[4 * j + k].get<double>();
        }
        EXPECT_LE(std::abs(dot), kOrthogonalCos * std::sqrt(li * lj)) << node["name"];
      }
  }
  // One root per entity, named by its id, in level order; dynamic ones marked.
  const auto lvl = scene::loadLevel(level("cornell-5.json"));
  const auto& roots = doc["scenes"][doc["scene"].get<std::size_t>()]["nodes"];
  ASSERT_EQ(roots.size(), lvl.entities.size());
  for (std::size_t i = 0; i < roots.size(); ++i) {
    const auto& node = doc["nodes"][roots[i].get<std::size_t>()];
    EXPECT_EQ(node["name"], lvl.entities[i].id);
    EXPECT_FALSE(node.contains("matrix"));
    EXPECT_EQ(node.contains("extras") && node["extras"].value("dynamic", false), lvl.entities[i].dynamic);
  }
  EXPECT_NE(std::find(doc["extensionsUsed"].begin(), doc["extensionsUsed"].end(), "KHR_lights_punctual"),
            doc["extensionsUsed"].end());
}

TEST(ExportGlb, EveryLightTypeAndAssetLightsRoundTrip) {
  ExportOptions o;
  o.cookCache = cookCache();
  const fs::path out = outDir() / "lights.glb";
  exportLevel(scene::loadLevel(writeLightsLevel()), out, o);
  const asset::CookedAsset back = asset::cook(out);
  ASSERT_EQ(back.lights.size(), 4u);
  const auto nodes = placedNodes(back);
  auto lightAt = [&](const std::string& node) -> std::pair<const asset::Light*, const Placed*> {
    const Placed* p = nullptr;
    for (const auto& n : nodes)
      if (n.name == node) p = &n;
    if (!p || back.nodes[std::size_t(p->node)].light < 0) return {nullptr, nullptr};
    return {&back.lights[std::size_t(back.nodes[std::size_t(p->node)].light)], p};
  };
  auto direction = [](const Placed* p) { return -glm::normalize(glm::vec3(p->world[2])); };
  auto near = [](glm::vec3 a, glm::vec3 b, float tol) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tol) << "component " << k;
  };

  {  // directional: irradiance → lux, identity; shines down its −Z = world −Y after −90° about X.
    auto [L, p] = lightAt("sun/light");
    ASSERT_NE(L, nullptr);
    EXPECT_EQ(L->type, asset::LightType::Directional);
    EXPECT_FLOAT_EQ(L->intensity, 3.0f);
    near(direction(p), {0, -1, 0}, kDirectionTol);
  }
  {  // spot: cone angles in radians, range kept.
    auto [L, p] = lightAt("spot/light");
    ASSERT_NE(L, nullptr);
    EXPECT_EQ(L->type, asset::LightType::Spot);
    EXPECT_FLOAT_EQ(L->intensity, 2.0f);
    near(L->color, {0.5f, 1.0f, 0.25f}, 0.0f);
    EXPECT_FLOAT_EQ(L->range, 5.0f);
    EXPECT_FLOAT_EQ(L->innerConeAngle, 10.0f * kDeg);
    EXPECT_FLOAT_EQ(L->outerConeAngle, 30.0f * kDeg);
    near(glm::vec3(p->world[3]), {0, 1, 0}, kPositionTol);
    near(direction(p), {0, 0, -1}, kDirectionTol);
  }
  {  // point with colour above 1: colour / 2, intensity × 2 — the same colour × intensity.
    auto [L, p] = lightAt("hot/light");
    ASSERT_NE(L, nullptr);
    EXPECT_EQ(L->type, asset::LightType::Point);
    near(L->color, {1.0f, 0.5f, 0.25f}, 0.0f);
    EXPECT_FLOAT_EQ(L->intensity, 3.0f);
    EXPECT_EQ(L->range, 0.0f);
    near(glm::vec3(p->world[3]), {0.1f, 0.2f, 0.3f}, kPositionTol);
  }
  {  // the asset's spot, placed by the entity (scale 2 moves it, the rigid node drops the scale).
    auto [L, p] = lightAt("lamp/bulb-node");
    ASSERT_NE(L, nullptr);
    EXPECT_EQ(L->type, asset::LightType::Spot);
    EXPECT_FLOAT_EQ(L->intensity, 3.0f);
    near(L->color, {1.0f, 0.5f, 0.25f}, 0.0f);
    EXPECT_FLOAT_EQ(L->range, 2.0f);
    EXPECT_FLOAT_EQ(L->innerConeAngle, 0.2f);
    EXPECT_FLOAT_EQ(L->outerConeAngle, 0.5f);
    near(glm::vec3(p->world[3]), {0.3f, 0.2f + 2.0f * 0.1f, 0.0f}, kPositionTol);
    near(direction(p), {0, -1, 0}, kDirectionTol);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(glm::length(glm::vec3(p->world[k])), 1.0f, kDirectionTol);
  }
  // Shadows have no glTF equivalent: kept as light extras for tools that want them.
  const Glb g = readGlb(out);
  std::size_t unshadowed = 0;
  for (const auto& l : g.doc["extensions"]["KHR_lights_punctual"]["lights"])
    unshadowed += l["extras"]["shadows"] == false;
  EXPECT_EQ(unshadowed, 1u);
}

TEST(ExportGlb, EmissiveAboveOneUsesEmissiveStrength) {
  ExportOptions o;
  o.cookCache = cookCache();
  const fs::path out = outDir() / "emissive.glb";
  exportLevel(scene::loadLevel(writeLightsLevel()), out, o);
  const Glb g = readGlb(out);
  std::size_t found = 0;
  for (const auto& m : g.doc["materials"]) {
    if (!m.contains("extensions")) continue;
    ++found;
    EXPECT_EQ(m["emissiveFactor"], nlohmann::json({1.0, 0.5, 0.0}));
    EXPECT_EQ(m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"].get<double>(), 4.0);
  }
  EXPECT_EQ(found, 1u);
  EXPECT_NE(std::find(g.doc["extensionsUsed"].begin(), g.doc["extensionsUsed"].end(), "KHR_materials_emissive_strength"),
            g.doc["extensionsUsed"].end());
}

TEST(ExportGlb, ShearedInstanceIsWrittenInWorldSpace) {
  ExportOptions o;
  o.cookCache = cookCache();
  const fs::path out = outDir() / "sheared.glb";
  const auto lvl = scene::loadLevel(writeLightsLevel());
  exportLevel(lvl, out, o);
  const asset::CookedAsset back = asset::cook(out);
  const Expected want = expectedInstances(lvl, 0.0);
  // squash scale (1, 3, 1) above a 45° roll: the world matrix shears, so no TRS node can hold it.
  const Imported got = importedInstances(back, "sheared");
  EXPECT_EQ(got.instances, 1u);
  const Box& box = want.entityBounds.at("sheared");
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(got.bounds.min[k], box.min[k], kBoundsRel * box.diagonal());
    EXPECT_NEAR(got.bounds.max[k], box.max[k], kBoundsRel * box.diagonal());
  }
  for (const auto& p : placedNodes(back))
    if (p.root == "sheared" && back.nodes[std::size_t(p.node)].mesh >= 0) {
      EXPECT_EQ(p.world, glm::mat4(1.0f));
    }
  EXPECT_EQ(importedInstances(back).triangles, want.triangles);
}

TEST(ExportGlb, UnwritableOutputIsAnInternalErrorNamingThePath) {
  ExportOptions o;
  o.cookCache = cookCache();
  const fs::path blocker = outDir() / "not-a-folder";
  writeFileAtomic(blocker, std::string("a file where a folder should be"));
  const fs::path out = blocker / "level.glb";
  try {
    exportLevel(scene::loadLevel(level("cornell-1.json")), out, o);
    ADD_FAILURE() << "no error";
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find(out.string()), std::string::npos) << e.what();
  }
}

TEST(ExportGlb, UnknownAssetNodeIsTheRenderersInputErrorAndWritesNothing) {
  ExportOptions o;
  o.cookCache = cookCache();
  const nlohmann::json bad = {{"bounce_level", 1},
                              {"effects", nlohmann::json::array()},
                              {"entities", {{{"id", "box"}, {"mesh", {{"asset", boxGlb()}, {"node", "nope"}}}}}}};
  const fs::path out = outDir() / "bad-node.glb";
  fs::remove(out);
  try {
    exportLevel(scene::loadLevel(writeLevel("bad-node.json", bad)), out, o);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("Box.glb"), std::string::npos) << msg;
    EXPECT_NE(msg.find("nope"), std::string::npos) << msg;
  }
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace bounce::scene_export::test
