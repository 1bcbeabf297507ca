// The reference sees what the rasteriser sees: its camera rays, texture filtering and the scene a
// level expands to; and `bounce reference` caches by content.
#include <gtest/gtest.h>

#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/ref/reference.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/scene/systems.hpp"
#include "tests/unit/ref/test_scenes.hpp"

namespace bounce::ref {
namespace {

// Float matrix maths in glm's projection vs the tracer's double-precision ray.
constexpr float kNdcTolerance = 2e-5f;
// Bilinear texture filtering in float: the sRGB decode (std::pow) and a lerp of values in [0, 1],
// each within a few ulps (ulp(1) = 1.2e-7); 1e-6 allows ~8.
constexpr float kFilterTol = 1e-6f;

TEST(Camera, RayGoesThroughPixelCentreOfTheRasterisersProjection) {
  RefCamera cam = test::lookAt({0.3f, 1.2f, 2.0f}, {-0.2f, 0.1f, 0.0f}, {0, 1, 0}, 72.0f);
  cam.near = 0.05f;
  cam.far = 7.0f;
  const std::uint32_t w = 40, h = 30;
  glm::mat4 proj = glm::perspectiveRH_ZO(cam.yfovRad, float(w) / float(h), cam.near, cam.far);
  proj[1][1] *= -1.0f;  // render::perspectiveVk
  const glm::mat4 viewProj = proj * glm::inverse(cam.world);
  for (auto [x, y] : {std::pair{0u, 0u}, {39u, 29u}, {17u, 5u}, {3u, 22u}}) {
    const CameraRay r = cameraRay(cam, w, h, x, y);
    auto ndc = [&](float t) {
      const glm::vec4 c = viewProj * glm::vec4(r.origin + t * r.direction, 1.0f);
      return glm::vec3(c) / c.w;
    };
    const glm::vec3 mid = ndc(1.0f);
    EXPECT_NEAR(mid.x, (x + 0.5f) / w * 2.0f - 1.0f, kNdcTolerance) << x << "," << y;
    EXPECT_NEAR(mid.y, (y + 0.5f) / h * 2.0f - 1.0f, kNdcTolerance) << x << "," << y;  // row 0 at the top
    EXPECT_NEAR(ndc(r.tMin).z, 0.0f, kNdcTolerance);  // near plane: depth 0
    EXPECT_NEAR(ndc(r.tMax).z, 1.0f, kNdcTolerance);  // far plane: depth 1
  }
}

TEST(Texture, BilinearFilterOfSrgbDecodedTexels) {
  // Two texels in a row: sRGB 128 and 255. Decoded: ((128/255 + 0.055)/1.055)^2.4 and 1.
  const std::vector<std::uint8_t> rgba = {128, 128, 128, 255, 255, 0, 255, 255};
  const RefTexture t = makeTexture(2, 1, rgba, true);
  const float a = std::pow((128.0f / 255.0f + 0.055f) / 1.055f, 2.4f);
  EXPECT_NEAR(t.sample({0.25f, 0.5f}).x, a, kFilterTol);                   // texel centre: that texel
  EXPECT_NEAR(t.sample({0.5f, 0.5f}).x, 0.5f * (a + 1.0f), kFilterTol);   // between centres: the linear mean
  EXPECT_NEAR(t.sample({0.5f, 0.5f}).y, 0.5f * a, kFilterTol);            // green of texel 1 is 0
  EXPECT_NEAR(t.sample({0.0f, 0.5f}).x, 0.5f * (a + 1.0f), kFilterTol);   // REPEAT: the edge blends both ends
  EXPECT_NEAR(t.sample({1.25f, -3.5f}).x, a, kFilterTol);                 // periodic in u and v
  const RefTexture linear = makeTexture(2, 1, rgba, false);
  EXPECT_NEAR(linear.sample({0.25f, 0.5f}).x, 128.0f / 255.0f, kFilterTol);
  const RefTexture broken = makeTexture(3, 3, rgba, true);  // wrong pixel count: white, as GpuScene
  EXPECT_EQ(broken.sample({0.3f, 0.3f}), glm::vec3(1.0f));
}

std::filesystem::path outDir() { return std::filesystem::path(BOUNCE_TEST_OUT) / "ref"; }
std::filesystem::path cornell() { return std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json"; }

// Every SceneBvh shares one Embree device (scene_bvh.cpp sharedDevice, each BVH holding a reference):
// BVHs built on several threads at once each answer their own rays, and one destroyed first leaves the
// others working (the device outlives it). Each BVH i is a floor quad at height i.
TEST(SceneBvh, BvhsOnOneSharedDeviceBuildOnThreadsAndOutliveEachOther) {
  constexpr std::size_t kCount = 6;
  std::vector<std::unique_ptr<SceneBvh>> bvh(kCount);
  parallelFor(0, kCount, [&](std::size_t i) {
    SceneDesc s;
    s.materials.push_back({});
    s.meshes.push_back(test::quad(glm::vec3(-1.0f, float(i), -1.0f), glm::vec3(0, 0, 2), glm::vec3(2, 0, 0), 0));
    bvh[i] = std::make_unique<SceneBvh>(std::move(s));
  });
  bvh[0].reset();
  bvh[3].reset();
  for (std::size_t i = 0; i < kCount; ++i) {
    if (!bvh[i]) continue;
    Hit hit;
    ASSERT_TRUE(bvh[i]->intersect(glm::vec3(0.0f, 10.0f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f), 0.0f, 100.0f, hit)) << i;
    EXPECT_FLOAT_EQ(hit.position.y, float(i)) << i;
    EXPECT_FALSE(bvh[i]->occluded(glm::vec3(0.0f, float(i) + 0.5f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 0.0f, 100.0f)) << i;
  }
}

TEST(LevelScene, CornellExpandsLikeTheRasteriser) {
  const scene::Level level = scene::loadLevel(cornell());
  ecs::Registry registry;
  scene::instantiate(level, registry);
  scene::motionSystem(registry, 0.0);
  scene::transformSystem(registry);
  ReferenceAssets assets;
  assets.load(registry, outDir() / "cooked");
  const SceneDesc s = extractScene(registry, level, assets);

  // 8 box parts (one primitive each) and the textured prop's one primitive.
  ASSERT_EQ(s.meshes.size(), 9u);
  ASSERT_EQ(s.materials.size(), 9u);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, RefLightType::Point);
  EXPECT_EQ(s.lights[0].position, glm::vec3(0.0f, 0.5f, 0.0f));
  EXPECT_NEAR(s.lights[0].radiance.y, 0.92f * 0.25f, 1e-7f);  // colour × intensity
  EXPECT_NEAR(s.camera.yfovRad, glm::radians(72.0f), 1e-6f);
  EXPECT_EQ(glm::vec3(s.camera.world[3]), glm::vec3(0.0f, 0.38f, 0.27f));
  // Cornell's red wall keeps its factor; the prop is textured.
  int textured = 0;
  for (const auto& m : s.materials) textured += m.albedoTexture >= 0;
  EXPECT_EQ(textured, 1);
  EXPECT_EQ(s.textures.size(), 1u);
  // At t = 0 the prop's orbit puts it at centre + radius·(+X) = (0.12, 0.42, 0).
  const RefMesh& prop = s.meshes.back();
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const auto& p : prop.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 centre = 0.5f * (lo + hi);
  EXPECT_NEAR(centre.x, 0.12f, 1e-4f);
  EXPECT_NEAR(centre.y, 0.42f, 1e-4f);
  EXPECT_NEAR(centre.z, 0.0f, 1e-4f);
}

TEST(ReferenceCache, SecondRunIsServedFromTheCacheAndKeysFollowInputs) {
  const auto cacheDir = outDir() / "reference-cache";
  std::filesystem::remove_all(cacheDir);
  ReferenceRequest r;
  r.input = cornell();
  r.spp = 2;
  r.bounces = 1;
  r.resolution = std::pair{16u, 12u};
  r.cacheDir = cacheDir;
  r.cookCache = outDir() / "cooked";
  r.progress = false;

  const ReferenceResult first = renderReference(r);
  EXPECT_FALSE(first.fromCache);
  EXPECT_TRUE(std::filesystem::exists(first.cachePath));
  EXPECT_GT(first.stats.rays, 16u * 12u * 2u);
  EXPECT_EQ(first.image.width, 16u);
  EXPECT_EQ(first.image.height, 12u);
  const ReferenceResult second = renderReference(r);
  EXPECT_TRUE(second.fromCache);
  EXPECT_EQ(second.key, first.key);
  EXPECT_EQ(second.image.rgb, first.image.rgb);

  // A capture script of the same level without camera motion, frame 0, poses the same scene.
  ReferenceRequest viaScript = r;
  viaScript.input = std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/captures/cornell-1.json";
  EXPECT_EQ(renderReference(viaScript).key, first.key);

  for (auto change : {+[](ReferenceRequest& q) { q.spp = 3; }, +[](ReferenceRequest& q) { q.bounces = 0; },
                      +[](ReferenceRequest& q) { q.frame = 30; }, +[](ReferenceRequest& q) { q.resolution = std::pair{12u, 16u}; }}) {
    ReferenceRequest other = r;
    change(other);
    EXPECT_NE(renderReference(other).key, first.key);
  }
}

// Issue 11: the key hashes the assets' content keys, not their absolute paths: the same level and
// asset in two folders (a moved or second checkout) name the same entry; planReference names the
// entry renderReference writes, without tracing.
TEST(ReferenceCache, KeyDoesNotDependOnWhereTheCheckoutIsAndPlanningTracesNothing) {
  const auto root = outDir() / "reference-moved";
  std::filesystem::remove_all(root);
  const std::string levelJson =
      R"({"bounce_level": 1, "effects": ["direct"], "entities": [{"id": "floor", "mesh": {"asset": "quad.gltf"}},
          {"id": "camera", "transform": {"translation": [0, 1, 0], "rotation_euler_deg": [-90, 0, 0]},
           "camera": {"yfov_deg": 60, "near": 0.05, "far": 5}},
          {"id": "lamp", "transform": {"translation": [0, 2, 0]},
           "light": {"type": "point", "color": [1, 1, 1], "intensity": 1}}]})";
  std::vector<ReferencePlan> plans;
  for (const char* where : {"a/checkout", "b/moved/elsewhere"}) {
    const auto dir = root / where;
    std::filesystem::create_directories(dir);
    std::filesystem::copy_file(std::filesystem::path(BOUNCE_SOURCE_DIR) / "tests/data/render/quad.gltf", dir / "quad.gltf");
    std::ofstream(dir / "level.json") << levelJson;
    ReferenceRequest r;
    r.input = dir / "level.json";
    r.spp = 1;
    r.resolution = std::pair{8u, 8u};
    r.cacheDir = root / "cache";
    r.cookCache = root / "cooked";
    r.progress = false;
    plans.push_back(planReference(r));
  }
  EXPECT_EQ(plans[0].key, plans[1].key);
  EXPECT_FALSE(std::filesystem::exists(plans[0].cachePath)) << "planning traces nothing";
  ReferenceRequest r;
  r.input = root / "a/checkout/level.json";
  r.spp = 1;
  r.resolution = std::pair{8u, 8u};
  r.cacheDir = root / "cache";
  r.cookCache = root / "cooked";
  r.progress = false;
  const ReferenceResult traced = renderReference(r);
  EXPECT_EQ(traced.cachePath, plans[0].cachePath);
  EXPECT_TRUE(loadCachedReference(plans[0].cachePath, 8, 8).has_value());
}

TEST(ReferenceCache, FrameBeyondTheCaptureScriptIsAnInputError) {
  ReferenceRequest r;
  r.input = std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/captures/cornell-1.json";
  r.frame = 61;  // the script simulates frames 0..60
  r.cacheDir = outDir() / "reference-cache-frame";  // not SecondRunIsServedFromTheCache's, which it clears
  r.cookCache = outDir() / "cooked";
  r.progress = false;
  try {
    renderReference(r);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--frame: frame 61 is not simulated"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bounce::ref
