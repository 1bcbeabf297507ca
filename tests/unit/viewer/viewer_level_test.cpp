// The level made for a glTF file (game/viewer_level.hpp) and the orbit camera of `bounce play`
// (game/play_controls.hpp): exact structure, framing invariants, orbit keeps its pivot.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "engine/core/file.hpp"
#include "engine/core/paths.hpp"
#include "engine/scene/level.hpp"
#include "game/play_controls.hpp"
#include "game/session.hpp"
#include "game/viewer_level.hpp"

namespace fs = std::filesystem;
using namespace bounce;
using namespace bounce::game;

namespace {

const fs::path kAssets = fs::path(BOUNCE_SHARED_DIR) / "assets";
const fs::path kOut = fs::path(BOUNCE_TEST_OUT) / "viewer";
// Positions are floats written as shortest decimals and read back: exact up to float rounding of
// the arithmetic that follows (a few ulps of numbers of order 1..200).
constexpr float kTol = 1e-4f;

const scene::EntityDesc& entity(const scene::Level& level, const std::string& id) {
  for (const auto& e : level.entities)
    if (e.id == id) return e;
  throw std::runtime_error("no entity " + id);
}

scene::Level writeAndLoad(const fs::path& asset, const std::string& name) {
  fs::create_directories(kOut);
  const fs::path file = kOut / name;
  writeFileAtomic(file, viewerLevelText(asset, assetBounds(asset, cookCacheDir()), kOut));
  return scene::loadLevel(file);
}

}  // namespace

TEST(ViewerLevel, GltfFilesAreRecognisedByExtension) {
  EXPECT_TRUE(isGltfFile("a/Duck.glb"));
  EXPECT_TRUE(isGltfFile("a/Duck.GLTF"));
  EXPECT_FALSE(isGltfFile("a/cornell-1.json"));
  EXPECT_FALSE(isGltfFile("a/glb"));
}

TEST(ViewerLevel, BoundsFollowTheNodeTransforms) {
  // Box.gltf: a unit cube under a node that turns it -90° about X: still [-0.5, 0.5]³.
  const AssetBounds box = assetBounds(kAssets / "Box/glTF/Box.gltf", cookCacheDir());
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(box.min[a], -0.5f, 1e-6f);
    EXPECT_NEAR(box.max[a], 0.5f, 1e-6f);
  }
  // Duck: the mesh accessor's box (x -69.3..96.2, y 9.9..164, z -61.3..53.9) scaled by the root's 0.01.
  const AssetBounds duck = assetBounds(kAssets / "Duck/glTF-Binary/Duck.glb", cookCacheDir());
  EXPECT_NEAR(duck.min.x, -0.692985f, 1e-5f);
  EXPECT_NEAR(duck.max.y, 1.6397f, 1e-5f);
  EXPECT_NEAR(duck.min.y, 0.0992937f, 1e-5f);
}

TEST(ViewerLevel, StructureAndFraming) {
  const fs::path asset = kAssets / "Duck/glTF-Binary/Duck.glb";
  const AssetBounds b = assetBounds(asset, cookCacheDir());
  const scene::Level level = writeAndLoad(asset, "duck.json");
  const glm::vec3 c = b.centre();
  const float r = b.radius();

  EXPECT_EQ(level.effects.names(), (std::vector<std::string>{"direct", "shadows", "probes"}));
  EXPECT_EQ(level.background, glm::vec3(kViewerSky));
  EXPECT_NEAR(level.probes.spacing, 2.0f * kViewerGroundHalf * r / float(kViewerProbesPerAxis), kTol);
  EXPECT_EQ(level.probes.rays, kViewerProbeRays);
  ASSERT_EQ(level.entities.size(), 4u);

  // The asset, at the origin, untransformed.
  const auto& a = entity(level, "asset");
  ASSERT_TRUE(a.mesh);
  EXPECT_EQ(a.mesh->asset, fs::absolute(asset).lexically_normal());
  EXPECT_EQ(a.transform, scene::Transform{});
  EXPECT_FALSE(a.dynamic);

  // The ground: under the lowest point, centred below the model, kViewerGroundHalf radii each side.
  const auto& g = entity(level, "ground");
  ASSERT_TRUE(g.mesh);
  // Compared as canonical paths: a build tree's content/ is a link to the source tree's.
  EXPECT_EQ(std::filesystem::weakly_canonical(g.mesh->asset),
            std::filesystem::weakly_canonical(contentDir() / "src/ground/ground.gltf"));
  EXPECT_NEAR(g.transform.translation.y, b.min.y, kTol);
  EXPECT_NEAR(g.transform.translation.x, c.x, kTol);
  EXPECT_NEAR(g.transform.translation.z, c.z, kTol);
  EXPECT_NEAR(g.transform.scale.x, 2.0f * kViewerGroundHalf * r, kTol);
  EXPECT_NEAR(g.transform.scale.z, 2.0f * kViewerGroundHalf * r, kTol);

  // The camera looks at the centre, the bounding sphere fits the vertical field of view, and the
  // near/far planes keep the model and the whole ground.
  const auto& cam = entity(level, "camera");
  ASSERT_TRUE(cam.camera);
  const glm::vec3 eye = cam.transform.translation;
  const glm::vec3 f = FlyCamera::forward(cam.transform.rotation);
  const float d = glm::length(c - eye);
  EXPECT_GT(glm::dot(f, (c - eye) / d), 1.0f - 1e-5f);
  EXPECT_GE(d * std::sin(0.5f * cam.camera->yfovRad), r);
  EXPECT_LE(d * std::sin(0.5f * cam.camera->yfovRad), 1.1f * r) << "not needlessly far";
  EXPECT_GT(eye.y, c.y) << "seen from above";
  EXPECT_LT(cam.camera->near, d - r);
  EXPECT_GT(cam.camera->far, d + std::sqrt(2.0f) * kViewerGroundHalf * r + r);

  // The sun: a directional light with shadows, shining down.
  const auto& sun = entity(level, "sun");
  ASSERT_TRUE(sun.light);
  EXPECT_EQ(sun.light->type, scene::LightType::Directional);
  EXPECT_TRUE(sun.light->shadows);
  EXPECT_EQ(sun.light->intensity, kViewerSunIrradiance);
  EXPECT_LT(FlyCamera::forward(sun.transform.rotation).y, -0.5f);
}

TEST(ViewerLevel, WrittenPathsAreRelativeToTheLevel) {
  const fs::path asset = kAssets / "Box/glTF-Binary/Box.glb";
  fs::create_directories(kOut);
  const std::string text = viewerLevelText(asset, assetBounds(asset, cookCacheDir()), kOut);
  EXPECT_EQ(text.find("\"/"), std::string::npos) << "no absolute path:\n" << text;
  EXPECT_NE(text.find("Box/glTF-Binary/Box.glb\""), std::string::npos) << text;
}

TEST(ViewerLevel, NonGltfInputIsUnchanged) {
  EXPECT_EQ(levelPathFor("content/levels/cornell-1.json"), fs::path("content/levels/cornell-1.json"));
  EXPECT_EQ(captureScriptPathFor("content/captures/cornell-1.json"), fs::path("content/captures/cornell-1.json"));
}

TEST(OrbitCamera, KeepsThePivotAndZooms) {
  scene::Transform t;
  t.translation = {1.0f, 2.0f, 3.0f};
  t.rotation = FlyCamera::rotationFromYawPitch(0.3f, -0.4f);
  FlyCamera cam(t);
  const glm::vec3 pivot = t.translation + FlyCamera::forward(t.rotation) * 2.0f;
  const glm::vec3 rightBefore = t.rotation * glm::vec3(1, 0, 0);
  float distance = 2.0f;
  const scene::Transform u = cam.orbit(t, {100.0f, -40.0f}, 2.0f, distance);
  EXPECT_NEAR(distance, 2.0f * FlyCamera::kZoomStep * FlyCamera::kZoomStep, 1e-6f);
  const glm::vec3 back = u.translation + FlyCamera::forward(u.rotation) * distance;
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(back[a], pivot[a], 1e-5f);
  // Drag right: the model turns right, so the camera goes round to its left.
  EXPECT_LT(glm::dot(u.translation - t.translation, rightBefore), 0.0f);
  EXPECT_NEAR(cam.yaw(), 0.3f - 100.0f * FlyCamera::kOrbitRadiansPerPixel, 1e-6f);
  // Zooming far in stops at the minimum distance, still looking at the pivot.
  cam.orbit(u, {}, 1000.0f, distance);
  EXPECT_EQ(distance, FlyCamera::kMinOrbitDistance);
}

TEST(OrbitCamera, DriverTakesOverAndResets) {
  ecs::Registry reg;
  const ecs::Entity e = reg.create();
  scene::Transform start;
  start.translation = {0.0f, 0.0f, 5.0f};
  reg.emplace<scene::Transform>(e, start);
  CameraDriver driver(reg, e);
  driver.setOrbitDistance(5.0f);
  FlyInput in;
  in.zoom = 1.0f;
  EXPECT_TRUE(driver.drive(in, 0.016f));
  EXPECT_NEAR(driver.orbitDistance(), 4.5f, 1e-6f);
  EXPECT_NEAR(reg.get<scene::Transform>(e).translation.z, 4.5f, 1e-5f) << "zoomed towards the origin";
  driver.reset();
  EXPECT_EQ(driver.orbitDistance(), 5.0f);
  EXPECT_EQ(reg.get<scene::Transform>(e), start);
}
