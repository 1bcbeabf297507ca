// Shadows against geometry: tests/data/render/plane-shadow.json puts a 0.2 m square occluder
// 0.5 m below a point light, 1.5 m above a white floor; the camera hangs between occluder and
// floor (so it sees only the floor). A point light casts a hard shadow whose umbra is the
// occluder's central projection onto the floor. Each floor pixel is classified by where the ray
// from the light to its surface point crosses the occluder's plane:
//   inside the square by more than the PCF margin  → umbra: no direct light at all;
//   outside by more than the margin                → lit: the unshadowed closed form ρ/π·I·h/d³
//                                                     (no acne, no light leaking, no peter-panning
//                                                     into the lit floor);
//   within the margin                              → penumbra of the filter, not checked.
// With `shadows` off the same level matches the unshadowed closed form everywhere.
// The same test runs for a spot light pointing down (plane-shadow-spot.json: the umbra is again a
// central projection, inside the lit cone) and a directional light 20° off vertical
// (plane-shadow-directional.json: a parallel projection, the umbra is the occluder shifted along
// the light direction), with each light type's shadow-map texel size.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "engine/gpu/testing.hpp"
#include "tests/unit/render/analytic.hpp"

using namespace bounce;
using namespace bounce::rtest;

namespace {

constexpr std::uint32_t kWidth = 96, kHeight = 64;
constexpr std::uint32_t kShadowResolution = 1024;  // FrameSettings' default, which renderLevel uses
// RGBA16F storage: up to 2^-10 relative when the device truncates to half (lavapipe does), with
// 50 % to spare (see direct_light_test.cpp).
constexpr float kRelativeTolerance = 1.5e-3f;
// Umbra pixels must be black: every PCF tap compares against the occluder's depth, so the
// visibility is exactly 0 and the radiance exactly 0; one leaking tap of nine would give ~1e-2.
constexpr float kUmbraMax = 1e-6f;
// Half-width of the region around the shadow edge left unchecked, in shadow-map texels: the
// 3×3 hardware-PCF taps reach 2 texels (shadow.glsl), the normal offset shifts the lookup by up
// to 1.5 texels sideways, and the rasterised occluder edge is exact only to half a texel;
// 4 texels total, rounded up to 6.
constexpr float kMarginTexels = 6.0f;

// Geometry of the occluder in plane-shadow.json (a quad of half-size 0.5 scaled by 0.2).
struct Occluder {
  glm::vec3 centre;
  float halfSize;
};

Occluder readOccluder(const scene::Level& level) {
  for (const auto& e : level.entities)
    if (e.id == "occluder") return {e.transform.translation, 0.5f * e.transform.scale.x};
  ADD_FAILURE() << "no occluder";
  return {};
}

enum class Zone { Umbra, Lit, Margin };

// Signed distance (metres, in the occluder's plane) from the point where the ray from p towards
// the light crosses that plane to the occluder square's boundary: negative inside.
float signedDistanceToOccluder(const FloorScene& s, const Occluder& o, glm::vec3 p) {
  glm::vec3 q;
  if (s.light.type == scene::LightType::Directional) {
    const glm::vec3 d = s.lightDirection;  // travel direction, d.y < 0
    q = p - d * ((o.centre.y - p.y) / -d.y);
  } else {
    const glm::vec3 L = s.lightPosition;
    q = L + (p - L) * ((L.y - o.centre.y) / (L.y - p.y));
  }
  return std::max(std::abs(q.x - o.centre.x), std::abs(q.z - o.centre.z)) - o.halfSize;
}

// One shadow-map texel, in metres in the occluder's plane (where the edge is rasterised), as
// shadow_setup.cpp lays the maps out.
float shadowTexel(const FloorScene& s, const Occluder& o, const scene::Level& level) {
  const float res = float(kShadowResolution);
  switch (s.light.type) {
    case scene::LightType::Point:
      // Every checked floor point lies in the −Y face of the light's cube map (asserted below), a
      // 90° frustum: 2·tan 45°·(distance along −Y)/resolution.
      return 2.0f * (s.lightPosition.y - o.centre.y) / res;
    case scene::LightType::Spot: {
      // A frustum of half-angle 1.05·θ_outer about the (vertical) spot axis.
      const float half = std::min(1.05f * s.light.outerConeRad, 1.5f);
      return 2.0f * std::tan(half) * (s.lightPosition.y - o.centre.y) / res;
    }
    case scene::LightType::Directional: {
      // An orthographic box of half-width r = half the diagonal of the scene bounds: 2r/resolution
      // across the light, stretched by 1/|d.y| where the horizontal plane cuts it. Bounds: the
      // floor (a unit quad scaled by its scale) and the occluder.
      glm::vec3 lo(0.0f), hi(0.0f);
      for (const auto& e : level.entities) {
        if (!e.mesh) continue;
        const glm::vec3 half = 0.5f * glm::vec3(e.transform.scale.x, 0.0f, e.transform.scale.z);
        lo = glm::min(lo, e.transform.translation - half);
        hi = glm::max(hi, e.transform.translation + half);
      }
      return glm::length(hi - lo) / res / std::abs(s.lightDirection.y);
    }
  }
  return 0.0f;
}

Zone classify(const FloorScene& s, const Occluder& o, float texel, glm::vec3 p) {
  const float sd = signedDistanceToOccluder(s, o, p);
  if (sd < -kMarginTexels * texel) return Zone::Umbra;
  if (sd > kMarginTexels * texel) return Zone::Lit;
  return Zone::Margin;
}

std::string describe(std::uint32_t x, std::uint32_t y, glm::vec3 a, glm::vec3 g) {
  std::ostringstream s;
  s << "pixel (" << x << "," << y << "): rendered (" << a.r << "," << a.g << "," << a.b << "), expected (" << g.r << ","
    << g.g << "," << g.b << ")";
  return s.str();
}

bool matches(glm::vec3 a, glm::vec3 g) {
  for (int c = 0; c < 3; ++c)
    if (!(std::abs(a[c] - g[c]) <= kRelativeTolerance * g[c])) return false;
  return true;
}

}  // namespace

struct ShadowCase {
  const char* level;
  int minUmbra, minLit;  // the scene puts this much umbra and lit floor in view
};

void PrintTo(const ShadowCase& c, std::ostream* os) { *os << c.level; }

class Shadows : public ::testing::TestWithParam<ShadowCase> {};

TEST_P(Shadows, UmbraIsDarkAndLitFloorMatchesClosedForm) {
  const auto path = kDataDir / GetParam().level;
  const scene::Level level = scene::loadLevel(path);
  const FloorScene s = readFloorScene(level);
  const Occluder o = readOccluder(level);
  const float texel = shadowTexel(s, o, level);
  const Frame frame = renderLevel(path, kWidth, kHeight);
  EXPECT_EQ(frame.passes, (std::vector<std::string>{"shadow", "gbuffer", "lighting", "tonemap"}));

  int umbra = 0, lit = 0, badUmbra = 0, badLit = 0;
  std::string firstBadUmbra, firstBadLit;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const glm::vec3 p = floorPoint(s, kWidth, kHeight, x, y).value();
      const glm::vec3 toP = p - s.lightPosition;
      if (s.light.type == scene::LightType::Point) {
        ASSERT_TRUE(-toP.y >= std::max(std::abs(toP.x), std::abs(toP.z))) << "floor point outside the −Y cube face";
      }
      const glm::vec3 a = frame.at(x, y);
      const glm::vec3 g = floorRadiance(s, p);
      switch (classify(s, o, texel, p)) {
        case Zone::Umbra:
          ++umbra;
          if (!(std::max({a.r, a.g, a.b}) <= kUmbraMax) && badUmbra++ == 0) firstBadUmbra = describe(x, y, a, {0, 0, 0});
          break;
        case Zone::Lit:
          ++lit;
          if (!matches(a, g) && badLit++ == 0) firstBadLit = describe(x, y, a, g);
          break;
        case Zone::Margin: break;
      }
    }
  EXPECT_GT(umbra, GetParam().minUmbra);
  EXPECT_GT(lit, GetParam().minLit);
  EXPECT_EQ(badUmbra, 0) << badUmbra << " of " << umbra << " umbra pixels receive light; first: " << firstBadUmbra;
  EXPECT_EQ(badLit, 0) << badLit << " of " << lit << " lit pixels differ from the closed form; first: " << firstBadLit;
}

INSTANTIATE_TEST_SUITE_P(LightTypes, Shadows,
                         ::testing::Values(ShadowCase{"plane-shadow.json", 1000, 2000},
                                           ShadowCase{"plane-shadow-spot.json", 1000, 2000},
                                           ShadowCase{"plane-shadow-directional.json", 1000, 2000}),
                         [](const ::testing::TestParamInfo<ShadowCase>& info) {
                           const std::string name = info.param.level;
                           return name == "plane-shadow.json" ? std::string("Point")
                                  : name == "plane-shadow-spot.json" ? std::string("Spot")
                                                                      : std::string("Directional");
                         });

TEST(ShadowsOff, MatchesUnshadowedClosedFormEverywhere) {
  const auto path = kDataDir / "plane-shadow.json";
  const FloorScene s = readFloorScene(scene::loadLevel(path));
  const Frame frame = renderLevel(path, kWidth, kHeight, std::vector<std::string>{"direct"});
  EXPECT_EQ(frame.passes, (std::vector<std::string>{"gbuffer", "lighting", "tonemap"}));
  int bad = 0;
  std::string first;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const glm::vec3 p = floorPoint(s, kWidth, kHeight, x, y).value();
      const glm::vec3 a = frame.at(x, y), g = floorRadiance(s, p);
      if (!matches(a, g) && bad++ == 0) first = describe(x, y, a, g);
    }
  EXPECT_EQ(bad, 0) << bad << " pixels differ; first: " << first;
}
