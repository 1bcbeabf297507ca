// SL's bounce in relight's transport (level `"probes": {"relight": true, "sl_bounce": true}`; README
// "SL's bounce in relight's transport, session 15"): pass "sl.relight_bounce"
// (shaders/sl/relight_bounce.comp: sl.glsl's slIrradianceAt at relight's surfels) against the
// closed-form irradiance of one sphere light and against sl::evaluate (the C++ reference); its flux
// onto a closed box against the SL's emitted flux; and "probes.relight" with that E_SL in the
// surfels' ΔE against relightReference, in the closed white box of tests/unit/probes/relight_fixture.hpp.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gi/sl/evaluate.hpp"
#include "engine/gi/sl/intensity_words.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/math/sampling.hpp"
#include "shade_selftest.hpp"
#include "tests/unit/probes/relight_fixture.hpp"

using namespace bounce;
using namespace bounce::gi::sl;

namespace {

constexpr int kOrder = 4;
constexpr double kY00 = 0.28209479177387814;  // Y_00 = 1/(2√π)
constexpr double kPi = 3.14159265358979324;
// GLSL fp32 against sl::evaluate's double, relative to Σ|L̃||Ṽ| (shade_gpu_test.cpp's bound).
constexpr double kTolerance = 2e-3;
// The cap's irradiance in sl.glsl / evaluate.cpp is its order-3 projection (Â_3 = 0): at normal
// incidence on a small cap, Σ_l Â_l (2l+1)/(4π) = (π + 2π + 5π/4)/(4π) = 1.0625 times the exact
// clamped cosine's 1, so one SL's E sits up to 6.25 % above L π sin²θ (and the box's total above Φ).
constexpr double kCapTruncation = 1.0625;

struct SurfelCase {  // relight.comp's Surfel (std430: 3 vec4)
  glm::vec4 position, normal, albedo;
};

struct Sls {
  std::vector<Light> lights;          // sl::evaluate's
  std::vector<ShadedSphere> shaded;   // pass 2's
  std::vector<glm::vec3> intensity;   // 16 per SL, fp16-exact (pass 1 stores fp16 pairs)
};

// An SL at c, radius r, object `object`, rotated by `rot`; `raw` its L^c (16 coefficients, local frame).
void addSl(Sls& s, glm::vec3 c, float r, int object, const glm::mat3& rot, const std::array<glm::vec3, 16>& raw) {
  const auto stored = unpackIntensity(packIntensity(raw));
  Light l;
  l.sphere = {glm::dvec3(c), double(r)};
  l.rotation = glm::dmat3(rot);
  l.object = object;
  for (int k = 0; k < 16; ++k) {
    l.intensity.push_back(glm::dvec3(stored[std::size_t(k)]));
    s.intensity.push_back(stored[std::size_t(k)]);
  }
  s.lights.push_back(l);
  s.shaded.push_back({c, r, rot, std::uint32_t(object)});
}

// A uniform emitter: only L_00, so its exitant radiance is L = c_0 Y_00 in every direction.
std::array<glm::vec3, 16> uniformSh(glm::vec3 c0) {
  std::array<glm::vec3, 16> raw{};
  raw[0] = c0;
  return raw;
}

std::vector<glm::vec3> onDevice(gpu::Context& ctx, const Sls& s, std::span<const SurfelCase> surfels, Blocking blocking) {
  ShadeData data(ctx, kOrder);
  data.setSpheres(s.shaded);
  gpu::Buffer intensity(ctx, {kIntensityBlockBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::Upload,
                              "sl.test.intensity"});
  std::memset(intensity.mapped(), 0, intensity.size());
  for (std::size_t i = 0; i * 16 < s.intensity.size(); ++i) {
    const auto words = packIntensity(std::span(s.intensity).subspan(i * 16, 16));
    std::memcpy(intensity.mapped() + i * sizeof words, words.data(), sizeof words);
  }
  // Uncut (Node::enableRelightBounce specialises pass 2's cut; these SLs are all in reach anyway).
  const gpu::SpecConstants spec = ShadeData::specialization(kOrder, blocking, std::uint32_t(s.shaded.size()), 0.0f);
  const std::vector<glm::vec4> out = sltest::runShadeSelfTest<glm::vec4, SurfelCase>(
      ctx, data, intensity, "sl/relight_bounce.comp.spv", spec, surfels, true);
  std::vector<glm::vec3> e;
  for (const glm::vec4& v : out) e.emplace_back(v);
  return e;
}

std::vector<SurfelCase> boxSurfels(const gi::probes::RelightData& data) {
  std::vector<SurfelCase> out;
  for (const gi::probes::Surfel& sf : data.surfels)
    out.push_back({glm::vec4(sf.position, 1.0f), glm::vec4(sf.normal, 0.0f), glm::vec4(sf.albedo, 0.0f)});
  return out;
}

}  // namespace

// One uniform SL of radius r straight above a surfel facing it at distance d: a Lambertian sphere of
// radiance L sends E = L π sin²θ, sin θ = r/d (exact while the sphere is above the horizon), the
// irradiance of a point source of intensity Φ/(4π). The pass gives that times the order-3 cap's
// truncation (1 ≤ ratio ≤ 1.0625), with L = c_0 Y_00 read from pass 1's intensity SH.
TEST(SlRelightBounceGpu, OneSlAboveASurfelIsTheSphereLightIrradiance) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const glm::vec3 c0(2.0f, 1.0f, 0.5f);
  // Three cases in one dispatch (one pipeline to compile): each SL 50 m from the others' surfels,
  // whose light there is ≤ (0.05/50)² / sin²θ = 4e-4 of a surfel's own at grazing incidence, where
  // the order-3 clamped cosine is 0.094: below 4e-5.
  const std::array<float, 3> heights = {0.12f, 0.4f, 1.0f};
  Sls s;
  std::vector<SurfelCase> surfels;
  for (std::size_t k = 0; k < heights.size(); ++k) {
    const float x = 50.0f * float(k);
    addSl(s, {x, heights[k], -0.2f}, 0.05f, int(k), glm::mat3(1.0f), uniformSh(c0));
    surfels.push_back({glm::vec4(x, 0.0f, -0.2f, 1.0f), glm::vec4(0, 1, 0, 0), glm::vec4(0.5f)});
  }
  const std::vector<glm::vec3> e = onDevice(ctx, s, surfels, Blocking::PerSphere);
  for (std::size_t k = 0; k < heights.size(); ++k) {
    const double d = heights[k], sin2 = (0.05 / d) * (0.05 / d);
    for (int c = 0; c < 3; ++c) {
      const double exact = double(c0[c]) * kY00 * kPi * sin2;
      std::printf("d %.2f channel %d: E %.6g, L pi sin^2 %.6g, ratio %.5f\n", d, c, e[k][c], exact, e[k][c] / exact);
      EXPECT_GE(e[k][c], exact * (1.0 - 1e-4)) << "d " << d;
      EXPECT_LE(e[k][c], exact * (kCapTruncation + 1e-4)) << "d " << d;
    }
  }
}

// The box's surfels under three SLs with full SH intensities (two overlapping spheres of one object,
// one of another, rotated): the device = sl::evaluate per surfel (per-sphere; both blockings' sl.glsl
// paths are SlShadeGpu's). Then one uniform
// SL: the flux the walls take, Σ_s E_SL(s) A_s, is its emitted flux Φ = π L · 4π r² (a closed box
// takes all of it) up to the cap truncation and the surfels' sampling of the walls.
TEST(SlRelightBounceGpu, TheBoxSurfelsMatchTheReferenceAndTakeTheEmittedFlux) {
  gi::probes::relighttest::Fixture f;
  const std::vector<SurfelCase> surfels = boxSurfels(f.data);
  math::Pcg32 rng(21, 7);
  Sls s;
  for (const auto& [c, r, object] : {std::tuple{glm::vec3(-0.1f, -0.25f, 0.0f), 0.08f, 0},
                                     std::tuple{glm::vec3(0.0f, -0.2f, 0.05f), 0.07f, 0},
                                     std::tuple{glm::vec3(0.2f, 0.1f, -0.15f), 0.06f, 1}}) {
    std::array<glm::vec3, 16> raw{};
    for (int k = 0; k < 16; ++k) raw[std::size_t(k)] = k == 0 ? glm::vec3(1.5f) + rng.nextFloat3() : (rng.nextFloat3() - 0.5f) * 0.8f;
    const glm::vec3 axis = glm::normalize(glm::vec3(math::uniformSphere(rng.next2D())));
    addSl(s, c, r, object, glm::mat3(glm::rotate(glm::mat4(1.0f), 6.0f * rng.nextFloat(), axis)), raw);
  }
  for (Blocking blocking : {Blocking::PerSphere}) {
    const std::vector<glm::vec3> gpu = onDevice(f.ctx, s, surfels, blocking);
    EvalSettings es;
    es.order = kOrder;
    es.blocking = blocking;
    double worst = 0.0;
    int lit = 0;
    for (std::size_t i = 0; i < surfels.size(); ++i) {
      const Evaluation ev = evaluate(s.lights, glm::dvec3(surfels[i].position), glm::dvec3(surfels[i].normal), es);
      double scale = 1e-6;
      for (const LightTerm& t : ev.terms)
        if (!t.culled) scale += glm::length(t.average) * std::abs(t.visibility);
      lit += glm::length(ev.irradiance) > 1e-4;
      for (int c = 0; c < 3; ++c) {
        const double err = std::abs(double(gpu[i][c]) - ev.irradiance[c]);
        worst = std::max(worst, err / scale);
        ASSERT_LE(err, kTolerance * scale) << "surfel " << i << " channel " << c;
      }
    }
    std::printf("%s: worst |GPU - C++| / scale %.3g over %zu surfels (%d lit)\n",
                blocking == Blocking::PerSphere ? "per-sphere" : "per-object", worst, surfels.size(), lit);
    EXPECT_GT(lit, int(surfels.size()) * 3 / 4);
  }

  Sls one;
  const glm::vec3 c0(2.0f, 1.0f, 0.5f);
  const float r = 0.05f;
  addSl(one, {0.1f, -0.2f, 0.05f}, r, 0, glm::mat3(1.0f), uniformSh(c0));
  const std::vector<glm::vec3> e = onDevice(f.ctx, one, surfels, Blocking::PerSphere);
  for (int c = 0; c < 3; ++c) {
    double flux = 0.0;
    for (std::size_t i = 0; i < surfels.size(); ++i) flux += double(e[i][c]) * double(f.data.surfels[i].area);
    const double phi = kPi * double(c0[c]) * kY00 * 4.0 * kPi * double(r) * double(r);
    std::printf("channel %d: walls' flux %.6g, emitted %.6g, ratio %.4f\n", c, flux, phi, flux / phi);
    EXPECT_GT(flux, 0.95 * phi);
    EXPECT_LT(flux, kCapTruncation * 1.02 * phi);  // 2 %: 1024 area-stratified surfels' sampling of the walls
  }
}

// "probes.relight" with the SLs' bounce on (RelightPass::setSlBounce, E_SL from the pass above in
// its buffer) and no dynamic shadow: the first step re-emits ρ E_SL (its flux ρ Σ E A ≤ ρ × the SL's
// emitted flux, up to the cap truncation), the probes gather only the surfels' ΔL (no probe ray sees
// the SL itself: the first bounce stays pass 2's), and 3 steps = relightReference with the same E_SL.
TEST(SlRelightBounceGpu, RelightCarriesTheSlBounceAsItsReference) {
  gi::probes::relighttest::Fixture f;
  const std::vector<SurfelCase> surfels = boxSurfels(f.data);
  Sls one;
  const glm::vec3 c0(2.0f, 1.0f, 0.5f);
  const float r = 0.05f;
  addSl(one, {0.1f, -0.2f, 0.05f}, r, 0, glm::mat3(1.0f), uniformSh(c0));
  const std::vector<glm::vec3> e = onDevice(f.ctx, one, surfels, Blocking::PerSphere);
  std::vector<glm::vec4> e4;
  for (const glm::vec3& v : e) e4.emplace_back(v, 0.0f);

  gi::probes::RelightPass pass(f.ctx, f.volume, f.data, f.packed);
  pass.setLights({&f.light, 1}, *f.bvh);
  pass.setTestVisibility(f.vStatic);  // V_now = V_static: no dynamic shadow, ΔE is E_SL alone
  ASSERT_FALSE(pass.slBounceOn());    // off unless the level asks
  pass.setSlBounce(true);
  gpu::upload(f.ctx, pass.slBounce(), {reinterpret_cast<const std::uint8_t*>(e4.data()), e4.size() * sizeof(glm::vec4)});

  f.run(pass, 1, false);
  const std::vector<glm::vec3> l = f.radiance(pass);
  for (int c = 0; c < 3; ++c) {
    double reemitted = 0.0;  // π ΔL A summed: the surfels' exitant flux
    for (std::size_t i = 0; i < l.size(); ++i) reemitted += kPi * double(l[i][c]) * double(f.data.surfels[i].area);
    const double phi = kPi * double(c0[c]) * kY00 * 4.0 * kPi * double(r) * double(r);
    std::printf("channel %d: first re-emission %.6g, rho x emitted %.6g, ratio %.4f\n", c, reemitted,
                double(gi::probes::relighttest::kRho) * phi, reemitted / (double(gi::probes::relighttest::kRho) * phi));
    EXPECT_GT(reemitted, 0.0);
    EXPECT_LE(reemitted, kCapTruncation * 1.02 * double(gi::probes::relighttest::kRho) * phi);
  }
  // The second step adds the room's bounce of that re-emission: a closed box takes all of it, so its
  // flux is ρ × the first step's. More means the probe lookup at a surfel reads back light that the
  // surfels around it emitted (a planar floor cannot light itself): the SL's first bounce counted
  // again near its receivers. Measured 1.10 ρ here (0.551): the SL's bounce is a hot spot of ~0.3 m
  // under it, which 0.25 m probes at order 3 spread into the upper hemisphere of its own floor (the
  // shadow loss spread over half the floor in ProbeRelightGpu.Iterations… gives 0.49–0.50). Bound
  // 1.15 ρ: fails if the lookup starts reading more of the receivers' own light.
  f.run(pass, 1, false);
  const std::vector<glm::vec3> l2 = f.radiance(pass);
  double first = 0.0, second = 0.0;
  for (std::size_t i = 0; i < l.size(); ++i) {
    const double a = double(f.data.surfels[i].area);
    for (int c = 0; c < 3; ++c) first += a * std::abs(double(l[i][c])), second += a * std::abs(double(l2[i][c] - l[i][c]));
  }
  std::printf("second step's flux / first's %.4f (rho %.2f)\n", second / first, double(gi::probes::relighttest::kRho));
  EXPECT_GT(second, 0.0);
  EXPECT_LE(second, 1.15 * double(gi::probes::relighttest::kRho) * first);
  f.run(pass, 1, false);  // 3 steps in all
  std::vector<glm::vec3> want;
  gi::probes::relightReference(f.data, f.volume, {&f.light, 1}, f.vStatic, f.vStatic, 3, want, nullptr, e);
  const std::vector<glm::vec3> got = f.delta(pass);
  const float scale = gi::probes::relighttest::maxAbs(want);
  ASSERT_GT(scale, 0.0f);
  for (std::size_t i = 0; i < got.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[i][c], want[i][c], 1e-4f * scale) << "coefficient " << i;
  // Off: the same pass with the bounce switched off gathers nothing (V_now = V_static).
  pass.setSlBounce(false);
  pass.reset();
  f.run(pass, 1, false);
  EXPECT_EQ(gi::probes::relighttest::maxAbs(f.delta(pass)), 0.0f);
}
