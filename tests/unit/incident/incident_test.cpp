// The incident-light service's CPU face (engine/gi/incident, incident.glsl compiled as C++):
// lights projected into SH against Monte-Carlo projections and closed forms, visibility by ray
// tests (shadowed = zero), the service's sum, and the hard cases (light at / inside the receiver).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/gi/incident/incident.hpp"
#include "engine/math/sampling.hpp"
#include "tests/support/box_mesh.hpp"
#include "engine/math/sh.hpp"
#include "engine/math/sh_exp.hpp"
#include "tests/support/point_light.hpp"

namespace bounce::gi::incident {
namespace {

constexpr double kPi = 3.14159265358979323846;

using bounce::testing::pointLight;  // tests/support/point_light.hpp

render::LightGpu spotLight(glm::vec3 position, glm::vec3 direction, glm::vec3 intensity, float outer, float inner) {
  render::LightGpu l = pointLight(position, intensity);
  l.positionType.w = float(render::LightType::Spot);
  l.directionRange = glm::vec4(glm::normalize(direction), 0.0f);
  l.cone = glm::vec4(std::cos(outer), std::cos(inner), 0.0f, 0.0f);
  return l;
}

render::LightGpu directionalLight(glm::vec3 direction, glm::vec3 irradiance) {
  render::LightGpu l = pointLight(glm::vec3(0.0f), irradiance);
  l.positionType.w = float(render::LightType::Directional);
  l.directionRange = glm::vec4(glm::normalize(direction), 0.0f);
  return l;
}

// Monte-Carlo projection of a uniform cap of radiance L (per channel) and half-angle β about unit
// axis w: n×n stratified samples uniform in the cap (pdf 1/Ω), c_i ≈ (Ω/N) Σ L Y_i(ω_k). Exact
// sampling of the integrand's support, so the only error is the variation of Y_i over a stratum.
std::vector<glm::dvec3> mcCap(glm::dvec3 w, double cosBeta, glm::dvec3 L, int n) {
  const glm::dvec3 t = std::abs(w.x) < 0.9 ? glm::normalize(glm::cross(w, glm::dvec3(1, 0, 0)))
                                           : glm::normalize(glm::cross(w, glm::dvec3(0, 1, 0)));
  const glm::dvec3 b = glm::cross(w, t);
  math::Pcg32 rng(3, 5);
  const auto u = math::stratified2D(n, rng);
  const double omega = 2.0 * kPi * (1.0 - cosBeta);
  std::vector<glm::dvec3> c(9, glm::dvec3(0.0));
  for (const auto& s : u) {
    const double ct = 1.0 - s.x * (1.0 - cosBeta), st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
    const double phi = 2.0 * kPi * s.y;
    const glm::dvec3 d = ct * w + st * (std::cos(phi) * t + std::sin(phi) * b);
    const auto y = sh::evalBasis<double>(3, d);
    for (int i = 0; i < 9; ++i) c[i] += L * y[i];
  }
  for (auto& ci : c) ci *= omega / double(u.size());
  return c;
}

double maxAbsDiff(const RadianceSH& a, const std::vector<glm::dvec3>& b) {
  double m = 0.0;
  for (int i = 0; i < 9; ++i)
    for (int ch = 0; ch < 3; ++ch) m = std::max(m, std::abs(double(a[i][ch]) - b[i][ch]));
  return m;
}

// A point light seen from a point is a delta: its SH must equal the MC projection of a small
// emitting sphere of the same radiant intensity (radius ε = 0.01 d, radiance I/(πε²)), whose cap
// differs from the delta by O(β²) = 1e-4 relative. 32² stratified samples over the tiny cap: MC
// error ≪ 1e-4. Tolerance 1e-3 of E·Y_00's scale (E = I/d² ≈ 1.6): a wrong sign, axis or
// 1/d² would be off by O(1).
TEST(Incident, PointLightAtAPointMatchesMonteCarloOfASmallEmitter) {
  const glm::vec3 p(0.1f, -0.2f, 0.3f), lamp(0.6f, 0.5f, -0.4f);
  const glm::vec3 I(0.25f, 0.23f, 0.2f);
  const double d = glm::length(glm::dvec3(lamp - p));
  RadianceSH sh{};
  addLight(pointLight(lamp, I), p, 0.0f, 1.0f, sh);
  const double eps = 0.01 * d, sinBeta = eps / d, cosBeta = std::sqrt(1.0 - sinBeta * sinBeta);
  const glm::dvec3 Ls = glm::dvec3(I) / (kPi * eps * eps);
  const auto mc = mcCap(glm::normalize(glm::dvec3(lamp - p)), cosBeta, Ls, 32);
  const double scale = double(I.r) / (d * d);
  EXPECT_LT(maxAbsDiff(sh, mc), 1e-3 * scale);
  // The constant term exactly: L_00 = E·Y_00 with E = I/d².
  EXPECT_NEAR(sh[0].r, float(scale * sh::constants::kY00), 1e-6 * scale);
}

// The zonal factors s_l of incidentAddCap against an independent closed form: engine/math's
// capVisibilityZonal g (the ZH of a blocker's complement) gives the cap indicator's ZH
// (√(4π) − g_0, −g_1, −g_2), rotated by sh::rotateZonal, times L = e/Ω. Same function, two
// derivations: agreement to float rounding (1e-5 relative).
TEST(Incident, CapMatchesClosedFormZonalHarmonicsRotated) {
  for (const double alpha : {0.05, 0.4, 0.9, 1.3, kPi / 2}) {
    const glm::dvec3 w = glm::normalize(glm::dvec3(-0.3, 0.8, 0.5));
    const glm::dvec3 e(2.0, 1.0, 0.5);
    RadianceSH sh{};
    addCap(glm::vec3(w), float(std::cos(alpha)), glm::vec3(e), sh);
    const auto g = sh::capVisibilityZonal(alpha, 3);
    const std::vector<double> indicator = {std::sqrt(4.0 * kPi) - g[0], -g[1], -g[2]};
    const auto rotated = sh::rotateZonal<double>(indicator, w);
    const double omega = 2.0 * kPi * (1.0 - std::cos(alpha));
    for (int i = 0; i < 9; ++i)
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(sh[i][ch], rotated[i] * e[ch] / omega, 1e-5 * e[ch]) << "alpha " << alpha << " i " << i;
  }
}

// A receiver of radius R near a lamp (the DNRT case: a prop under the ceiling lamp): the light is a
// uniform cap of half-angle asin(R/d) — against its MC projection (64² stratified samples in the
// cap: error ~1e-4 of the scale) — whose flux E_cap·πR² is what the sphere intercepts, I·Ω.
// That flux is checked by an independent MC: rays from the lamp in 512² stratified uniform
// directions, the fraction hitting the sphere times 4π I (error ~1/N^(3/4) of the ≈ 10 % hit
// fraction, < 0.2 %; tolerance 1 %).
TEST(Incident, CapForANearLampMatchesMonteCarloAndCarriesTheInterceptedFlux) {
  const glm::vec3 o(0.0f, 0.42f, 0.0f), lamp(0.0f, 0.5f, 0.0f);
  const float R = 0.06f;
  const glm::vec3 I(0.25f, 0.23f, 0.2f);
  RadianceSH sh{};
  addLight(pointLight(lamp, I), o, R, 1.0f, sh);
  const double d = glm::length(glm::dvec3(lamp - o));
  const double cosA = std::sqrt(1.0 - (R / d) * (R / d));
  EXPECT_NEAR(capCosine(R, float(d)), cosA, 1e-6);
  const double omega = 2.0 * kPi * (1.0 - cosA);
  const glm::dvec3 flux = glm::dvec3(I) * omega;  // W per channel intercepted by the sphere
  const glm::dvec3 eCap = flux / (kPi * double(R) * R);
  const auto mc = mcCap(glm::dvec3(0, 1, 0), cosA, eCap / omega, 64);
  EXPECT_LT(maxAbsDiff(sh, mc), 1e-3 * eCap.r);

  // Independent flux: shoot from the lamp, count hits on the sphere.
  math::Pcg32 rng(9, 1);
  const auto u = math::stratified2D(512, rng);
  std::size_t hits = 0;
  const glm::dvec3 c = glm::dvec3(o) - glm::dvec3(lamp);
  for (const auto& s : u) {
    const glm::dvec3 dir = math::uniformSphere(s);
    const double tc = glm::dot(c, dir);
    if (tc > 0.0 && glm::dot(c, c) - tc * tc <= double(R) * R) ++hits;
  }
  const double mcFlux = 4.0 * kPi * double(I.r) * double(hits) / double(u.size());
  const double shFlux = double(sh[0].r) / sh::constants::kY00 * kPi * double(R) * R;  // E_cap·πR²
  EXPECT_NEAR(shFlux, mcFlux, 0.01 * mcFlux);
  // Band 1 keeps the centre's directional term exactly: E_cap·s_1 = I/d².
  EXPECT_NEAR(sh[2].r, 0.0f, 1e-6f);
  EXPECT_NEAR(double(sh[1].r), double(I.r) / (d * d) * sh::constants::kY1, 1e-4 * double(I.r) / (d * d));
}

TEST(Incident, DirectionalIsADeltaFromAgainstItsDirectionAndSpotRespectsItsCone) {
  RadianceSH sh{};
  const glm::vec3 dir = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  addLight(directionalLight(dir, glm::vec3(3.0f)), glm::vec3(5.0f), 1.0f, 0.5f, sh);
  const auto y = sh::evalBasis<double>(3, glm::dvec3(-dir));
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(sh[i].g, 1.5 * y[i], 1e-5) << i;  // E·v·Y_i(−dir), no cap

  // Spot pointing down from (0, 1, 0): a receiver straight below gets the point light's SH, one
  // outside the outer cone gets nothing.
  const auto spot = spotLight(glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(1.0f), 0.5f, 0.3f);
  RadianceSH inside{}, asPoint{}, outside{};
  addLight(spot, glm::vec3(0.0f), 0.1f, 1.0f, inside);
  addLight(pointLight(glm::vec3(0, 1, 0), glm::vec3(1.0f)), glm::vec3(0.0f), 0.1f, 1.0f, asPoint);
  addLight(spot, glm::vec3(2.0f, 0.0f, 0.0f), 0.1f, 1.0f, outside);
  for (int i = 0; i < 9; ++i) {
    EXPECT_NEAR(inside[i].r, asPoint[i].r, 1e-6f) << i;
    EXPECT_EQ(outside[i], glm::vec3(0.0f)) << i;
  }
}

// Hard cases: the lamp at the receiver's centre, inside its sphere, on a point receiver, and a
// huge intensity: finite, and bounded by the on-the-sphere value 2I/R² (the light counted as on
// the sphere's surface: a hemisphere cap).
TEST(Incident, LightAtOrInsideTheReceiverStaysFiniteAndBounded) {
  const glm::vec3 I(1.0f);
  const float R = 0.1f;
  for (const glm::vec3 offset : {glm::vec3(0.0f), glm::vec3(0.0f, 0.02f, 0.0f), glm::vec3(0.0f, 0.0999f, 0.0f)}) {
    RadianceSH sh{};
    addLight(pointLight(offset, I), glm::vec3(0.0f), R, 1.0f, sh);
    for (const auto& c : sh) EXPECT_TRUE(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b));
    const double bound = 2.0 / (R * R) * sh::constants::kY00;
    EXPECT_LE(sh[0].r, bound * (1.0 + 1e-5));
    EXPECT_GT(sh[0].r, 0.0f);
  }
  // Continuous across the sphere's surface: just inside vs just outside.
  RadianceSH in{}, outside{};
  addLight(pointLight(glm::vec3(0, R * 0.999f, 0), I), glm::vec3(0.0f), R, 1.0f, in);
  addLight(pointLight(glm::vec3(0, R * 1.001f, 0), I), glm::vec3(0.0f), R, 1.0f, outside);
  EXPECT_NEAR(in[0].r, outside[0].r, 0.05 * outside[0].r);
  // A point receiver on the light: finite (lights.glsl's d² ≥ 1e-12).
  RadianceSH onLight{};
  addLight(pointLight(glm::vec3(0.0f), glm::vec3(1e6f)), glm::vec3(0.0f), 0.0f, 1.0f, onLight);
  for (const auto& c : onLight) EXPECT_TRUE(std::isfinite(c.r));
}

ref::SceneDesc boxScene(glm::vec3 lo, glm::vec3 hi) { return bounce::testing::boxMesh(lo, hi); }

// Shadowed = zero: a slab between the receiver and the lamp blocks every ray (the service adds
// nothing); no slab: fully visible; a slab covering half the disc of ray origins: a fraction
// strictly between (the 9 rays: the centre and 8 around it, 3 or 4 of the ring blocked).
TEST(Incident, SceneVisibilityShadowedIsZeroUnblockedIsOneHalfIsBetween) {
  const auto lamp = pointLight(glm::vec3(0, 1, 0), glm::vec3(1.0f));
  const SceneVisibility blocked(boxScene(glm::vec3(-1, 0.4f, -1), glm::vec3(1, 0.5f, 1)));
  const SceneVisibility open(boxScene(glm::vec3(3, 3, 3), glm::vec3(4, 4, 4)));
  const SceneVisibility half(boxScene(glm::vec3(0.01f, 0.4f, -1), glm::vec3(1, 0.5f, 1)));
  EXPECT_EQ(blocked.visible(lamp, glm::vec3(0.0f), 0.1f), 0.0f);
  EXPECT_EQ(blocked.visible(lamp, glm::vec3(0.0f), 0.0f), 0.0f);
  EXPECT_EQ(open.visible(lamp, glm::vec3(0.0f), 0.1f), 1.0f);
  const float v = half.visible(lamp, glm::vec3(0.0f), 0.1f);
  EXPECT_GT(v, 0.3f);
  EXPECT_LT(v, 0.8f);
  const auto sun = directionalLight(glm::vec3(0, -1, 0), glm::vec3(2.0f));
  EXPECT_EQ(blocked.visible(sun, glm::vec3(0.0f), 0.1f), 0.0f);
  EXPECT_EQ(open.visible(sun, glm::vec3(0.0f), 0.1f), 1.0f);

  Service service;
  service.setVisibility(&blocked);
  const std::vector<render::LightGpu> lights = {lamp, sun};
  const RadianceSH none = service.lightsSH(glm::vec3(0.0f), 0.1f, lights);
  for (const auto& c : none) EXPECT_EQ(c, glm::vec3(0.0f));
}

// The service's sum: indirect + each light × its visibility, and the indirect alone when every
// light is blocked.
TEST(Incident, ServiceAddsIndirectAndLights) {
  const ConstantEnvironment env(glm::vec3(0.5f));
  const auto lamp = pointLight(glm::vec3(0, 1, 0), glm::vec3(1.0f));
  const std::vector<render::LightGpu> lights = {lamp};
  Service service;
  service.setIndirect(&env);
  const RadianceSH all = service.radianceSH(glm::vec3(0.0f), 0.2f, lights);
  RadianceSH lampSh{};
  addLight(lamp, glm::vec3(0.0f), 0.2f, 1.0f, lampSh);
  const RadianceSH envSh0 = env.radianceSH(glm::vec3(0.0f));
  for (int i = 0; i < 9; ++i) EXPECT_EQ(all[i], lampSh[i] + envSh0[i]) << i;
  // Windowed: the lamp's SH Hanning-windowed per band (1, 3/4, 1/4), the indirect light as it is.
  const RadianceSH windowed = service.radianceSH(glm::vec3(0.0f), 0.2f, lights, kHanningWindow);
  for (int i = 0; i < 9; ++i) {
    const float h = i == 0 ? 1.0f : i < 4 ? 0.75f : 0.25f;
    EXPECT_EQ(windowed[i], lampSh[i] * h + envSh0[i]) << i;
  }
  const SceneVisibility blocked(boxScene(glm::vec3(-1, 0.4f, -1), glm::vec3(1, 0.5f, 1)));
  service.setVisibility(&blocked);
  const RadianceSH indirectOnly = service.radianceSH(glm::vec3(0.0f), 0.2f, lights);
  const RadianceSH envSh = env.radianceSH(glm::vec3(0.0f));
  for (int i = 0; i < 9; ++i) EXPECT_EQ(indirectOnly[i], envSh[i]) << i;
}

// lightIrradiance, the one CPU copy of lights.glsl's irradiance (VLM's phase-1 mirror uses it):
// inverse square, the glTF range window, the spot ramp squared, directional as is.
TEST(Incident, LightIrradianceIsLightsGlslsInverseSquareRangeAndCone) {
  render::LightGpu point{};
  point.positionType = glm::vec4(0.0f, 2.0f, 0.0f, float(render::LightType::Point));
  point.radiance = glm::vec4(4.0f, 8.0f, 12.0f, 0.0f);  // intensity, W/sr
  glm::vec3 toLight;
  float dist = 0.0f;
  EXPECT_EQ(lightIrradiance(point, glm::vec3(0.0f), toLight, dist), glm::vec3(1.0f, 2.0f, 3.0f));
  EXPECT_EQ(toLight, glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(dist, 2.0f);
  point.directionRange.w = 4.0f;  // range 4 m at d = 2: window (1 − (1/2)⁴)² = (15/16)²
  EXPECT_NEAR(lightIrradiance(point, glm::vec3(0.0f), toLight, dist).x, (15.0f / 16.0f) * (15.0f / 16.0f), 1e-6f);

  render::LightGpu spot = point;
  spot.positionType.w = float(render::LightType::Spot);
  spot.directionRange = glm::vec4(0.0f, -1.0f, 0.0f, 0.0f);
  spot.cone = glm::vec4(0.5f, 1.0f, 0.0f, 0.0f);  // cos outer, cos inner
  // At (2, 0, 0) the light is seen at cos = 2/√8 = 0.707 from its axis: t = (0.707 − 0.5) / 0.5.
  const float t = (std::sqrt(0.5f) - 0.5f) / 0.5f;
  EXPECT_NEAR(lightIrradiance(spot, glm::vec3(2.0f, 0.0f, 0.0f), toLight, dist).x, 4.0f / 8.0f * t * t, 1e-6f);

  render::LightGpu sun{};
  sun.positionType.w = float(render::LightType::Directional);
  sun.directionRange = glm::vec4(0.0f, -1.0f, 0.0f, 0.0f);
  sun.radiance = glm::vec4(3.0f);
  EXPECT_EQ(lightIrradiance(sun, glm::vec3(5.0f), toLight, dist), glm::vec3(3.0f));
  EXPECT_EQ(toLight, glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_EQ(dist, 1e30f);
}


// One copy of the light math: the techniques' CPU face (lightIrradiance) and the path tracer's
// (ref::incidentIrradiance on its own light type) both compile lights.glsl's incidentIrradiance,
// so on the same light they agree bit for bit — direction, distance and irradiance — for every
// kind, with and without a range window, inside and outside a spot's cone, on the light itself.
TEST(Incident, PathTracerAndTechniquesShareLightsGlslsIrradianceBitForBit) {
  const glm::vec3 receivers[] = {{0.0f, 0.0f, 0.0f}, {0.3f, -0.2f, 0.1f}, {2.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f}};
  int compared = 0;
  for (const render::LightType type : {render::LightType::Point, render::LightType::Spot, render::LightType::Directional})
    for (const float range : {0.0f, 1.5f}) {
      render::LightGpu l{};
      l.positionType = glm::vec4(0.0f, 2.0f, 0.0f, float(type));
      l.directionRange = glm::vec4(glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f)), range);
      l.radiance = glm::vec4(4.0f, 8.0f, 12.0f, 0.0f);
      l.cone = glm::vec4(0.8f, 0.95f, 0.0f, 0.0f);
      const ref::RefLight r = refLight(l);  // the member-by-member copy the techniques use
      for (const glm::vec3& p : receivers) {
        glm::vec3 toA, toB;
        float distA = 0.0f, distB = 0.0f;
        const glm::vec3 a = lightIrradiance(l, p, toA, distA), b = ref::incidentIrradiance(r, p, toB, distB);
        EXPECT_EQ(a, b) << int(type) << " range " << range << " at " << p.x << "," << p.y << "," << p.z;
        EXPECT_EQ(toA, toB);
        EXPECT_EQ(distA, distB);
        ++compared;
      }
    }
  EXPECT_EQ(compared, 24);
}
}  // namespace
}  // namespace bounce::gi::incident
