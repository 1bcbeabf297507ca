// SL pass 2's per-receiver evaluation in GLSL (shaders/sl/sl.glsl, run per receiver by
// shaders/sl/evaluate_selftest.comp) against sl::evaluate (the double-precision reference), at SH
// orders 3 and 4 with per-sphere and per-object blocking: receivers on a plane under two objects
// (intersecting spheres within each), receivers inside a sphere, on its surface and under a sphere
// crossing the tangent plane; and the GPU output's continuity as a sphere slides through the
// receiver's tangent plane and over the receiver.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gi/sl/evaluate.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/testing.hpp"
#include "shade_selftest.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_exp.hpp"

using namespace bounce;
using namespace bounce::gi::sl;

namespace {

// fp32 against double: the GLSL and C++ run the same steps; the differences are float rounding in
// the log tables' interpolation, the rotated ZH and the exps (an OL exp's e^{f_0 Y_00} amplifies a
// relative error of f_0 by |f_0 Y_00| ≤ ~10 for the dense clusters here). Measured worst: see the
// report; the bound is relative to Σ_i |L̃_i| |Ṽ_i| (the terms' scale, so cancellation between terms
// cannot hide an error) plus 1e-6 absolute.
constexpr double kTolerance = 2e-3;

struct Receiver {
  glm::vec4 p, n;
};

struct Scene {
  std::vector<Light> lights;  // sl::evaluate's
  std::vector<ShadedSphere> shaded;
  std::vector<glm::vec3> intensity;  // 16 per SL, fp16-exact (the pass reads them as fp16 pairs)
};

void addLight(Scene& s, glm::vec3 c, float r, int object, math::Pcg32& rng, int order) {
  Light l;
  l.sphere = {glm::dvec3(c), double(r)};
  const glm::vec3 axis = glm::normalize(glm::vec3(math::uniformSphere(rng.next2D())));
  const glm::mat3 rot = glm::mat3(glm::rotate(glm::mat4(1.0f), 6.0f * rng.nextFloat(), axis));
  l.rotation = glm::dmat3(rot);
  l.object = object;
  ShadedSphere g{c, r, rot, std::uint32_t(object)};
  std::array<glm::vec3, 16> raw{};
  for (int k = 0; k < 16; ++k) {
    const glm::vec3 v = k == 0 ? glm::vec3(1.5f) + rng.nextFloat3() : (rng.nextFloat3() - 0.5f) * 0.8f;
    if (k < order * order) raw[std::size_t(k)] = v;
  }
  // Rounded to fp16 as pass 1 stores them, so the reference sees the values the shader reads.
  const auto stored = unpackIntensity(packIntensity(raw));
  for (int k = 0; k < 16; ++k) {
    if (k < order * order) l.intensity.push_back(glm::dvec3(stored[std::size_t(k)]));
    s.intensity.push_back(stored[std::size_t(k)]);
  }
  s.lights.push_back(l);
  s.shaded.push_back(g);
}

// Two objects above the plane z = 0: a chain of four overlapping spheres and a cluster of three.
Scene twoObjects(int order) {
  math::Pcg32 rng(11, 3);
  Scene s;
  addLight(s, {-0.3f, 0.0f, 0.6f}, 0.25f, 0, rng, order);
  addLight(s, {-0.1f, 0.1f, 0.75f}, 0.2f, 0, rng, order);
  addLight(s, {0.1f, 0.15f, 0.9f}, 0.18f, 0, rng, order);
  addLight(s, {0.3f, 0.1f, 1.05f}, 0.15f, 0, rng, order);
  addLight(s, {0.5f, -0.6f, 0.4f}, 0.2f, 1, rng, order);
  addLight(s, {0.7f, -0.5f, 0.45f}, 0.15f, 1, rng, order);
  addLight(s, {0.55f, -0.3f, 0.7f}, 0.12f, 1, rng, order);
  return s;
}

// A dense cluster of sixteen large overlapping spheres, each its own object (so every closer one
// blocks), within 30° of the zenith of receivers near the origin: the summed logs exceed the OL
// table's ‖f̂‖ = 4, so the hybrid exp halves and squares (slSquare).
Scene column(int order) {
  math::Pcg32 rng(12, 5);
  Scene s;
  for (int i = 0; i < 16; ++i) {
    const float a = 0.5236f * std::sqrt((float(i) + 0.5f) / 16.0f), phi = 2.39996f * float(i);
    const glm::vec3 d(std::sin(a) * std::cos(phi), std::sin(a) * std::sin(phi), std::cos(a));
    addLight(s, d * (0.35f + 0.01f * float(i)), 0.28f, i, rng, order);
  }
  return s;
}

std::vector<glm::vec3> runShader(gpu::Context& ctx, const Scene& s, std::span<const Receiver> receivers, int order,
                                 Blocking blocking, float influence = 0.0f, bool singleObject = false) {
  ShadeData data(ctx, order);
  data.setSpheres(s.shaded);
  gpu::Buffer intensity(ctx, {kIntensityBlockBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::Upload, "sl.test.intensity"});
  std::memset(intensity.mapped(), 0, intensity.size());
  for (std::size_t i = 0; i * 16 < s.intensity.size(); ++i) {
    const auto words = packIntensity(std::span(s.intensity).subspan(i * 16, 16));
    std::memcpy(intensity.mapped() + i * sizeof words, words.data(), sizeof words);
  }
  gpu::SpecConstants spec = ShadeData::specialization(order, blocking, std::uint32_t(s.shaded.size()), influence);
  spec.push_back(singleObject ? 1u : 0u);  // evaluate_selftest.comp kSingleObject
  const std::vector<glm::vec4> out =
      sltest::runShadeSelfTest<glm::vec4, Receiver>(ctx, data, intensity, "sl/evaluate_selftest.comp.spv", spec, receivers);
  std::vector<glm::vec3> e;
  for (const glm::vec4& v : out) e.emplace_back(v);
  return e;
}

std::vector<Receiver> planeAndHardReceivers(const Scene& s) {
  std::vector<Receiver> r;
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x)
      r.push_back({glm::vec4(-1.0f + 2.0f * x / 11.0f, -1.0f + 2.0f * y / 11.0f, 0.0f, 0.0f), glm::vec4(0, 0, 1, 0)});
  // Inside SL 0 (t = 0.8, 0.6 and 0.3 of its radius: shrunk, shrunk, culled), on its surface, and
  // on tilted planes through its centre's neighbourhood (the sphere crosses the tangent plane).
  const glm::vec3 c(s.shaded[0].centre);
  const float r0 = s.shaded[0].radius;
  const glm::vec3 toward = glm::normalize(glm::vec3(0.3f, -0.2f, -1.0f));
  for (float t : {0.8f, 0.6f, 0.3f, 1.0f, 1.02f})
    for (const glm::vec3& n : {glm::vec3(0, 0, 1), glm::normalize(glm::vec3(1, 0, 1)), -toward})
      r.push_back({glm::vec4(c + toward * (t * r0), 0.0f), glm::vec4(n, 0.0f)});
  return r;
}

// Receivers where the reference itself jumps — the hybrid exp switches between OL and halving-and-
// squaring at ‖f̂‖ = 4, which is not continuous (Ren et al.'s hybrid), and fp32 may switch on the
// other side — are skipped when `skipped` is given: those whose C++ value moves by more than the
// tolerance when p moves ±1e-4 m. The caller bounds how many.
void expectMatches(const Scene& s, std::span<const Receiver> receivers, const std::vector<glm::vec3>& gpu, int order,
                   Blocking blocking, double* worst, int* skipped = nullptr, double influence = 0.0) {
  EvalSettings es;
  es.order = order;
  es.blocking = blocking;
  es.influence = influence;
  int lit = 0;
  for (std::size_t i = 0; i < receivers.size(); ++i) {
    const glm::dvec3 p(receivers[i].p), n(receivers[i].n);
    const Evaluation ev = evaluate(s.lights, p, n, es);
    double scale = 1e-6;
    for (const LightTerm& t : ev.terms)
      if (!t.culled) scale += glm::length(t.average) * std::abs(t.visibility);
    lit += glm::length(ev.irradiance) > 1e-3;
    if (skipped) {
      const glm::dvec3 dp(1e-4, 0.0, 0.0);
      const glm::dvec3 jump = evaluate(s.lights, p + dp, n, es).irradiance - evaluate(s.lights, p - dp, n, es).irradiance;
      if (std::max({std::abs(jump.x), std::abs(jump.y), std::abs(jump.z)}) > kTolerance * scale) {
        ++*skipped;
        continue;
      }
    }
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(gpu[i][c])) << "receiver " << i;
      const double err = std::abs(double(gpu[i][c]) - ev.irradiance[c]);
      *worst = std::max(*worst, err / scale);
      EXPECT_LE(err, kTolerance * scale) << "receiver " << i << " channel " << c << ": GPU " << gpu[i][c] << " C++ "
                                        << ev.irradiance[c];
    }
  }
  EXPECT_GT(lit, int(receivers.size()) / 2);  // the fixture lights most receivers
}

}  // namespace

TEST(SlShadeGpu, DenseClusterNeedsSquaringsAndStillMatches) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  for (int order : {3, 4}) {
    const Scene s = column(order);
    // The receiver under the column sees all ten: their summed log is beyond the OL range.
    const sh::ExpTables& t = sh::expTables(order);
    std::vector<double> sum(std::size_t(order * order), 0.0);
    for (const Light& l : s.lights) {
      const double d = glm::length(l.sphere.centre);
      const auto g = t.logBlocker(std::asin(l.sphere.radius / d), l.sphere.centre / d);
      for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += g[k];
    }
    int squarings = 0;
    sh::expHybrid(sum, &squarings);
    double norm = 0.0;
    for (std::size_t k = 1; k < sum.size(); ++k) norm += sum[k] * sum[k];
    ASSERT_GT(squarings, 0) << "order " << order << " |f^| " << std::sqrt(norm) << ": the fixture does not reach the squarings";
    std::vector<Receiver> r;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        r.push_back({glm::vec4(-0.2f + 0.4f * x / 7.0f, -0.2f + 0.4f * y / 7.0f, 0.0f, 0.0f), glm::vec4(0, 0, 1, 0)});
    for (Blocking blocking : {Blocking::PerSphere, Blocking::PerObject}) {
      double worst = 0.0;
      int skipped = 0;
      expectMatches(s, r, runShader(ctx, s, r, order, blocking), order, blocking, &worst, &skipped);
      // The hybrid exp is continuous since its blend (sh_exp.hpp): no receiver sits on a jump any more
      // (before it, 1 of 64 did).
      EXPECT_EQ(skipped, 0) << "receivers at the hybrid exp's switch";
      std::printf("cluster, order %d %s (%d squarings at the centre): worst |GPU - C++| / scale = %.3g, %d of %zu receivers "
                  "at the reference's OL/squaring switch skipped\n",
                  order, blocking == Blocking::PerObject ? "per-object" : "per-sphere", squarings, worst, skipped, r.size());
    }
  }
}

TEST(SlShadeGpu, GlslEqualsEvaluateForOrdersAndBlockings) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  for (int order : {3, 4})
    for (Blocking blocking : {Blocking::PerSphere, Blocking::PerObject}) {
      SCOPED_TRACE("order " + std::to_string(order) + (blocking == Blocking::PerObject ? " per-object" : " per-sphere"));
      const Scene s = twoObjects(order);
      const std::vector<Receiver> r = planeAndHardReceivers(s);
      double worst = 0.0;
      expectMatches(s, r, runShader(ctx, s, r, order, blocking), order, blocking, &worst);
      std::printf("order %d %s: worst |GPU - C++| / scale = %.3g\n", order,
                  blocking == Blocking::PerObject ? "per-object" : "per-sphere", worst);
    }
}

// Per-object blocking draws the tiles whose SLs are all one object's with sl.frag's kSingleObject
// variant, which writes exp(0) instead of forming the closer objects' exp: on one object's SLs (the
// chain of twoObjects, receivers on the plane, inside, on and crossing its spheres) it gives the
// general variant's floats exactly, so the two kinds of tile meet without a seam.
TEST(SlShadeGpu, SingleObjectVariantGivesTheSameFloatsOnOneObject) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  for (int order : {3, 4}) {
    Scene s = twoObjects(order);
    s.lights.resize(4);  // object 0 only
    s.shaded.resize(4);
    s.intensity.resize(4 * 16);
    const std::vector<Receiver> r = planeAndHardReceivers(s);
    const auto general = runShader(ctx, s, r, order, Blocking::PerObject);
    const auto single = runShader(ctx, s, r, order, Blocking::PerObject, 0.0f, true);
    int lit = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      EXPECT_EQ(general[i], single[i]) << "order " << order << " receiver " << i;
      lit += general[i].x > 1e-3f;
    }
    EXPECT_GT(lit, int(r.size()) / 2);
  }
}

// One sphere of radius R slides down through a receiver's tangent plane and on through the receiver
// (centre from 1.5 R above to 1.5 R below, through p), steps of 1e-4 R: the GPU output stays finite
// and changes by at most kStep of its largest value per step (a jump — a sphere popping in or out,
// a discontinuous rule — would move it by a sizeable fraction), and equals the C++ reference along
// the way.
TEST(SlShadeGpu, SphereSlidingThroughTheTangentPlaneIsContinuous) {
  constexpr double kStep = 2e-3;
  gpu::Context& ctx = gpu::testkit::sharedContext();
  math::Pcg32 rng(4);
  Scene s;
  const float R = 0.3f;
  addLight(s, glm::vec3(0.0f), R, 0, rng, 4);
  const int steps = 30000;
  std::vector<Receiver> r;
  // Moving the sphere by +h is moving the receiver by −h (one sphere, UBO fixed): p = (0.05 R, 0, −h).
  for (int i = 0; i <= steps; ++i) {
    const float h = R * (1.5f - 3.0f * float(i) / float(steps));
    r.push_back({glm::vec4(0.05f * R, 0.0f, -h, 0.0f), glm::vec4(glm::normalize(glm::vec3(0.2f, 0.0f, 1.0f)), 0.0f)});
  }
  const std::vector<glm::vec3> e = runShader(ctx, s, r, 4, Blocking::PerSphere);
  double peak = 0.0;
  for (const glm::vec3& v : e) {
    ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
    peak = std::max(peak, double(glm::length(v)));
  }
  ASSERT_GT(peak, 1e-2);
  double worstStep = 0.0;
  for (int i = 1; i <= steps; ++i) worstStep = std::max(worstStep, double(glm::length(e[std::size_t(i)] - e[std::size_t(i - 1)])));
  std::printf("sliding sphere: peak %.4g, worst step %.3g of peak\n", peak, worstStep / peak);
  EXPECT_LE(worstStep, kStep * peak);
  std::vector<Receiver> some;
  std::vector<glm::vec3> someGpu;
  for (int i = 0; i <= steps; i += 500) {
    some.push_back(r[std::size_t(i)]);
    someGpu.push_back(e[std::size_t(i)]);
  }
  double worst = 0.0;
  EvalSettings es;
  for (std::size_t i = 0; i < some.size(); ++i) {
    const Evaluation ev = evaluate(s.lights, glm::dvec3(some[i].p), glm::dvec3(some[i].n), es);
    double scale = 1e-6;
    for (const LightTerm& t : ev.terms) scale += glm::length(t.average) * std::abs(t.visibility);
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(double(someGpu[i][c]) - ev.irradiance[c]) / scale);
      EXPECT_NEAR(someGpu[i][c], ev.irradiance[c], kTolerance * scale) << "step " << i * 500;
    }
  }
  std::printf("sliding sphere: worst |GPU - C++| / scale = %.3g\n", worst);
}

// Rule 0 (influence F = 4 radii, small enough that most of the fixture's SLs fade or vanish at some
// receivers): GLSL = C++ with it on, it changes the result (so it is exercised), and a receiver
// moving away from a lone sphere through the fade (t = 1.5 … 5 radii, steps of 1e-4 R) sees a
// continuous output that reaches exactly 0 beyond F.
TEST(SlShadeGpu, InfluenceCullingMatchesAndFadesContinuously) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const Scene s = twoObjects(4);
  const std::vector<Receiver> r = planeAndHardReceivers(s);
  const std::vector<glm::vec3> on = runShader(ctx, s, r, 4, Blocking::PerSphere, 4.0f);
  double worst = 0.0;
  expectMatches(s, r, on, 4, Blocking::PerSphere, &worst, nullptr, 4.0);
  const std::vector<glm::vec3> off = runShader(ctx, s, r, 4, Blocking::PerSphere, 0.0f);
  int changed = 0;
  for (std::size_t i = 0; i < r.size(); ++i) changed += glm::length(on[i] - off[i]) > 1e-2f * glm::length(off[i]);
  EXPECT_GT(changed, int(r.size()) / 4);
  std::printf("influence 4: worst |GPU - C++| / scale = %.3g, %d of %zu receivers changed by > 1%%\n", worst, changed, r.size());

  math::Pcg32 rng(9);
  Scene one;
  const float R = 0.2f;
  addLight(one, glm::vec3(0.0f, 0.0f, 0.0f), R, 0, rng, 4);
  std::vector<Receiver> path;
  const int steps = 35000;
  for (int i = 0; i <= steps; ++i) {
    const float t = 1.5f + 3.5f * float(i) / float(steps);
    path.push_back({glm::vec4(0.0f, -0.6f * t * R, -0.8f * t * R, 0.0f), glm::vec4(0.0f, 0.6f, 0.8f, 0.0f)});
  }
  const std::vector<glm::vec3> e = runShader(ctx, one, path, 4, Blocking::PerSphere, 4.0f);
  double peak = 0.0, worstStep = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    peak = std::max(peak, double(glm::length(e[i])));
    if (i > 0) worstStep = std::max(worstStep, double(glm::length(e[i] - e[i - 1])));
  }
  ASSERT_GT(peak, 1e-2);
  EXPECT_LE(worstStep, 2e-3 * peak);
  EXPECT_EQ(glm::length(e.back()), 0.0f);  // t = 5 > F: nothing
  std::printf("influence fade: worst step %.3g of peak\n", worstStep / peak);
}

// The scale and size hard cases through the GPU path: the two-object scene scaled by 1e-6
// and 1e6 (lengths only: every angle, so E, is unchanged) gives the scale-1 result within the
// tolerance, and = C++ at that scale; a zero-radius SL adds nothing, and a huge one (radius 1e3 m,
// its surface 0.5 m above the plane) keeps every output finite and = C++.
TEST(SlShadeGpu, ScalesAndZeroAndHugeSpheres) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const Scene base = twoObjects(4);
  const std::vector<Receiver> r = planeAndHardReceivers(base);
  const std::vector<glm::vec3> e1 = runShader(ctx, base, r, 4, Blocking::PerSphere);
  for (double scale : {1e-6, 1e6}) {
    Scene s = base;
    for (Light& l : s.lights) l.sphere = {l.sphere.centre * scale, l.sphere.radius * scale};
    for (ShadedSphere& g : s.shaded) g.centre *= float(scale), g.radius *= float(scale);
    std::vector<Receiver> rs = r;
    for (Receiver& x : rs) x.p *= float(scale);
    const std::vector<glm::vec3> es = runShader(ctx, s, rs, 4, Blocking::PerSphere);
    double worst = 0.0;
    expectMatches(s, rs, es, 4, Blocking::PerSphere, &worst);
    double peak = 0.0, diff = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      peak = std::max(peak, double(glm::length(e1[i])));
      diff = std::max(diff, double(glm::length(es[i] - e1[i])));
    }
    EXPECT_LE(diff, kTolerance * peak) << "scale " << scale;
    std::printf("scale %g: worst |GPU - C++| / scale %.3g, worst |E(scaled) - E(1)| %.3g of the peak\n", scale, worst,
                diff / peak);
  }
  math::Pcg32 rng(31);
  Scene zero = base;
  addLight(zero, {0.0f, 0.0f, 0.3f}, 0.0f, 7, rng, 4);
  const std::vector<glm::vec3> ez = runShader(ctx, zero, r, 4, Blocking::PerSphere);
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_EQ(ez[i], e1[i]) << "receiver " << i;
  Scene huge = base;
  addLight(huge, {0.0f, 0.0f, 1000.5f}, 1000.0f, 8, rng, 4);
  const std::vector<glm::vec3> eh = runShader(ctx, huge, r, 4, Blocking::PerSphere);
  double worst = 0.0;
  expectMatches(huge, r, eh, 4, Blocking::PerSphere, &worst);
  std::printf("huge sphere: worst |GPU - C++| / scale %.3g\n", worst);
}
