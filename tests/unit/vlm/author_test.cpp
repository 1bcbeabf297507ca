// VLM authoring (README "Virtual Light Meshes"): glTF nodes with extras.bounce_vlm become virtual
// lights (and stop being real geometry), the precedence between a node's extras and an entity's
// `vlm` component, the paired real material's albedo as the default reflectance (§3.4), and the
// per-tag overrides of the level (§3.5, Fig. 5.5).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/gi/vlm/make.hpp"
#include "engine/gi/vlm/vlm_mesh.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene_export/flatten.hpp"

namespace bounce::gi::vlm {
namespace {

namespace fs = std::filesystem;

// Float products of a few exact inputs.
constexpr float kTol = 1e-6f;
const glm::vec3 kWallAlbedo(0.2f, 0.4f, 0.6f);
const glm::vec3 kMadeAlbedo(0.7f, 0.7f, 0.7f);

fs::path outDir() {
  const fs::path d = fs::path(BOUNCE_TEST_OUT) / "vlm-author";
  fs::create_directories(d);
  return d;
}
fs::path cookCache() { return outDir() / "cooked"; }

// A glTF of two unit quads (2 triangles each): node 0 "vlm-lamp" with extras.bounce_vlm {tag 4,
// color [1, .5, .5], intensity 2}, node 1 "real" without extras. Written by vlm-make's writer, to a
// file of the test's own (`name`): ctest runs the tests of this binary in parallel processes, and
// one shared file was read by one test while another was rewriting it.
fs::path twoNodeAsset(const std::string& name) {
  MakeResult r;
  for (const char* name : {"lamp", "real"}) {
    MadeMesh m;
    m.source = name;
    m.tag = 4;
    m.albedo = kMadeAlbedo;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}};
    m.normals.assign(4, glm::vec3(0, 1, 0));
    m.indices = {0, 2, 1, 1, 2, 3};
    r.meshes.push_back(m);
  }
  const fs::path file = outDir() / (name + "-two-node.gltf");
  writeVlmGltf(r, file);
  nlohmann::json doc = nlohmann::json::parse(readFileText(file));
  doc["nodes"][0]["extras"]["bounce_vlm"]["color"] = {1, 0.5, 0.5};
  doc["nodes"][0]["extras"]["bounce_vlm"]["intensity"] = 2;
  doc["nodes"][1].erase("extras");
  writeFileAtomic(file, doc.dump(1));
  return file;
}

fs::path writeLevel(const std::string& name, const std::string& entities, const std::string& vlm = "{}") {
  const fs::path path = outDir() / (name + ".json");
  std::ofstream(path) << R"({"bounce_level": 1, "effects": ["direct", "vlm"], "vlm": )" << vlm
                      << R"(, "entities": [)" << entities << "]}";
  return path;
}

std::string wall() {
  const fs::path box = fs::path(BOUNCE_SOURCE_DIR) / "content/src/Box/glTF-Binary/Box.glb";
  return R"({"id": "wall", "mesh": {"asset": ")" + box.generic_string() +
         R"("}, "material": {"albedo": [0.2, 0.4, 0.6]}, "vlm_tag": 4})";
}

struct Loaded {
  scene::Level level;
  ecs::Registry registry;
  std::vector<VlmMesh> vlms;
};

std::unique_ptr<Loaded> load(const fs::path& level) {
  auto l = std::make_unique<Loaded>();
  l->level = scene::loadLevel(level);
  scene::instantiate(l->level, l->registry);
  l->vlms = collectVlms(l->registry, cookCache());
  return l;
}

void expectVec(glm::vec3 got, glm::vec3 want) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], kTol) << "channel " << c;
}

TEST(VlmAuthoring, NodeExtrasMakeAPlainMeshAVlm) {
  const std::string asset = twoNodeAsset("extras").generic_string();
  const auto l = load(writeLevel("extras", wall() + R"(, {"id": "lights", "mesh": {"asset": ")" + asset + R"("}})"));
  ASSERT_EQ(l->vlms.size(), 1u);
  const VlmMesh& m = l->vlms[0];
  EXPECT_EQ(m.name, "lights");
  ASSERT_EQ(m.local.size(), 2u) << "only the node with extras; the other one is real geometry";
  for (const VirtualLight& v : m.local) {
    EXPECT_EQ(v.tag, 4u);
    // reflectance: none given, so the paired real material (the wall, vlm_tag 4) · color · intensity
    expectVec(v.scale, kWallAlbedo * glm::vec3(1.0f, 0.5f, 0.5f) * 2.0f);
  }
  // The real-geometry side: the exporter (as the renderer and the path tracer) skips the VLM node.
  const scene_export::FlatScene flat = scene_export::flattenLevel(l->level, 0.0, cookCache());
  std::size_t lightsMeshes = 0;
  for (const auto& mesh : flat.meshes) lightsMeshes += flat.entities[mesh.entity].id == "lights";
  EXPECT_EQ(lightsMeshes, 1u);
}

TEST(VlmAuthoring, TheVlmComponentOverridesTheExtrasItGives) {
  const std::string asset = twoNodeAsset("component").generic_string();
  const auto l = load(writeLevel("component", R"({"id": "lights", "mesh": {"asset": ")" + asset +
                                                  R"("}, "vlm": {"tag": 9, "intensity": 3}})"));
  ASSERT_EQ(l->vlms.size(), 1u);
  ASSERT_EQ(l->vlms[0].local.size(), 4u) << "a vlm entity's every mesh node is virtual";
  for (std::size_t i = 0; i < 4; ++i) {
    const VirtualLight& v = l->vlms[0].local[i];
    EXPECT_EQ(v.tag, 9u);
    // No real geometry has tag 9: reflectance = the VLM primitive's base colour. Node 0 keeps its
    // extras colour (the component gives none); intensity is the component's on both.
    const glm::vec3 color = i < 2 ? glm::vec3(1.0f, 0.5f, 0.5f) : glm::vec3(1.0f);
    expectVec(v.scale, kMadeAlbedo * color * 3.0f);
  }
}

TEST(VlmAuthoring, LevelOverridesParseAndApply) {
  const auto l = load(writeLevel("overrides", wall(),
                                 R"({"overrides": {"4": {"intensity": 2, "color": [1, 0.5, 0], "hue_deg": 120}, "12": {}}})"));
  ASSERT_EQ(l->level.vlm.overrides.size(), 2u);
  EXPECT_EQ(l->level.vlm.overrides.at(4), (scene::VlmOverride{2.0f, glm::vec3(1.0f, 0.5f, 0.0f), 120.0f}));
  EXPECT_EQ(l->level.vlm.overrides.at(12), scene::VlmOverride{});

  // Intensity scales linearly; colour multiplies; white is grey and keeps under any hue rotation;
  // 120° turns red into green (the grey axis rotation maps the RGB axes onto each other).
  const glm::vec3 s(0.3f, 0.2f, 0.1f);
  expectVec(applyOverride(s, {2.0f, glm::vec3(1.0f), 0.0f}), 2.0f * s);
  expectVec(applyOverride(s, {1.0f, glm::vec3(1.0f, 0.5f, 0.0f), 0.0f}), glm::vec3(0.3f, 0.1f, 0.0f));
  expectVec(applyOverride(glm::vec3(0.5f), {1.0f, glm::vec3(1.0f), 77.0f}), glm::vec3(0.5f));
  expectVec(applyOverride(glm::vec3(1, 0, 0), {1.0f, glm::vec3(1.0f), 120.0f}), glm::vec3(0, 1, 0));
  expectVec(applyOverride(glm::vec3(1, 0, 0), {1.0f, glm::vec3(1.0f), 240.0f}), glm::vec3(0, 0, 1));

  const std::vector<VirtualLight> lights = {{{}, {}, {}, {}, 3}, {{}, {}, {}, {}, 0}, {{}, {}, {}, {}, 1}, {{}, {}, {}, {}, 3}};
  EXPECT_EQ(tagsOf(lights), (std::vector<std::uint32_t>{1, 3}));
}

TEST(VlmAuthoring, BadOverridesAreOneLineErrors) {
  auto error = [&](const std::string& name, const std::string& vlm) {
    const fs::path path = writeLevel(name, wall(), vlm);
    try {
      (void)scene::loadLevel(path);
    } catch (const InputError& e) {
      std::string msg = e.what();
      return msg.substr(msg.find(": ") + 2);  // without the file
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(error("ov-zero", R"({"overrides": {"0": {}}})"),
            "/vlm/overrides/0: key \"0\" is not a tag (expected a decimal tag id in [1, 16777216])");
  EXPECT_EQ(error("ov-name", R"({"overrides": {"red": {}}})"),
            "/vlm/overrides/red: key \"red\" is not a tag (expected a decimal tag id in [1, 16777216])");
  EXPECT_EQ(error("ov-key", R"({"overrides": {"1": {"hue": 3}}})"),
            "/vlm/overrides/1/hue: unknown key \"hue\" (expected one of: intensity, color, hue_deg)");
  EXPECT_EQ(error("ov-neg", R"({"overrides": {"1": {"intensity": -1}}})"),
            "/vlm/overrides/1/intensity: -1 is out of range (expected a number in [0, 1e+06])");
  EXPECT_EQ(error("ov-type", R"({"overrides": [1]})"),
            "/vlm/overrides: wrong type: array (expected an object {\"TAG\": {\"intensity\": x, \"color\": [r, g, b], \"hue_deg\": h}})");
}

}  // namespace
}  // namespace bounce::gi::vlm
