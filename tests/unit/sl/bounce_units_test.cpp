// Issue 13, "the SL bounce is ~10× too strong on the characters level": the whole bounce chain in
// C++ — pass 1 (sl::intensityReference: L_p = E(n)/π per sample, Eq. 10 over the baked Voronoi cells,
// Eq. 11 with the baked albedo SH) and pass 2 (sl::evaluate: Eq. 14–18 and the cap's Ṽ) — against
// a brute-force integral over the surface of a real Lambertian sphere. A sphere mesh is the one object
// an SL represents exactly (every direction from the centre has a sample on the surface, at distance
// R, with normal ω), so any factor that is off (irradiance vs radiance, 1/π, the 4π/N cell weights,
// the albedo product, the direction the intensity is looked up in) shows as a ratio ≠ 1.
//
// The GPU faces of both passes are compared to these C++ functions by SlIntensityGpu.* and
// SlShadeGpu.* (same math, ≤ 2e-3), so a units error in them would be shared by the C++ checked here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "engine/gi/incident/incident.hpp"
#include "engine/gi/sl/bake.hpp"
#include "engine/gi/sl/evaluate.hpp"
#include "engine/gi/sl/intensity.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_eval.hpp"
#include "tests/unit/dnrt/test_meshes.hpp"

using namespace bounce;
using namespace bounce::gi::sl;

namespace {

constexpr double kPi = math::kPi;

BakeSettings oneSphere() {
  BakeSettings s;
  s.spheres = 1;
  s.order = 4;
  s.directions = 92;      // the paper's count (§8.6)
  s.samplesPerAxis = 48;  // N = 2304 projection directions
  s.surfaceSamples = 1024;
  s.iterations = 6;
  return s;
}

// E at receiver (p, n) from the Lambertian sphere (centre c, radius R) whose surface point x with
// outward normal m leaves radiance L(x, m) (W/(m²·sr)): E = ∫ L cos θ_p cos θ_x / |x − p|² dA over the
// part of the sphere p sees (a convex body: x is seen iff m·(p − x) > 0) above p's tangent plane.
template <class Radiance>
glm::dvec3 bruteForceIrradiance(const glm::dvec3& c, double R, const glm::dvec3& p, const glm::dvec3& n,
                                Radiance radiance) {
  constexpr int kN = 200000;
  const double dA = 4.0 * kPi * R * R / kN;
  glm::dvec3 e(0.0);
  for (int i = 0; i < kN; ++i) {
    const glm::dvec3 m = math::fibonacciSphere(i, kN);
    const glm::dvec3 x = c + R * m;
    const glm::dvec3 d = x - p;
    const double r2 = glm::dot(d, d), r = std::sqrt(r2);
    const double cosX = -glm::dot(m, d) / r, cosP = glm::dot(n, d) / r;
    if (cosX <= 0.0 || cosP <= 0.0) continue;
    e += radiance(x, m) * cosX * cosP / r2 * dA;
  }
  return e;
}

struct Receiver {
  glm::dvec3 p, n;
  const char* name;
};

}  // namespace

// A sphere of albedo ρ under uniform radiance L_env from every direction: every surface point gets
// E = π L_env and re-emits ρ E / π = ρ L_env. Pass 1 must give the SL exactly that uniform intensity
// (DC = ρ L_env √(4π)); pass 2 must give a receiver E = ρ L_env · π sin²θ cos β (the sphere light's
// form factor × π — Ṽ's own tolerance, SlEvaluate.OneSphereMatchesFormFactor, is 8 %). And the Voronoi
// cells' weights 4π/N · N_j sum to the whole sphere of directions, 4π (basis DC sum = √(4π)).
TEST(SlBounceUnits, UniformlyLitSphereReemitsRhoEOverPi) {
  const glm::vec3 rho(0.5f, 0.25f, 1.0f);
  const auto mesh = gi::dnrt::testing::sphere(glm::vec3(0.0f), 1.0f, rho, 48);
  const SphereSet set = bake(mesh, oneSphere());
  ASSERT_EQ(set.spheres.size(), 1u);
  // The raw chain: without the bake's fitted bounce scale (bounce_scale.hpp; ~1 for a sphere).
  SlSphere s = set.spheres[0];
  s.bounceScale = 1.0f;
  ASSERT_EQ(s.samples.size(), 92u);  // every direction has its sample: no cell left dark

  double cellSum = 0.0;  // Σ_j (4π/N) Σ_{k∈cell j} Y_00 = (4π/N) N / √(4π) = √(4π)
  for (const auto& x : s.samples) cellSum += x.basis[0];
  EXPECT_NEAR(cellSum, std::sqrt(4.0 * kPi), 1e-5);

  const glm::vec3 lEnv(2.0f);
  const gi::incident::ConstantEnvironment env(lEnv);
  PosedSphere posed{s.centre, s.radius, glm::mat3(1.0f)};
  const auto indirect = env.radianceSH(s.centre);
  // L_p of every sample = E/π = L_env exactly (order-3 SH hold a constant exactly).
  for (const auto& x : s.samples) {
    const glm::vec3 l = sampleReflection(x, s, posed, {}, indirect);
    ASSERT_NEAR(l.x, lEnv.x, 1e-4f);
  }
  Light light;
  light.sphere = {glm::dvec3(s.centre), double(s.radius)};
  light.intensity = intensityReference(s, 4, posed, {}, indirect);
  const double sqrt4Pi = std::sqrt(4.0 * kPi);
  for (int ch = 0; ch < 3; ++ch)
    EXPECT_NEAR(light.intensity[0][ch], double(rho[ch] * lEnv[ch]) * sqrt4Pi, 2e-3 * double(rho[ch] * lEnv[ch]) * sqrt4Pi);

  double worst = 0.0;
  for (double d : {1.5, 2.0, 4.0})
    for (double beta : {0.0, 0.5}) {
      const glm::dvec3 n(std::sin(beta), 0.0, std::cos(beta));
      // Receiver below the sphere, its normal tilted by β from the direction to the centre.
      const glm::dvec3 up(0.0, 0.0, 1.0);
      const glm::dvec3 q = light.sphere.centre - d * up;
      const auto e = evaluate(std::span<const Light>(&light, 1), q, n, {});
      const double theta = std::asin(light.sphere.radius / d);
      const glm::dvec3 exact = glm::dvec3(rho) * double(lEnv.x) * kPi * std::sin(theta) * std::sin(theta) * std::cos(beta);
      const glm::dvec3 brute = bruteForceIrradiance(light.sphere.centre, light.sphere.radius, q, n,
                                                    [&](const glm::dvec3&, const glm::dvec3&) { return glm::dvec3(rho) * double(lEnv.x); });
      for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(brute[ch], exact[ch], 2e-3 * exact[ch]);  // the brute force itself
        worst = std::max(worst, std::abs(e.irradiance[ch] / exact[ch] - 1.0));
        EXPECT_NEAR(e.irradiance[ch], exact[ch], 0.08 * exact[ch]) << "d " << d << " β " << beta << " ch " << ch;
      }
    }
  std::printf("uniformly lit sphere: SL irradiance / closed form − 1, worst %.4f\n", worst);
}

// The same sphere lit by one directional light from +z only (irradiance E0 on a surface facing it):
// the top re-emits ρ E(m)/π, the bottom nothing. A receiver under the sphere facing up (a floor under
// a character) sees the dark half, one above facing down the lit half, one beside it both. The SL
// must match the brute force of the real sphere's reflected light at each — a flipped lookup
// direction or a missing/extra π would put the lit half's light on the floor, or scale all three.
// L(x) in the brute force is sampleReflection at x (the same order-3 irradiance SH of the light),
// so what is compared is Eq. 10–11 + Eq. 14–18, not the light's SH truncation.
TEST(SlBounceUnits, DirectionallyLitSphereLightsTheRightSide) {
  const glm::vec3 rho(0.8f);
  const auto mesh = gi::dnrt::testing::sphere(glm::vec3(0.0f), 1.0f, rho, 48);
  const SphereSet set = bake(mesh, oneSphere());
  // The raw chain: without the bake's fitted bounce scale (bounce_scale.hpp; ~1 for a sphere).
  SlSphere s = set.spheres[0];
  s.bounceScale = 1.0f;
  render::LightGpu sun{};
  sun.positionType = glm::vec4(0.0f, 0.0f, 0.0f, float(render::LightType::Directional));
  sun.directionRange = glm::vec4(0.0f, 0.0f, -1.0f, 0.0f);  // travelling down: lights the top
  sun.radiance = glm::vec4(3.0f, 3.0f, 3.0f, 0.0f);
  sun.shadow = glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f);
  const std::vector<render::LightGpu> lights{sun};
  const gi::incident::RadianceSH none{};
  glm::vec3 toLight;
  float dist = 0.0f;
  const double e0 = gi::incident::lightIrradiance(sun, glm::vec3(0.0f, 0.0f, 2.0f), toLight, dist).x;
  ASSERT_GT(e0, 0.0);

  // Rotate the SL to check the §7.1 frame too: the posed sphere is the rest one turned 90° about x
  // (local +z → world −y), with the light's direction turned the same way, so the world picture is
  // the rest picture turned.
  for (bool turned : {false, true}) {
    const glm::dmat3 rot = turned ? glm::dmat3(1, 0, 0, 0, 0, -1, 0, 1, 0) : glm::dmat3(1.0);
    std::vector<render::LightGpu> worldLights = lights;
    worldLights[0].directionRange = glm::vec4(glm::vec3(rot * glm::dvec3(0, 0, -1)), 0.0f);
    PosedSphere posed{s.centre, s.radius, glm::mat3(rot)};
    Light light;
    light.sphere = {glm::dvec3(s.centre), double(s.radius)};
    light.rotation = rot;
    light.intensity = intensityReference(s, 4, posed, worldLights, none);
    auto radiance = [&](const glm::dvec3& x, const glm::dvec3& m) {
      SurfaceSample smp;
      smp.position = glm::vec3(glm::transpose(rot) * x);
      smp.normal = glm::vec3(glm::transpose(rot) * m);
      // sampleReflection is the white-Lambertian L_p (Eq. 3); the surface's albedo enters at Eq. 11.
      return glm::dvec3(rho) * glm::dvec3(sampleReflection(smp, s, posed, worldLights, none));
    };
    const Receiver receivers[] = {
        {{0, 0, -2}, {0, 0, 1}, "below, facing up"},
        {{0, 0, 2}, {0, 0, -1}, "above, facing down"},
        {{2, 0, 0}, {-1, 0, 0}, "beside, facing it"},
        {{0, 0, -1.3}, {0, 0, 1}, "just below"},
        {{0, 0, 1.3}, {0, 0, -1}, "just above"},
    };
    double slAbove = 0.0, slBelow = 0.0, worst = 0.0;
    for (const Receiver& r : receivers) {
      const glm::dvec3 p = rot * r.p, n = rot * r.n;
      const double brute = bruteForceIrradiance(light.sphere.centre, light.sphere.radius, p, n, radiance).x;
      const double sl = evaluate(std::span<const Light>(&light, 1), p, n, {}).irradiance.x;
      if (r.p.z == 2.0) slAbove = sl;
      if (r.p.z == -2.0) slBelow = sl;
      // ρ E0/π · π sin²θ: what a uniformly lit sphere at this distance would give, the error's scale.
      const double scale = 0.8 * e0 / glm::dot(r.p, r.p);
      std::printf("%s%s: SL %.5f, brute force %.5f, difference / scale %.4f\n", turned ? "turned, " : "", r.name, sl,
                  brute, (sl - brute) / scale);
      worst = std::max(worst, std::abs(sl - brute) / scale);
      // Measured worst 0.042 of the scale (Eq. 16 weighs the sphere's points by cos γ without the
      // 1/distance² of the true form factor, and order-4 truncation); a units error would be ≥ 2.
      EXPECT_NEAR(sl, brute, 0.06 * scale) << r.name << (turned ? " (turned)" : "");
    }
    std::printf("worst |SL − brute force| / scale %.4f\n", worst);
    // The dark half faces the receiver below: it gets a small fraction of what the one above gets.
    EXPECT_LT(slBelow, 0.05 * slAbove);
    EXPECT_GT(slAbove, 0.0);
  }
}

// Why SL's bounce is ~10× the reference's on the floor around the characters' feet (README "SL"):
// not a units error (the two tests above) but pass 1's input. A sphere (albedo 0.6, R = 0.3 m)
// resting on a floor (albedo 0.5) under a point lamp 3 m above it. Pass 1 is fed what a probe at the
// sphere's centre holds: the floor as the STATIC scene has it, lit everywhere (probes are baked
// without the dynamic objects, §5.1's departure in intensity.hpp). The real floor is dark in the
// sphere's umbra — exactly the floor the sphere's underside faces, and whose bounce comes back to
// the floor around it. Brute force (floor radiance ρ_f E_lamp V/π, V = 0 in the umbra, integrated
// over the floor for each point of the sphere, then over the sphere for each floor receiver):
// the SL must match the unshadowed truth (it models what it is given), and the shadowed truth —
// what the path-traced reference sees — is less. Measured: by a factor 1.4–1.7 only (receivers
// outside the umbra see the sphere's side, which faces the lit floor beyond it), so this explains
// a part of the excess, not the factor ~10.
TEST(SlBounceUnits, StaticProbeLightOverLightsTheFloorAroundAnObjectByLessThan2x) {
  constexpr double kH = 3.0, kI = 6.0, kRhoFloor = 0.5, kR = 0.3;
  const glm::vec3 rhoS(0.6f);
  const glm::dvec3 c(0.0, 0.0, kR + 0.005);
  const glm::dvec3 lamp(0.0, 0.0, kH);
  auto inUmbra = [&](const glm::dvec3& q) {  // the lamp → q segment passes through the sphere
    const glm::dvec3 d = lamp - q;
    const double t = std::clamp(glm::dot(c - q, d) / glm::dot(d, d), 0.0, 1.0);
    return glm::length(q + t * d - c) < kR;
  };
  auto floorRadiance = [&](const glm::dvec3& q, bool shadowed) {
    const glm::dvec3 d = lamp - q;
    const double r2 = glm::dot(d, d);
    const double e = kI * (d.z / std::sqrt(r2)) / r2;  // point lamp: I cos / r²  (W/m²)
    return shadowed && inUmbra(q) ? 0.0 : kRhoFloor * e / kPi;
  };
  // Floor quadrature: polar rings, geometric in radius (the contact point needs fine rings).
  struct FloorPoint {
    glm::dvec3 q;
    double area;
  };
  std::vector<FloorPoint> floor;
  {
    constexpr int kRings = 240, kSectors = 96;
    const double r0 = 1e-3, r1 = 40.0, g = std::pow(r1 / r0, 1.0 / kRings);
    for (int i = 0; i < kRings; ++i) {
      const double a = r0 * std::pow(g, i), b = a * g, rm = 0.5 * (a + b);
      for (int k = 0; k < kSectors; ++k) {
        const double phi = 2.0 * kPi * (k + 0.5) / kSectors;
        floor.push_back({{rm * std::cos(phi), rm * std::sin(phi), 0.0}, 0.5 * (b * b - a * a) * 2.0 * kPi / kSectors});
      }
    }
  }
  // Radiance a point x of the real sphere (outward normal m) reflects: ρ_s E(x)/π, E from the floor.
  auto sphereRadiance = [&](const glm::dvec3& x, const glm::dvec3& m, bool shadowed) {
    double e = 0.0;
    for (const FloorPoint& f : floor) {
      const glm::dvec3 d = f.q - x;
      const double r2 = glm::dot(d, d), r = std::sqrt(r2);
      const double cx = glm::dot(m, d) / r, cf = -d.z / r;
      if (cx > 0.0 && cf > 0.0) e += floorRadiance(f.q, shadowed) * cx * cf / r2 * f.area;
    }
    return double(rhoS.x) * e / kPi;
  };

  // The probe at the centre: the static floor's radiance in the lower hemisphere, order 3.
  gi::incident::RadianceSH probe{};
  {
    constexpr int kN = 20000;
    for (int i = 0; i < kN; ++i) {
      const glm::dvec3 w = math::fibonacciSphere(i, kN);
      if (w.z >= 0.0) continue;
      const double l = floorRadiance(c + (-c.z / w.z) * w, false);
      const auto y = sh::evalBasis<double>(3, w);
      for (int k = 0; k < 9; ++k) probe[std::size_t(k)] += glm::vec3(float(l * y[std::size_t(k)] * 4.0 * kPi / kN));
    }
  }
  const auto mesh = gi::dnrt::testing::sphere(glm::vec3(c), float(kR), rhoS, 48);
  const SphereSet set = bake(mesh, oneSphere());
  // The raw chain: without the bake's fitted bounce scale (bounce_scale.hpp; ~1 for a sphere).
  SlSphere s = set.spheres[0];
  s.bounceScale = 1.0f;
  const PosedSphere posed{s.centre, s.radius, glm::mat3(1.0f)};
  Light light;
  light.sphere = {glm::dvec3(s.centre), double(s.radius)};
  light.intensity = intensityReference(s, 4, posed, {}, probe);

  // Precompute the real sphere's reflected radiance, both ways, on a point set.
  constexpr int kS = 1500;
  std::vector<double> lOpen(kS), lShadowed(kS);
  for (int i = 0; i < kS; ++i) {
    const glm::dvec3 m = math::fibonacciSphere(i, kS);
    lOpen[std::size_t(i)] = sphereRadiance(c + kR * m, m, false);
    lShadowed[std::size_t(i)] = sphereRadiance(c + kR * m, m, true);
  }
  auto truth = [&](const glm::dvec3& p, const std::vector<double>& l) {
    double e = 0.0;
    const double dA = 4.0 * kPi * kR * kR / kS;
    for (int i = 0; i < kS; ++i) {
      const glm::dvec3 m = math::fibonacciSphere(i, kS);
      const glm::dvec3 d = c + kR * m - p;
      const double r2 = glm::dot(d, d), r = std::sqrt(r2);
      const double cx = -glm::dot(m, d) / r, cp = d.z / r;
      if (cx > 0.0 && cp > 0.0) e += l[std::size_t(i)] * cx * cp / r2 * dA;
    }
    return e;
  };
  for (double x : {0.35, 0.5, 0.8, 1.5}) {
    const glm::dvec3 p(x, 0.0, 0.0), n(0.0, 0.0, 1.0);
    const double sl = evaluate(std::span<const Light>(&light, 1), p, n, {}).irradiance.x;
    const double open = truth(p, lOpen), shadowed = truth(p, lShadowed);
    std::printf("floor receiver %.2f m from the contact point: SL %.5f, truth with the static (lit) floor %.5f, "
                "truth with the sphere's shadow on the floor %.5f: SL / real = %.1f\n",
                x, sl, open, shadowed, sl / shadowed);
    // The SL models what pass 1 is given: measured within 18 % of the unshadowed truth up to 0.8 m
    // (order-3 probe, order-4 SL), 46 % at 1.5 m where the receiver sees the sphere's side at grazing.
    EXPECT_NEAR(sl, open, (x > 1.0 ? 0.5 : 0.25) * open) << x;
    // The umbra's share: measured SL / real 1.4–1.7 — a factor < 2, NOT the ~10 the characters show.
    EXPECT_GT(sl, 1.2 * shadowed) << x;
    EXPECT_LT(sl, 2.5 * shadowed) << x;
  }
}
