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

// Signed distance (metres, in the occluder's plane) from the point where the light→p ray crosses
// that plane to the occluder square's boundary: negative inside.
float signedDistanceToOccluder(const FloorScene& s, const Occluder& o, glm::vec3 p) {
  const glm::vec3 L = s.lightPosition;
  const glm::vec3 q = L + (p - L) * ((L.y - o.centre.y) / (L.y - p.y));
  return std::max(std::abs(q.x - o.centre.x), std::abs(q.z - o.centre.z)) - o.halfSize;
}

Zone classify(const FloorScene& s, const Occluder& o, glm::vec3 p) {
  // Every checked floor point lies in the −Y face of the light's cube map (asserted below), a
  // 90° frustum: one texel spans 2·tan 45°·(distance along −Y)/resolution metres, measured in the
  // occluder's plane where the edge is rasterised.
  const float texel = 2.0f * (s.lightPosition.y - o.centre.y) / float(kShadowResolution);
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

TEST(Shadows, UmbraIsDarkAndLitFloorMatchesClosedForm) {
  const auto path = kDataDir / "plane-shadow.json";
  const scene::Level level = scene::loadLevel(path);
  const FloorScene s = readFloorScene(level);
  const Occluder o = readOccluder(level);
  const Frame frame = renderLevel(path, kWidth, kHeight);
  EXPECT_EQ(frame.passes, (std::vector<std::string>{"shadow", "gbuffer", "lighting", "tonemap"}));

  int umbra = 0, lit = 0, badUmbra = 0, badLit = 0;
  std::string firstBadUmbra, firstBadLit;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const glm::vec3 p = floorPoint(s, kWidth, kHeight, x, y).value();
      const glm::vec3 toP = p - s.lightPosition;
      ASSERT_TRUE(-toP.y >= std::max(std::abs(toP.x), std::abs(toP.z))) << "floor point outside the −Y cube face";
      const glm::vec3 a = frame.at(x, y);
      const glm::vec3 g = floorRadiance(s, p);
      switch (classify(s, o, p)) {
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
  // The scene puts the whole shadow inside the view with lit floor around it.
  EXPECT_GT(umbra, 1000);
  EXPECT_GT(lit, 2000);
  EXPECT_EQ(badUmbra, 0) << badUmbra << " of " << umbra << " umbra pixels receive light; first: " << firstBadUmbra;
  EXPECT_EQ(badLit, 0) << badLit << " of " << lit << " lit pixels differ from the closed form; first: " << firstBadLit;
}

TEST(Shadows, ShadowsOffMatchesUnshadowedClosedFormEverywhere) {
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
