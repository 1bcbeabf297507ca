// SL local lights (engine/gi/sl/local_light.hpp, §7.3): the visible fraction of a sphere light through
// SL blockers against a brute-force count of the light's cap directions that miss the blockers, and
// the degenerate receivers (inside a sphere, at the light, zero radii).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/gi/sl/local_light.hpp"
#include "engine/math/sampling.hpp"

using namespace bounce;
using namespace bounce::gi::sl;

namespace {

// The exact visible fraction of the light's cap from p: directions uniform in solid angle over the cap
// (cos uniform in [cos α, 1], azimuth uniform; 256 × 256 strata centres), each tested against every
// blocker by a ray–sphere intersection in front of the light.
double bruteForce(std::span<const Sphere> blockers, const LocalLight& light, const glm::dvec3& p) {
  const glm::dvec3 axis = glm::normalize(light.position - p);
  const double dx = glm::length(light.position - p);
  const double cosA = std::sqrt(std::max(0.0, 1.0 - (light.radius / dx) * (light.radius / dx)));
  const glm::dvec3 t = glm::normalize(std::abs(axis.x) < 0.9 ? glm::cross(axis, {1, 0, 0}) : glm::cross(axis, {0, 1, 0}));
  const glm::dvec3 b = glm::cross(axis, t);
  constexpr int kN = 256;
  int visible = 0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      const double c = 1.0 - (1.0 - cosA) * (i + 0.5) / kN, s = std::sqrt(std::max(0.0, 1.0 - c * c));
      const double phi = 2.0 * math::kPi * (j + 0.5) / kN;
      const glm::dvec3 d = c * axis + s * (std::cos(phi) * t + std::sin(phi) * b);
      bool hit = false;
      for (const Sphere& sp : blockers) {
        const glm::dvec3 oc = sp.centre - p;
        const double tc = glm::dot(oc, d), h2 = glm::dot(oc, oc) - tc * tc;
        if (tc > 0.0 && h2 < sp.radius * sp.radius && tc < dx) hit = true;
      }
      visible += hit ? 0 : 1;
    }
  return double(visible) / double(kN * kN);
}

struct Errors {
  double worst = 0.0, shadowRef = 0.0, shadowSl = 0.0;
};

// Receivers on the floor z = 0 along x ∈ [−2, 2] under one blocker between them and a sphere light.
Errors floorLine(const Sphere& blocker, const LocalLight& light, int order, LocalForm form = LocalForm::Cap) {
  Errors e;
  const std::vector<Sphere> blockers{blocker};
  for (int i = 0; i <= 80; ++i) {
    const glm::dvec3 p(-2.0 + 4.0 * i / 80.0, 0.0, 0.0);
    const double ref = bruteForce(blockers, light, p);
    const double v = localLightVisibility(blockers, light, p, {0, 0, 1}, order, 0.0, form);
    EXPECT_TRUE(std::isfinite(v));
    e.worst = std::max(e.worst, std::abs(v - ref));
    e.shadowRef += 1.0 - ref;
    e.shadowSl += 1.0 - v;
  }
  return e;
}

}  // namespace

// The brute force's own error: 256 strata per axis resolve the cap's edge to ~1/256 of the light's
// angular radius per stratum row; measured worst 7e-4.
constexpr double kCapTolerance = 3e-3;

// One sphere between a sphere light and the floor: the Cap form against the brute-force visible
// fraction of the light's cap, along a line through umbra, penumbra and light, at SH orders 3 and 4
// (Cap does not depend on it), for a large, a small and a zero-radius (point) light.
TEST(SlLocalLight, OneSphereBetweenALightAndTheFloorMatchesTheBruteForceCap) {
  const Sphere blocker{{0.2, 0.0, 1.0}, 0.3};
  for (const double radius : {0.5, 0.1, 0.0})
    for (const int order : {3, 4}) {
      const Errors e = floorLine(blocker, {{0.0, 0.0, 3.0}, radius}, order);
      std::printf("light R %.2f order %d: worst |v - v_ref| %.2e, total shadow %.3f vs %.3f\n", radius, order, e.worst,
                  e.shadowSl, e.shadowRef);
      EXPECT_LT(e.worst, radius > 0.0 ? kCapTolerance : 2e-6) << "R " << radius;  // R = 0: hard, up to kMinVisible
      EXPECT_GT(e.shadowRef, 5.0);  // the line crosses the shadow
    }
}

// Why Cap is the default: the paper's SH form (order 3–4 log ZH, hybrid exp, cap average) cannot
// hold a ~20° blocker, so most of the shadow is missing (measured: 16 % of it at orders 3 and 4).
TEST(SlLocalLight, TheShFormMissesMostOfTheShadow) {
  const Sphere blocker{{0.2, 0.0, 1.0}, 0.3};
  for (const int order : {3, 4}) {
    const Errors e = floorLine(blocker, {{0.0, 0.0, 3.0}, 0.1}, order, LocalForm::Sh);
    std::printf("SH form, order %d: worst |v - v_ref| %.3f, total shadow %.3f vs %.3f\n", order, e.worst, e.shadowSl,
                e.shadowRef);
    EXPECT_LT(e.shadowSl, 0.25 * e.shadowRef);
    EXPECT_GT(e.shadowSl, 0.0);
  }
}

// Two blockers side by side over the floor: the product of their fractions (Cap) against the true
// visible fraction, exact where their shadows on the light's cap do not overlap; the worst case here
// (both half-covering the light) stays within kTwoBlockerTolerance.
TEST(SlLocalLight, TwoBlockersMultiplyTheirFractions) {
  const std::vector<Sphere> blockers{{{-0.35, 0.0, 1.0}, 0.3}, {{0.35, 0.0, 1.0}, 0.3}};
  const LocalLight light{{0.0, 0.0, 3.0}, 0.3};
  constexpr double kTwoBlockerTolerance = 0.05;
  double worst = 0.0;
  for (int i = 0; i <= 40; ++i) {
    const glm::dvec3 p(-1.5 + 3.0 * i / 40.0, 0.1, 0.0);
    worst = std::max(worst, std::abs(localLightVisibility(blockers, light, p, {0, 0, 1}, 4) - bruteForce(blockers, light, p)));
  }
  std::printf("two blockers: worst |v - v_ref| %.4f\n", worst);
  EXPECT_LT(worst, kTwoBlockerTolerance);
}

// Degenerate receivers and sizes: finite, in [0, 1], and the rules' values.
TEST(SlLocalLight, DegenerateReceiversStayFiniteAndBounded) {
  const LocalLight light{{0.0, 0.0, 3.0}, 0.2};
  const glm::dvec3 up(0, 0, 1);
  // Receiver inside a sphere (its centre within kCullFraction of the radius: culled, so unblocked).
  EXPECT_DOUBLE_EQ(localLightVisibility(std::vector<Sphere>{{{0, 0, 0.1}, 0.5}}, light, {0, 0, 0}, up, 4), 1.0);
  // Inside but near the surface: shrunk by rule 1, finite, in [0, 1].
  for (double z : {0.3, 0.45, 0.5, 0.55}) {
    const double v = localLightVisibility(std::vector<Sphere>{{{0, 0, z}, 0.5}}, light, {0, 0, 0}, up, 4);
    EXPECT_TRUE(std::isfinite(v) && v >= 0.0 && v <= 1.0) << z;
  }
  // Zero-radius sphere: no blocker. Zero-radius light straight behind a sphere: fully blocked (hard).
  EXPECT_DOUBLE_EQ(localLightVisibility(std::vector<Sphere>{{{0, 0, 1}, 0.0}}, light, {0, 0, 0}, up, 4), 1.0);
  EXPECT_LT(localLightVisibility(std::vector<Sphere>{{{0, 0, 1}, 0.3}}, {{0, 0, 3}, 0.0}, {0, 0, 0}, up, 4), 1e-5);
  // Receiver at the light's centre, and a light inside a sphere (not blocked by it, §6.2).
  EXPECT_DOUBLE_EQ(localLightVisibility(std::vector<Sphere>{{{0, 0, 1}, 0.3}}, light, {0, 0, 3}, up, 4), 1.0);
  EXPECT_DOUBLE_EQ(localLightVisibility(std::vector<Sphere>{{{0, 0, 2.9}, 0.5}}, light, {0, 0, 0}, up, 4), 1.0);
  // Huge and tiny scales: the same configuration scaled by 1e6 and 1e-6 gives the same v.
  const double v1 = localLightVisibility(std::vector<Sphere>{{{0.2, 0, 1}, 0.3}}, light, {0.1, 0, 0}, up, 4);
  for (double k : {1e-6, 1e6}) {
    const double vk = localLightVisibility(std::vector<Sphere>{{{0.2 * k, 0, k}, 0.3 * k}}, {{0, 0, 3 * k}, 0.2 * k},
                                           {0.1 * k, 0, 0}, up, 4);
    EXPECT_NEAR(vk, v1, 1e-9) << k;
  }
}

// Continuity (the blocker weights' fades): a sphere sliding past the light's distance and into the
// light moves v by at most kStep per 1e-4 of its radius.
TEST(SlLocalLight, MovingBlockersChangeVisibilityContinuously) {
  const LocalLight light{{0.0, 0.0, 2.0}, 0.2};
  constexpr double kStep = 2e-3;
  double worst = 0.0, prev = -1.0;
  for (int i = 0; i <= 20000; ++i) {
    // From the floor's side, up past the light (through it: gap < 0 there), off-axis by 0.1.
    const Sphere s{{0.1, 0.0, 0.6 + 2.0 * i / 20000.0}, 0.2};
    const double v = localLightVisibility(std::vector<Sphere>{s}, light, {0, 0, 0}, {0, 0, 1}, 4);
    if (prev >= 0.0) worst = std::max(worst, std::abs(v - prev) / (2.0 / 20000.0 / 1e-4 / 0.2));
    prev = v;
  }
  std::printf("worst step per 1e-4 R: %.2e\n", worst);
  EXPECT_LT(worst, kStep);
}

// The shadow scale shrinks a blocker's cap to that share of its solid angle, and the union share
// weights its log: two coincident spheres with share ½ block like one.
TEST(SlLocalLight, ShadowScaleShrinksTheCapAndUnionShareCountsOverlapsOnce) {
  const LocalLight light{{0.0, 0.0, 3.0}, 0.3};
  const glm::dvec3 p(0.05, 0.0, 0.0), up(0, 0, 1);
  const std::vector<Sphere> one{{{0.0, 0.0, 1.0}, 0.3}}, two{{{0.0, 0.0, 1.0}, 0.3}, {{0.0, 0.0, 1.0}, 0.3}};
  const double v1 = localLightVisibility(one, light, p, up, 4);
  const std::vector<double> half{0.5, 0.5};
  EXPECT_NEAR(localLightVisibility(two, light, p, up, 4, 0.0, LocalForm::Cap, sh::LogKind::Windowed, half), v1, 1e-12);
  // Scale 0.25 of the solid angle = a sphere of about half the angular radius: against the brute force.
  const std::vector<double> quarter{0.25};
  const double dist = glm::length(one[0].centre - p), b = std::asin(0.3 / dist);
  const double bs = std::acos(1.0 - 0.25 * (1.0 - std::cos(b)));
  const std::vector<Sphere> smaller{{one[0].centre, dist * std::sin(bs)}};
  EXPECT_NEAR(localLightVisibility(one, light, p, up, 4, 0.0, LocalForm::Cap, sh::LogKind::Windowed, {}, quarter),
              bruteForce(smaller, light, p), kCapTolerance);
}
