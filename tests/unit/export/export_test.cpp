// bounce export round trip: a level is exported to .glb, re-imported with the engine's own glTF
// cooker, and compared with the level's instances computed independently (test_util.hpp) from the
// cooked source assets and the scene systems.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/anim/skinning.hpp"
#include "engine/core/error.hpp"
#include "engine/scene/transform_math.hpp"
#include "engine/scene_export/export.hpp"
#include "tests/unit/export/test_util.hpp"

namespace bounce::scene_export::test {
namespace {

// Bounds: relative to the scene's diagonal. The exporter and this test compose the same float
// matrices, but the re-import adds one more product (root identity · node matrix) and the vertex
// transform may round differently: a few float ulps, far below 1e-5.
constexpr float kBoundsRel = 1e-5f;
// Positions (metres) of lights and cameras in scenes under 1 m: float rounding of the
// Gram–Schmidt rigid frame and of the matrix written as doubles.
constexpr float kPositionTol = 1e-6f;
// Unit direction vectors: same rounding.
constexpr float kDirectionTol = 1e-6f;

fs::path exportTo(const std::string& name, const fs::path& levelFile, double t, ExportStats* stats = nullptr) {
  ExportOptions o;
  o.timeSeconds = t;
  o.cookCache = cookCache();
  const fs::path out = outDir() / name;
  const ExportStats s = exportLevel(scene::loadLevel(levelFile), out, o);
  if (stats) *stats = s;
  return out;
}

void expectBoxNear(const Box& actual, const Box& expected, float tol) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(actual.min[k], expected.min[k], tol) << "min[" << k << "]";
    EXPECT_NEAR(actual.max[k], expected.max[k], tol) << "max[" << k << "]";
  }
}

void expectVecNear(const glm::vec3& a, const glm::vec3& b, float tol) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tol) << "component " << k;
}

const Placed* findNode(const std::vector<Placed>& nodes, const std::string& name) {
  for (const auto& p : nodes)
    if (p.name == name) return &p;
  return nullptr;
}

// The material of the first primitive of the first mesh node under entity `root`.
const asset::Material* entityMaterial(const asset::CookedAsset& a, const std::string& root) {
  for (const auto& p : placedNodes(a)) {
    const int mesh = a.nodes[std::size_t(p.node)].mesh;
    if (p.root != root || mesh < 0) continue;
    const int m = a.meshes[std::size_t(mesh)].primitives.at(0).material;
    return m < 0 ? nullptr : &a.materials[std::size_t(m)];
  }
  return nullptr;
}

TEST(Export, Cornell5TrianglesAndBoundsMatchTheLevelsInstances) {
  const auto lvl = scene::loadLevel(level("cornell-5.json"));
  ExportStats stats;
  const auto glb = exportTo("cornell5-t0.glb", level("cornell-5.json"), 0.0, &stats);
  const Expected want = expectedInstances(lvl, 0.0);
  const asset::CookedAsset back = asset::cook(glb);
  const Imported got = importedInstances(back);

  EXPECT_EQ(got.triangles, want.triangles);
  EXPECT_EQ(got.instances, want.instances);
  EXPECT_EQ(stats.triangles, want.triangles);
  EXPECT_EQ(stats.instances, want.instances);
  EXPECT_GT(want.triangles, 0u);
  expectBoxNear(got.bounds, want.bounds, kBoundsRel * want.bounds.diagonal());
  // Per entity too: each instance is under the root node named by its entity id.
  for (const auto& [id, box] : want.entityBounds) {
    SCOPED_TRACE(id);
    expectBoxNear(importedInstances(back, id).bounds, box, kBoundsRel * want.bounds.diagonal());
  }
  // Meshes are shared: two entities instance Box.glb (with different albedo overrides, so two
  // meshes), but the file holds fewer meshes than instances.
  EXPECT_LT(stats.meshes, stats.instances);
}

TEST(Export, Cornell5LightMatchesWithIdentityUnitConversion) {
  const auto glb = exportTo("cornell5-light.glb", level("cornell-5.json"), 0.0);
  const asset::CookedAsset back = asset::cook(glb);
  ASSERT_EQ(back.lights.size(), 1u);
  const asset::Light& L = back.lights[0];
  EXPECT_EQ(L.type, asset::LightType::Point);
  // cornell-5.json: "color": [1.0, 0.92, 0.8], "intensity": 0.25 — 1 Bounce unit = 1 cd.
  EXPECT_FLOAT_EQ(L.color.r, 1.0f);
  EXPECT_FLOAT_EQ(L.color.g, 0.92f);
  EXPECT_FLOAT_EQ(L.color.b, 0.8f);
  EXPECT_FLOAT_EQ(L.intensity, 0.25f);
  EXPECT_EQ(L.range, 0.0f);
  const auto nodes = placedNodes(back);
  const Placed* lamp = findNode(nodes, "ceiling-lamp/light");
  ASSERT_NE(lamp, nullptr);
  EXPECT_EQ(back.nodes[std::size_t(lamp->node)].light, 0);
  EXPECT_EQ(lamp->root, "ceiling-lamp");
  expectVecNear(glm::vec3(lamp->world[3]), {0.0f, 0.5f, 0.0f}, kPositionTol);
}

TEST(Export, Cornell5CameraMatches) {
  const auto glb = exportTo("cornell5-camera.glb", level("cornell-5.json"), 0.0);
  const asset::CookedAsset back = asset::cook(glb);
  ASSERT_EQ(back.cameras.size(), 1u);
  const asset::Camera& c = back.cameras[0];
  EXPECT_EQ(c.type, asset::CameraType::Perspective);
  EXPECT_FLOAT_EQ(c.yfov, float(90.0 * M_PI / 180.0));  // "yfov_deg": 90
  EXPECT_FLOAT_EQ(c.znear, 0.005f);
  EXPECT_FLOAT_EQ(c.zfar, 5.0f);
  EXPECT_EQ(c.aspectRatio, 0.0f);  // omitted: the viewer's aspect
  const auto nodes = placedNodes(back);
  const Placed* cam = findNode(nodes, "camera/camera");
  ASSERT_NE(cam, nullptr);
  EXPECT_EQ(back.nodes[std::size_t(cam->node)].camera, 0);
  expectVecNear(glm::vec3(cam->world[3]), {0.0f, 0.42f, 0.27f}, kPositionTol);
  // Looks down −Z of "rotation_euler_deg": [-30, 0, 0] (issue 16: wider, the whole floor in view).
  const glm::quat rotation = scene::quatFromEulerDeg({-30.0f, 0.0f, 0.0f});
  const glm::vec3 forward = glm::mat3_cast(rotation) * glm::vec3(0, 0, -1);
  expectVecNear(-glm::normalize(glm::vec3(cam->world[2])), forward, kDirectionTol);
  expectVecNear(glm::normalize(glm::vec3(cam->world[1])), glm::mat3_cast(rotation) * glm::vec3(0, 1, 0), kDirectionTol);
}

TEST(Export, Cornell5MaterialOverridesSurvive) {
  const auto glb = exportTo("cornell5-materials.glb", level("cornell-5.json"), 0.0);
  const asset::CookedAsset back = asset::cook(glb);
  const asset::Material* red = entityMaterial(back, "prop-red-box");
  const asset::Material* blue = entityMaterial(back, "prop-blue-box");
  ASSERT_NE(red, nullptr);
  ASSERT_NE(blue, nullptr);
  // cornell-5.json albedo overrides; both props share Box.glb's geometry.
  EXPECT_FLOAT_EQ(red->baseColorFactor.r, 0.8f);
  EXPECT_FLOAT_EQ(red->baseColorFactor.g, 0.1f);
  EXPECT_FLOAT_EQ(red->baseColorFactor.b, 0.1f);
  EXPECT_FLOAT_EQ(blue->baseColorFactor.r, 0.1f);
  EXPECT_FLOAT_EQ(blue->baseColorFactor.g, 0.2f);
  EXPECT_FLOAT_EQ(blue->baseColorFactor.b, 0.8f);
  // Without an override the source material's factors are kept (the cornell walls' colours).
  const asset::CookedAsset cornell = asset::loadOrCook(contentAsset("cornell/cornell.gltf"), cookCache());
  std::size_t matched = 0;
  for (const auto& src : cornell.materials)
    for (const auto& m : back.materials)
      if (m.name == src.name && m.baseColorFactor == src.baseColorFactor && m.emissiveFactor == src.emissiveFactor) {
        ++matched;
        break;
      }
  EXPECT_EQ(matched, cornell.materials.size());
}

TEST(Export, Cornell5TexturedPropKeepsItsTexturePixels) {
  const auto glb = exportTo("cornell5-texture.glb", level("cornell-5.json"), 0.0);
  const asset::CookedAsset back = asset::cook(glb);
  const asset::CookedAsset src =
      asset::loadOrCook(contentAsset("BoxTextured/glTF-Draco-gltfpipeline/BoxTextured.gltf"), cookCache());
  ASSERT_FALSE(src.materials.empty());
  const int srcTex = src.materials[0].baseColorTexture.texture;
  ASSERT_GE(srcTex, 0);
  const asset::Material* m = entityMaterial(back, "prop-textured-box");
  ASSERT_NE(m, nullptr);
  ASSERT_GE(m->baseColorTexture.texture, 0);
  const asset::Texture& a = back.textures[std::size_t(m->baseColorTexture.texture)];
  const asset::Texture& b = src.textures[std::size_t(srcTex)];
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_TRUE(a.pixels == b.pixels) << "PNG is lossless: every RGBA8 byte must survive";
  // The truck's textures survive too, and each source texture is written once.
  const asset::CookedAsset truck =
      asset::loadOrCook(contentAsset("CesiumMilkTruck/glTF-Draco-gltfpipeline/CesiumMilkTruck.gltf"), cookCache());
  EXPECT_EQ(back.textures.size(), src.textures.size() + truck.textures.size());
}

TEST(Export, TimeMovesADynamicPropByItsScriptedMotion) {
  const auto lvl = scene::loadLevel(level("cornell-5.json"));
  const asset::CookedAsset at0 = asset::cook(exportTo("cornell5-time0.glb", level("cornell-5.json"), 0.0));
  const asset::CookedAsset at1 = asset::cook(exportTo("cornell5-time1.glb", level("cornell-5.json"), 1.0));
  const Box truck0 = importedInstances(at0, "prop-truck").bounds;
  const Box truck1 = importedInstances(at1, "prop-truck").bounds;
  // prop-truck: ping-pong keyframes, translation (-0.2, 0, 0.12) at t=0 → (-0.2, 0, -0.02) at t=4,
  // no rotation: at t=1 it has moved a quarter of the way, Δz = -0.14/4 = -0.035 m.
  const glm::vec3 motion(0.0f, 0.0f, -0.035f);
  Box moved;
  moved.grow(truck0.min + motion);
  moved.grow(truck0.max + motion);
  // The truck's wheels turn with its own clip (issue 12): a polygonal wheel's lowest and foremost
  // points move by up to r·(1 − cos(π/n)); 2e-4 m bounds that at the truck's 0.02 scale (observed 8e-6).
  constexpr float kTurningWheels = 2e-4f;
  expectBoxNear(truck1, moved, kTurningWheels);
  // And as the systems say (independent expansion at t = 1).
  const Expected want1 = expectedInstances(lvl, 1.0);
  expectBoxNear(truck1, want1.entityBounds.at("prop-truck"), kBoundsRel * want1.bounds.diagonal());
  expectBoxNear(importedInstances(at1).bounds, want1.bounds, kBoundsRel * want1.bounds.diagonal());
  // The static box does not move.
  const Box box0 = importedInstances(at0, "cornell-box").bounds;
  const Box box1 = importedInstances(at1, "cornell-box").bounds;
  expectBoxNear(box1, box0, 0.0f);
}

TEST(Export, AnimatedCharactersAreWrittenInTheirPoseAtTheGivenTime) {
  // characters.json: the fox's exported vertices are its skinned pose at t (engine/anim, the same
  // evaluation the renderer's CPU face and the tracer use), placed by the entity: its bounds match
  // the pose computed here and change between t = 0 and t = 0.3 (clip and motion).
  const fs::path file = level("characters.json");
  const auto lvl = scene::loadLevel(file);
  auto posedFoxBounds = [&](double t) {
    ecs::Registry registry;
    const auto entities = scene::instantiate(lvl, registry);
    scene::motionSystem(registry, t);
    anim::attachAnimators(registry, cookCache());
    anim::animationSystem(registry, t);
    scene::transformSystem(registry);
    Box box;
    for (std::size_t i = 0; i < entities.size(); ++i) {
      if (lvl.entities[i].id != "fox") continue;
      const auto& an = registry.get<anim::Animator>(entities[i]);
      const auto& pose = registry.get<anim::Pose>(entities[i]);
      const glm::mat4 world = registry.get<scene::WorldTransform>(entities[i]).matrix;  // the default scene: the skin frame
      for (std::size_t n = 0; n < an.asset->nodes.size(); ++n) {
        if (!anim::isSkinned(*an.asset, int(n))) continue;
        std::vector<glm::vec3> p, nrm;
        for (std::size_t pi = 0; pi < an.asset->meshes[std::size_t(an.asset->nodes[n].mesh)].primitives.size(); ++pi) {
          anim::posePrimitive(*an.asset, int(n), pi, &pose, p, nrm);
          for (const auto& v : p) box.grow(glm::vec3(world * glm::vec4(v, 1.0f)));
        }
      }
    }
    return box;
  };
  const Box at0 = importedInstances(asset::cook(exportTo("characters-t0.glb", file, 0.0)), "fox").bounds;
  const Box at3 = importedInstances(asset::cook(exportTo("characters-t03.glb", file, 0.3)), "fox").bounds;
  const Box want0 = posedFoxBounds(0.0), want3 = posedFoxBounds(0.3);
  expectBoxNear(at0, want0, kBoundsRel * want0.diagonal());
  expectBoxNear(at3, want3, kBoundsRel * want3.diagonal());
  EXPECT_GT(glm::distance(at0.min, at3.min) + glm::distance(at0.max, at3.max), 0.05f);  // it ran
}

}  // namespace
}  // namespace bounce::scene_export::test
