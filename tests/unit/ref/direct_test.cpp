// Direct light (bounces 0) against closed forms: a Lambertian plane under point and spot lights,
// E = I·cosθ/d² and L = ρ/π·E; the glTF range window; an occluder's umbra is exactly black.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/math/sampling.hpp"
#include "tests/unit/ref/test_scenes.hpp"

namespace bounce::ref {
namespace {

using test::pixel;

constexpr std::uint32_t kSize = 32;
constexpr float kRho = 0.5f;
// Float rounding: Embree's hit point and the tracer's float light maths carry ~1e-6 relative
// error per step; d³ and the cone ramp amplify it a few times.
constexpr double kRelTolerance = 2e-4;

SceneDesc plane(const RefLight& light) {
  SceneDesc s;
  s.materials.push_back({glm::vec3(kRho), -1, glm::vec3(0.0f), -1});
  s.meshes.push_back(test::quad({-10, 0, -10}, {0, 0, 20}, {20, 0, 0}, 0));  // y = 0, normal +Y
  s.lights.push_back(light);
  s.camera = test::lookAt({0.1f, 2.5f, 0.4f}, {0, 0, 0}, {0, 0, -1}, 70.0f);
  return s;
}

// ρ/π · I · cosθ/d² for a point at p on the floor (normal +Y) and a light at q.
glm::dvec3 lambertPoint(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& intensity) {
  const glm::dvec3 v = q - p;
  const double d = glm::length(v);
  return double(kRho) / math::kPi * intensity * (v.y / d) / (d * d);
}

void expectNear(glm::vec3 got, glm::dvec3 expected, double scale, const std::string& where) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], kRelTolerance * scale) << where << " channel " << c;
}

TEST(Direct, PointLightOverPlaneMatchesClosedForm) {
  RefLight light;
  light.type = RefLightType::Point;
  light.position = {0.3f, 1.0f, -0.2f};
  light.radiance = {2.0f, 1.0f, 0.5f};
  SceneBvh bvh(plane(light));
  const gpu::FloatImage direct = trace(bvh, test::settings(kSize, 1, 0));
  // The plane cannot see itself: bounce rays escape to the black background, so unlimited
  // bounces give the same image, exactly.
  const gpu::FloatImage all = trace(bvh, test::settings(kSize, 4, kUnlimitedBounces));
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      glm::dvec3 p;
      ASSERT_TRUE(test::hitFloor(bvh.scene().camera, kSize, x, y, p));
      const glm::dvec3 expected = lambertPoint(p, glm::dvec3(light.position), glm::dvec3(light.radiance));
      expectNear(pixel(direct, x, y), expected, expected.x, "pixel " + std::to_string(x) + "," + std::to_string(y));
      EXPECT_EQ(pixel(all, x, y), pixel(direct, x, y));
    }
}

TEST(Direct, SpotConeFollowsLightsGlsl) {
  const float inner = glm::radians(20.0f), outer = glm::radians(30.0f);
  RefLight light;
  light.type = RefLightType::Spot;
  light.position = {0.0f, 1.0f, 0.0f};
  light.direction = {0.0f, -1.0f, 0.0f};
  light.radiance = glm::vec3(3.0f);
  light.cosInner = std::cos(inner);
  light.cosOuter = std::cos(outer);
  SceneBvh bvh(plane(light));
  const gpu::FloatImage img = trace(bvh, test::settings(kSize, 1, 0));
  const double peak = lambertPoint({0, 0, 0}, {0, 1, 0}, glm::dvec3(3.0)).x;
  int full = 0, ramp = 0, dark = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      glm::dvec3 p;
      ASSERT_TRUE(test::hitFloor(bvh.scene().camera, kSize, x, y, p));
      const glm::dvec3 q(light.position);
      const double cosAngle = glm::dot(glm::normalize(p - q), glm::dvec3(0, -1, 0));
      const double t = std::clamp((cosAngle - std::cos(double(outer))) / (std::cos(double(inner)) - std::cos(double(outer))), 0.0, 1.0);
      const std::string where = "pixel " + std::to_string(x) + "," + std::to_string(y);
      if (cosAngle < std::cos(double(outer)) - 1e-4) {
        EXPECT_EQ(pixel(img, x, y), glm::vec3(0.0f)) << where;  // outside the cone: exactly dark
        ++dark;
      } else {
        expectNear(pixel(img, x, y), lambertPoint(p, q, glm::dvec3(3.0)) * t * t, peak, where);
        t >= 1.0 ? ++full : ++ramp;
      }
    }
  // The view covers all three regions of the cone.
  EXPECT_GT(full, 20);
  EXPECT_GT(ramp, 20);
  EXPECT_GT(dark, 20);
}

TEST(Direct, RangeWindowEndsLightAtRange) {
  RefLight light;
  light.type = RefLightType::Point;
  light.position = {0.0f, 1.0f, 0.0f};
  light.radiance = glm::vec3(1.0f);
  light.range = 1.4f;
  SceneBvh bvh(plane(light));
  const gpu::FloatImage img = trace(bvh, test::settings(kSize, 1, 0));
  const double peak = lambertPoint({0, 0, 0}, {0, 1, 0}, glm::dvec3(1.0)).x;
  int lit = 0, dark = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      glm::dvec3 p;
      ASSERT_TRUE(test::hitFloor(bvh.scene().camera, kSize, x, y, p));
      const double d = glm::length(glm::dvec3(light.position) - p), r = d / light.range;
      const std::string where = "pixel " + std::to_string(x) + "," + std::to_string(y);
      if (d >= light.range * (1.0 + 1e-5)) {
        EXPECT_EQ(pixel(img, x, y), glm::vec3(0.0f)) << where;
        ++dark;
      } else {
        const double w = std::clamp(1.0 - r * r * r * r, 0.0, 1.0);  // KHR_lights_punctual window
        expectNear(pixel(img, x, y), lambertPoint(p, glm::dvec3(light.position), glm::dvec3(1.0)) * w * w, peak, where);
        ++lit;
      }
    }
  EXPECT_GT(lit, 20);
  EXPECT_GT(dark, 20);
}

TEST(Direct, OccluderUmbraIsExactlyBlack) {
  RefLight light;
  light.type = RefLightType::Point;
  light.position = {0.0f, 1.0f, 0.0f};
  light.radiance = glm::vec3(1.0f);
  SceneDesc s = plane(light);
  // A 0.2 m square at y = 0.5 under the lamp: its shadow on the floor is the 0.4 m square
  // |x|, |z| < 0.2 (the light is twice as high as the occluder).
  s.meshes.push_back(test::quad({-0.1f, 0.5f, -0.1f}, {0, 0, 0.2f}, {0.2f, 0, 0}, 0));
  s.camera = test::lookAt({0.9f, 2.0f, 0.3f}, {0, 0, 0}, {0, 1, 0}, 50.0f);
  SceneBvh bvh(std::move(s));
  const gpu::FloatImage img = trace(bvh, test::settings(kSize, 1, 0));
  int umbra = 0, lit = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      const CameraRay r = cameraRay(bvh.scene().camera, kSize, kSize, x, y);
      const double tOcc = (0.5 - double(r.origin.y)) / double(r.direction.y);
      const glm::dvec3 o = glm::dvec3(r.origin) + tOcc * glm::dvec3(r.direction);
      if (tOcc > 0.0 && std::max(std::abs(o.x), std::abs(o.z)) < 0.11) continue;  // sees the occluder
      glm::dvec3 p;
      ASSERT_TRUE(test::hitFloor(bvh.scene().camera, kSize, x, y, p));
      const double m = std::max(std::abs(p.x), std::abs(p.z));
      const std::string where = "pixel " + std::to_string(x) + "," + std::to_string(y);
      if (m < 0.19) {
        EXPECT_EQ(pixel(img, x, y), glm::vec3(0.0f)) << where;
        ++umbra;
      } else if (m > 0.21) {
        const glm::dvec3 expected = lambertPoint(p, glm::dvec3(light.position), glm::dvec3(1.0));
        expectNear(pixel(img, x, y), expected, expected.x, where);
        ++lit;
      }
    }
  EXPECT_GT(umbra, 10);
  EXPECT_GT(lit, 100);
}

// A light with a radius (scene::Light::radius, SL local lights) is a sphere: the centre's E cos θ
// times the visible fraction of its cap (one shadow ray per sample at a direction uniform in the
// cap). Under a square occluder: against that fraction by dense sampling of the cap (128² strata, ray
// vs the square), within 4 σ of the Bernoulli mean at 256 spp (σ ≤ 0.5/16) plus the strata's error;
// fully lit pixels are exactly the point light's closed form (no ray blocked: estimator constant).
TEST(Direct, SphereLightPenumbraMatchesItsVisibleCapFraction) {
  RefLight light;
  light.type = RefLightType::Point;
  light.position = {0.0f, 1.0f, 0.0f};
  light.radiance = glm::vec3(1.0f);
  light.radius = 0.1f;
  SceneDesc s = plane(light);
  s.meshes.push_back(test::quad({-0.1f, 0.5f, -0.1f}, {0, 0, 0.2f}, {0.2f, 0, 0}, 0));
  s.camera = test::lookAt({0.9f, 2.0f, 0.3f}, {0, 0, 0}, {0, 1, 0}, 50.0f);
  SceneBvh bvh(std::move(s));
  constexpr std::uint32_t kSpp = 256;
  const gpu::FloatImage img = trace(bvh, test::settings(kSize, kSpp, 0));
  const auto fraction = [&](const glm::dvec3& p) {
    const glm::dvec3 q(light.position);
    const double dist = glm::length(q - p), cosA = std::sqrt(1.0 - 0.01 / (dist * dist));
    const glm::dvec3 w = (q - p) / dist;
    const glm::dvec3 t = glm::normalize(glm::cross(w, glm::dvec3(1, 0, 0))), b = glm::cross(w, t);
    constexpr int kN = 128;
    int seen = 0;
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j) {
        const double c = 1.0 - (1.0 - cosA) * (i + 0.5) / kN, sn = std::sqrt(1.0 - c * c), phi = 2.0 * math::kPi * (j + 0.5) / kN;
        const glm::dvec3 d = c * w + sn * (std::cos(phi) * t + std::sin(phi) * b);
        const glm::dvec3 o = p + (0.5 - p.y) / d.y * d;
        seen += std::max(std::abs(o.x), std::abs(o.z)) < 0.1 ? 0 : 1;
      }
    return double(seen) / double(kN * kN);
  };
  int penumbra = 0, lit = 0, umbra = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      const CameraRay r = cameraRay(bvh.scene().camera, kSize, kSize, x, y);
      const double tOcc = (0.5 - double(r.origin.y)) / double(r.direction.y);
      const glm::dvec3 o = glm::dvec3(r.origin) + tOcc * glm::dvec3(r.direction);
      if (tOcc > 0.0 && std::max(std::abs(o.x), std::abs(o.z)) < 0.11) continue;  // sees the occluder
      glm::dvec3 p;
      ASSERT_TRUE(test::hitFloor(bvh.scene().camera, kSize, x, y, p));
      const double f = fraction(p);
      const glm::dvec3 full = lambertPoint(p, glm::dvec3(light.position), glm::dvec3(1.0));
      const std::string where = "pixel " + std::to_string(x) + "," + std::to_string(y);
      if (f == 1.0) {
        expectNear(pixel(img, x, y), full, full.x, where);
        ++lit;
      } else {
        EXPECT_NEAR(pixel(img, x, y).x / full.x, f, 4.0 * 0.5 / std::sqrt(double(kSpp)) + 0.01) << where;
        penumbra += f > 0.0 ? 1 : 0;
        umbra += f == 0.0 ? 1 : 0;
      }
    }
  EXPECT_GT(penumbra, 20);
  EXPECT_GT(lit, 100);
  std::printf("sphere light: %d penumbra, %d umbra, %d lit pixels\n", penumbra, umbra, lit);
}

}  // namespace
}  // namespace bounce::ref
