// SL pass 2's edge-aware upsample (shaders/common/upsample.glsl via upsample_selftest.comp, the code
// upsample.frag runs) against its C++ reference gi::upsampleTaps / gi::upsampleBlend (double): the
// taps of every pixel of odd-sized images at half and quarter resolution exactly, the blend within a
// bound derived from fp32 rounding and GLSL's exp/pow precision, and no light across a depth
// discontinuity or a crease (exact zeros on the GPU).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "engine/gi/resolution.hpp"
#include "engine/gi/upsample.hpp"
#include "engine/gpu/testing.hpp"
#include "tests/support/compute_selftest.hpp"

using namespace bounce;
using namespace bounce::gi;

namespace {

struct Case {  // upsample_selftest.comp Case (std430)
  glm::ivec4 pixel{0};  // x, y, step
  glm::ivec4 sizes{0};  // reduced xy, full zw
  glm::vec4 p{0.0f}, n{0.0f}, f{0.0f};
  glm::vec4 pq[4]{}, nq[4]{}, e[4]{};
};
struct Result {  // upsample_selftest.comp Result
  glm::vec4 e;
  glm::ivec4 j[2], q[2];
  glm::vec4 f;
};
static_assert(sizeof(Case) == 272 && sizeof(Result) == 96);

std::vector<Result> run(const std::vector<Case>& cases) {
  return testgpu::runComputeSelfTest<Result>(gpu::testkit::sharedContext(), "sl/upsample_selftest.comp.spv",
                                             std::span<const Case>(cases));
}

std::array<UpsampleSample, 4> samplesOf(const Case& c) {
  std::array<UpsampleSample, 4> s;
  for (int k = 0; k < 4; ++k)
    s[std::size_t(k)] = {glm::dvec3(c.pq[k]), glm::dvec3(c.nq[k]), c.pq[k].w > 0.5f, glm::dvec3(c.e[k])};
  return s;
}
glm::dvec3 reference(const Case& c) {
  return upsampleBlend(glm::dvec3(c.p), glm::dvec3(c.n), double(c.p.w), glm::dvec2(c.f), samplesOf(c));
}

// fp32 unit roundoff, and GLSL 4.50's precision of exp (3 + 2|x| ULP), ULP = 2u near the result.
constexpr double kU = 1.0 / 16777216.0;  // 2⁻²⁴

// |GPU − reference| allowed for one blend. R = Σ w_k E_k / W with w_k = b_k m_k; a relative error
// ε_k in w_k moves R by at most Σ ε_k w_k |E_k − R| / W (first order), the sums and the division
// add ≤ 8u max|E|. ε_k: the plane distance x = |n·(p_k − p)| / (0.01 eye) carries δx ≤ u (4(|p| +
// |p_k|) + 4|n·(p_k − p)|) / (0.01 eye) + 4u x, so exp(−x²) carries 2x δx + (3 + 2x²) 2u; c = n·n_k
// carries 4u absolute, so c⁸ (three squarings, 3u more) carries 32u / c + 3u; the products 4u.
double blendBound(const Case& c, const glm::dvec3& want) {
  const glm::dvec3 p(c.p), n(c.n);
  const double eye = c.p.w;
  double num = 0.0, weight = 0.0, biggest = 0.0;
  for (int k = 0; k < 4; ++k) {
    const UpsampleSample s = samplesOf(c)[std::size_t(k)];
    biggest = std::max({biggest, std::abs(s.e.x), std::abs(s.e.y), std::abs(s.e.z)});
    const double m = upsampleMatch(p, n, eye, s);
    const double b = ((k & 1) ? c.f.x : 1.0 - c.f.x) * ((k >> 1) ? c.f.y : 1.0 - c.f.y);
    if (m * b <= 0.0) continue;
    const double dot = std::abs(glm::dot(n, s.p - p));
    const double x = dot / (eye * kUpsamplePlaneScale);
    const double dx = kU * (4.0 * (glm::length(p) + glm::length(s.p)) + 4.0 * dot) / (eye * kUpsamplePlaneScale) + 4.0 * kU * x;
    const double cn = std::max(glm::dot(n, s.n), 1e-30);
    const double eps = 2.0 * x * dx + (3.0 + 2.0 * x * x) * 2.0 * kU + 32.0 * kU / cn + 3.0 * kU + 4.0 * kU;
    const double spread = std::max({std::abs(s.e.x - want.x), std::abs(s.e.y - want.y), std::abs(s.e.z - want.z)});
    num += eps * m * b * spread;
    weight += m * b;
  }
  return (weight > 0.0 ? num / weight : 0.0) + 8.0 * kU * biggest + 1e-30;
}

glm::vec3 unit(std::mt19937& rng) {
  std::normal_distribution<float> g;
  return glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
}

}  // namespace

// Every pixel of 37×23 and 64×48 images, steps 2 and 4: the 4 reduced samples, the G-buffer pixels they
// hold (clamped at the last row and column) and the bilinear fractions, exactly as the C++ reference.
TEST(SlUpsampleGpu, TapsOfEveryPixelMatchTheReference) {
  std::vector<Case> cases;
  for (const int step : {2, 4})
    for (const glm::ivec2 full : {glm::ivec2(37, 23), glm::ivec2(64, 48)}) {
      const glm::ivec2 reduced = glm::ivec2(gi::reducedSize(glm::uvec2(full), std::uint32_t(step)));
      for (int y = 0; y < full.y; ++y)
        for (int x = 0; x < full.x; ++x) {
          Case c;
          c.pixel = {x, y, step, 0};
          c.sizes = {reduced, full};
          c.p = {0, 0, 0, 1};
          c.n = {0, 0, 1, 0};
          cases.push_back(c);
        }
    }
  const std::vector<Result> got = run(cases);
  ASSERT_EQ(got.size(), cases.size());
  std::size_t checked = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const UpsampleTaps want = upsampleTaps({c.pixel.x, c.pixel.y}, c.pixel.z, {c.sizes.x, c.sizes.y}, {c.sizes.z, c.sizes.w});
    for (int k = 0; k < 4; ++k) {
      const glm::ivec4& jj = got[i].j[k / 2];
      const glm::ivec4& qq = got[i].q[k / 2];
      ASSERT_EQ(glm::ivec2(jj[2 * (k % 2)], jj[2 * (k % 2) + 1]), want.j[std::size_t(k)]) << "case " << i << " tap " << k;
      ASSERT_EQ(glm::ivec2(qq[2 * (k % 2)], qq[2 * (k % 2) + 1]), want.q[std::size_t(k)]) << "case " << i << " tap " << k;
      // Every tap is inside both images.
      ASSERT_TRUE(glm::all(glm::lessThan(want.j[std::size_t(k)], glm::ivec2(c.sizes.x, c.sizes.y))));
      ASSERT_TRUE(glm::all(glm::lessThan(want.q[std::size_t(k)], glm::ivec2(c.sizes.z, c.sizes.w))));
    }
    ASSERT_EQ(double(got[i].f.x), want.f.x) << "case " << i;
    ASSERT_EQ(double(got[i].f.y), want.f.y) << "case " << i;
    // Sample j0 stands for G-buffer pixel step·j0 ≤ pixel < step·(j0 + 1).
    ASSERT_GE(want.f.x, 0.0);
    ASSERT_LT(want.f.x, 1.0);
    ++checked;
  }
  EXPECT_EQ(checked, std::size_t(2 * (37 * 23 + 64 * 48)));
}

// Random receivers around a pixel's tangent plane (offsets up to 3× the plane scale, normals tilted up
// to ~60°, 1 in 8 samples background): the GLSL blend equals the double reference within blendBound.
TEST(SlUpsampleGpu, BlendMatchesTheReferenceWithinTheDerivedBound) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::vector<Case> cases;
  for (int i = 0; i < 4000; ++i) {
    Case c;
    const float eye = 0.5f + 9.5f * u01(rng);
    const glm::vec3 n = unit(rng);
    const glm::vec3 p = unit(rng) * (eye + 1.0f);
    c.p = glm::vec4(p, eye);
    c.n = glm::vec4(n, 0.0f);
    const int step = (i & 1) ? 4 : 2;
    c.f = glm::vec4(float(int(u01(rng) * float(step))) / float(step), float(int(u01(rng) * float(step))) / float(step), 0, 0);
    for (int k = 0; k < 4; ++k) {
      const glm::vec3 along = glm::normalize(glm::cross(n, unit(rng)));
      const float off = (u01(rng) - 0.5f) * 6.0f * float(kUpsamplePlaneScale) * eye;
      c.pq[k] = glm::vec4(p + along * (0.05f * eye * u01(rng)) + n * off, u01(rng) < 0.875f ? 1.0f : 0.0f);
      c.nq[k] = glm::vec4(glm::normalize(n + 0.9f * u01(rng) * unit(rng)), 0.0f);
      c.e[k] = glm::vec4(10.0f * u01(rng), 10.0f * u01(rng), 10.0f * u01(rng), 0.0f);
    }
    cases.push_back(c);
  }
  const std::vector<Result> got = run(cases);
  std::size_t compared = 0, skipped = 0, fallback = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    // Skip the cases a rounding can send down the other branch: Σ weight within 1 % of the threshold,
    // or the best-match fallback with two matches within 1e-3 of each other.
    double weight = 0.0;
    std::vector<double> matches;
    for (int k = 0; k < 4; ++k) {
      const double m = upsampleMatch(glm::dvec3(c.p), glm::dvec3(c.n), c.p.w, samplesOf(c)[std::size_t(k)]);
      weight += m * ((k & 1) ? c.f.x : 1.0 - c.f.x) * ((k >> 1) ? c.f.y : 1.0 - c.f.y);
      matches.push_back(m);
    }
    std::sort(matches.rbegin(), matches.rend());
    if (std::abs(weight - kUpsampleMinWeight) < 0.01 * kUpsampleMinWeight ||
        (weight <= kUpsampleMinWeight && matches[0] - matches[1] <= 1e-3 * matches[0])) {
      ++skipped;
      continue;
    }
    fallback += weight <= kUpsampleMinWeight;
    const glm::dvec3 want = reference(c);
    const double bound = blendBound(c, want);
    for (int ch = 0; ch < 3; ++ch) {
      const double err = std::abs(double(got[i].e[ch]) - want[ch]);
      ASSERT_TRUE(std::isfinite(double(got[i].e[ch]))) << "case " << i;
      ASSERT_LE(err, bound) << "case " << i << " channel " << ch << " want " << want[ch];
      worst = std::max(worst, err / bound);
    }
    ++compared;
  }
  std::printf("upsample blend: %zu cases compared (%zu on the best-match fallback), %zu skipped near a branch; worst "
              "error / bound %.3f\n", compared, fallback, skipped, worst);
  EXPECT_GE(compared, 3900u);
  EXPECT_GE(fallback, 10u);  // the fallback branch is exercised too
}

// A depth edge and a crease: a pixel on a near plane (z = −2, eye 2 m) whose taps are two near samples
// (E red) and two samples 0.5 m behind (E green) takes NO green, exactly — the far samples' plane
// distance is 25 plane scales, exp(−625) underflows to 0 in fp32 — and its red is the near samples'
// own E (their weighted mean of equal values). The same with the far taps on a perpendicular wall
// through the pixel's plane (n·n_q = 0): no light across the crease. Half and quarter fractions.
// x / x in GLSL: 2.5 ULP (GLSL 4.50 §4.7.1) around 1, where one ULP is 2⁻²³ above and 2⁻²⁴ below;
// 3 · 2⁻²³ covers both sides.
constexpr float kEqualSumsQuotientTol = 3.0f / 8388608.0f;

TEST(SlUpsampleGpu, NoLightCrossesADepthEdgeOrACrease) {
  std::vector<Case> cases;
  for (const int step : {2, 4})
    for (int fx = 0; fx < step; ++fx)
      for (int fy = 0; fy < step; ++fy)
        for (const bool crease : {false, true})
          for (int nearMask = 1; nearMask < 15; ++nearMask) {  // which taps are on the near plane (not all, not none)
            Case c;
            c.p = {0.1f, 0.2f, -2.0f, 2.0f};
            c.n = {0.0f, 0.0f, 1.0f, 0.0f};
            c.f = {float(fx) / float(step), float(fy) / float(step), 0, 0};
            for (int k = 0; k < 4; ++k) {
              const glm::vec3 at(0.1f + 0.004f * float(k & 1), 0.2f + 0.004f * float(k >> 1), -2.0f);
              if (nearMask >> k & 1) {
                c.pq[k] = glm::vec4(at, 1.0f);
                c.nq[k] = {0.0f, 0.0f, 1.0f, 0.0f};
                c.e[k] = {1.0f, 0.0f, 0.0f, 0.0f};
              } else {
                c.pq[k] = crease ? glm::vec4(at + glm::vec3(0.0f, 0.0f, 0.0f), 1.0f) : glm::vec4(at - glm::vec3(0, 0, 0.5f), 1.0f);
                c.nq[k] = crease ? glm::vec4(1.0f, 0.0f, 0.0f, 0.0f) : glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
                c.e[k] = {0.0f, 1.0f, 0.0f, 0.0f};
              }
            }
            cases.push_back(c);
          }
  const std::vector<Result> got = run(cases);
  std::size_t lit = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const glm::dvec3 want = reference(cases[i]);
    ASSERT_LT(want.y, 1e-200) << "case " << i;  // the reference agrees: exp(−625) of the far light
    ASSERT_EQ(got[i].e.y, 0.0f) << "case " << i << ": light crossed the edge";
    // Red: the near samples' E (1) where their bilinear weight is positive, else the best match's (1
    // too: a near sample matches perfectly). Σ w_k E_k and Σ w_k are the same fp32 sum here (E = 1), but
    // GLSL 4.50 allows x / y an error of 2.5 ULP, so a GPU may return 1 ± a few ULP (llvmpipe gives 1).
    ASSERT_NEAR(got[i].e.x, 1.0f, kEqualSumsQuotientTol) << "case " << i;
    lit += std::abs(got[i].e.x - 1.0f) <= kEqualSumsQuotientTol;
  }
  EXPECT_EQ(lit, cases.size());
}
