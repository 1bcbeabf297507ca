// Direct lighting against closed forms (pbrt-style analytic scenes): a large white Lambertian
// floor (ρ = 0.8) seen by a camera looking straight down, lit by one punctual light. EVERY pixel's
// linear radiance read back from the HDR target must equal
//   point:        L = ρ/π · I·h/d³
//   spot:         L = ρ/π · I·h/d³ · s²    (lights.glsl cone falloff)
//   directional:  L = ρ/π · E·cosθ
// where the surface point of each pixel is reconstructed in the test from the pixel centre through
// the camera of the level file (not from the renderer's matrices). The light sits off the image
// centre, so a mirrored or flipped image fails too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <sstream>

#include "engine/gpu/testing.hpp"
#include "tests/unit/render/analytic.hpp"

using namespace bounce;
using namespace bounce::rtest;

namespace {

// Non-square on purpose: an aspect-ratio mistake moves every pixel's surface point.
constexpr std::uint32_t kWidth = 96, kHeight = 64;

// The HDR target is RGBA16F: 11 significant bits. Vulkan lets the float→half conversion round
// to nearest (error ≤ 2^-11 ≈ 4.9e-4 relative) or towards zero (≤ 2^-10 ≈ 9.8e-4); lavapipe
// truncates, and its errors here are all negative and reach 9.6e-4. Everything else is float32
// (depth reconstruction through invViewProj, ~1e-6 relative). 1.5e-3 is the truncation bound
// with 50 % to spare; a wrong π, falloff exponent, cosine or albedo is off by far more.
constexpr float kRelativeTolerance = 1.5e-3f;
// An absolute allowance, as a fraction of the image's peak radiance, for pixels near zero: at the
// spot's outer cone the falloff s² has slope up to 2/(cos θ_inner − cos θ_outer) ≈ 20 per unit of
// cos α, and the float32 position error (~1e-6) becomes ~2e-5 of the unfalloffed value there; half
// floats below 6.1e-5 are subnormal (absolute step 6e-8). 1e-4 of the peak covers both.
constexpr float kAbsoluteOfPeak = 1e-4f;

struct Comparison {
  int failures = 0;
  int pixels = 0;
  float peak = 0.0f;
  float maxRelative = 0.0f;  // over pixels above 1% of the peak (reported, not asserted)
  std::string worst;
};

// Compares every pixel of `frame` with the closed form of `scene`; pixels that miss the floor
// are not expected (the floor fills the view in every plane level).
Comparison compareWithClosedForm(const Frame& frame, const FloorScene& scene) {
  Comparison c;
  std::vector<glm::vec3> expected(std::size_t(frame.width) * frame.height);
  for (std::uint32_t y = 0; y < frame.height; ++y)
    for (std::uint32_t x = 0; x < frame.width; ++x) {
      auto p = floorPoint(scene, frame.width, frame.height, x, y);
      EXPECT_TRUE(p && std::abs(p->x) < 2.0f && std::abs(p->z) < 2.0f) << "pixel " << x << "," << y << " misses the floor";
      expected[std::size_t(y) * frame.width + x] = p ? floorRadiance(scene, *p) : glm::vec3(0.0f);
    }
  for (const auto& e : expected) c.peak = std::max({c.peak, e.r, e.g, e.b});
  float worstExcess = 0.0f;
  for (std::uint32_t y = 0; y < frame.height; ++y)
    for (std::uint32_t x = 0; x < frame.width; ++x) {
      const glm::vec3 g = expected[std::size_t(y) * frame.width + x];
      const glm::vec3 a = frame.at(x, y);
      ++c.pixels;
      bool bad = false;
      for (int ch = 0; ch < 3; ++ch) {
        const float err = std::abs(a[ch] - g[ch]);
        const float bound = kRelativeTolerance * g[ch] + kAbsoluteOfPeak * c.peak;
        if (!(err <= bound)) bad = true;  // also catches NaN
        if (g[ch] > 0.01f * c.peak) c.maxRelative = std::max(c.maxRelative, err / g[ch]);
        if (err / bound > worstExcess) {
          worstExcess = err / bound;
          std::ostringstream s;
          s << "pixel (" << x << "," << y << ") channel " << ch << ": rendered " << a[ch] << ", closed form " << g[ch];
          c.worst = s.str();
        }
      }
      c.failures += bad;
    }
  return c;
}

void expectMatches(const std::string& levelFile) {
  const auto path = kDataDir / levelFile;
  const FloorScene scene = readFloorScene(scene::loadLevel(path));
  const Frame frame = renderLevel(path, kWidth, kHeight);
  const Comparison c = compareWithClosedForm(frame, scene);
  EXPECT_EQ(c.failures, 0) << c.failures << " of " << c.pixels << " pixels outside the bound; worst " << c.worst;
  EXPECT_GT(c.peak, 0.01f) << "the scene is too dark to test anything";
  ::testing::Test::RecordProperty("max_relative_error", std::to_string(c.maxRelative));
  EXPECT_EQ(frame.passes, (std::vector<std::string>{"gbuffer", "lighting", "tonemap"}));
}

}  // namespace

TEST(DirectLight, PointLightMatchesInverseCubeLawEverywhere) {
  // Self-check of the scene: the closed form varies a lot over the image, so a constant or a
  // wrong falloff exponent cannot pass by accident.
  const FloorScene s = readFloorScene(scene::loadLevel(kDataDir / "plane-point.json"));
  const float centre = floorRadiance(s, *floorPoint(s, kWidth, kHeight, kWidth / 2, kHeight / 2)).r;
  const float corner = floorRadiance(s, *floorPoint(s, kWidth, kHeight, kWidth - 1, kHeight - 1)).r;
  EXPECT_GT(centre / corner, 2.0f);
  expectMatches("plane-point.json");
}

TEST(DirectLight, SpotLightMatchesConeFalloffEverywhere) {
  // The image must contain the full cone, the falloff ring and the dark outside.
  const FloorScene s = readFloorScene(scene::loadLevel(kDataDir / "plane-spot.json"));
  int inner = 0, ring = 0, outside = 0;
  const glm::vec3 plainPoint = s.light.color * s.light.intensity;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      glm::vec3 p = *floorPoint(s, kWidth, kHeight, x, y);
      glm::vec3 v = s.lightPosition - p;
      float d = glm::length(v);
      float ratio = irradiance(s, p).r / (plainPoint.r * v.y / (d * d * d));
      (ratio >= 1.0f ? inner : ratio > 0.0f ? ring : outside) += 1;
    }
  EXPECT_GT(inner, 100);
  EXPECT_GT(ring, 100);
  EXPECT_GT(outside, 100);
  expectMatches("plane-spot.json");
}

TEST(DirectLight, DirectionalLightMatchesCosineLawEverywhere) {
  const FloorScene s = readFloorScene(scene::loadLevel(kDataDir / "plane-directional.json"));
  // The level tilts the light 30° from vertical: E·cos 30°.
  EXPECT_NEAR(glm::dot(glm::vec3(0, 1, 0), -s.lightDirection), std::cos(glm::radians(30.0f)), 1e-6f);
  expectMatches("plane-directional.json");
}

// Without `direct` the lights contribute nothing (the floor is not emissive: every pixel is black)
// and no shadow pass runs, even though `shadows` is named: shadows only modulate direct light.
TEST(DirectLight, NoDirectEffectMeansNoLightAndNoShadowPass) {
  const Frame frame = renderLevel(kDataDir / "plane-point.json", 48, 32, std::vector<std::string>{"shadows"});
  float peak = 0.0f;
  for (float v : frame.rgb) peak = std::max(peak, std::abs(v));
  EXPECT_EQ(peak, 0.0f);
  EXPECT_EQ(frame.passes, (std::vector<std::string>{"gbuffer", "lighting", "tonemap"}));
}
