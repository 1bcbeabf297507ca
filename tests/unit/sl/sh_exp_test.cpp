// SH exponentiation (engine/math/sh_exp.hpp): the cap's closed-form ZH against projection, the log
// table's exactness, and SH-exp of 1…64 overlapping blockers against the brute-force product of
// visibilities on a fine direction sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "engine/core/error.hpp"
#include "engine/math/sh_eval.hpp"
#include "engine/math/sh_exp.hpp"
#include "engine/math/sh_project.hpp"
#include "engine/math/sh_rotate.hpp"
#include "../math/test_util.hpp"

using namespace bounce;
using namespace bounce::sh;

namespace {

const double kPi = math::kPi;
const double kSqrt4Pi = std::sqrt(4.0 * kPi);
// Closed form vs Monte-Carlo projection of a discontinuous indicator with 256² stratified samples:
// the error is the strata cut by the cap's edge, ~perimeter/N ≈ 1e-3.
constexpr double kCapProjectionTol = 3e-3;
// A clamped log cannot reproduce a truncated cap exactly; the best fit's ‖exp(f) − g‖₂ grows with θ
// (a hemisphere is the worst) and with the window. Measured maxima (printed) with ~10 % margin.
constexpr double kLogFitTolWindowed = 1.1;  // of ‖1‖ = √(4π) ≈ 3.54
constexpr double kLogFitTolRaw = 0.56;
// exp(f) = 1 + f + O(‖f‖²): for ‖f‖ ≈ 2e-4 the second-order term is ~1e-7 in RMS.
constexpr double kSecondOrderTol = 1e-6;
// Fine direction sampling for brute force: Fibonacci points; the projection of a product of
// indicators has quadrature error ~ edge length / √N, about 1e-3 at N = 40000.
constexpr int kBruteDirections = 40000;

std::vector<double> bruteProject(const std::function<double(const glm::dvec3&)>& f, int order) {
  std::vector<double> c(std::size_t(order * order), 0.0);
  const double w = 4.0 * kPi / kBruteDirections;
  for (int i = 0; i < kBruteDirections; ++i) {
    const glm::dvec3 d = math::fibonacciSphere(i, kBruteDirections);
    const double v = f(d);
    if (v == 0.0) continue;
    const auto y = evalBasis<double>(order, d);
    for (int k = 0; k < order * order; ++k) c[k] += w * v * y[k];
  }
  return c;
}

// RMS over the sphere of the difference of two SH functions: ‖a − b‖₂ / √(4π) (orthonormal basis).
double rmsDiff(std::span<const double> a, std::span<const double> b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s) / kSqrt4Pi;
}

struct Blocker {
  glm::dvec3 dir;
  double theta;
};

// K blockers whose directions lie within 0.5 rad of +Z with θ in [0.15, 0.6]: they overlap.
std::vector<Blocker> overlapping(int k, std::uint64_t seed) {
  math::Pcg32 rng(seed);
  std::vector<Blocker> b;
  for (int i = 0; i < k; ++i) {
    const double cosMax = std::cos(0.5);
    const double z = cosMax + (1.0 - cosMax) * rng.nextDouble();
    const double phi = 2.0 * kPi * rng.nextDouble();
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    b.push_back({{r * std::cos(phi), r * std::sin(phi), z}, 0.15 + 0.45 * rng.nextDouble()});
  }
  return b;
}

}  // namespace

TEST(ShExp, CapZonalMatchesProjectionAndSolidAngle) {
  for (double theta : {0.0, 0.1, 0.5, 1.0, kPi / 2, 2.5}) {
    const auto g = capVisibilityZonal(theta, 4);
    // ∫ v = √(4π) g_0 = 4π − 2π(1 − cos θ) (the cap's solid angle removed).
    EXPECT_NEAR(kSqrt4Pi * g[0], 4.0 * kPi - 2.0 * kPi * (1.0 - std::cos(theta)), 1e-12) << theta;
    const auto p = projectMonteCarlo(
        [&](const glm::dvec3& d) { return d.z > std::cos(theta) ? 0.0 : 1.0; }, 4, 256, 7);
    for (int l = 0; l < 4; ++l) EXPECT_NEAR(g[l], p[index(l, 0)], kCapProjectionTol) << theta << " l=" << l;
  }
}

TEST(ShExp, LogTableIsAClampedLogOfTheCap) {
  for (LogKind kind : {LogKind::Windowed, LogKind::Raw}) {
    const bool windowed = kind == LogKind::Windowed;
    for (int order : {3, 4}) {
      const ExpTables& t = expTables(order, kind);
      std::printf("%s order %d: max ||exp(log g) - g|| over the table = %.4f\n", windowed ? "windowed" : "raw", order,
                  t.logResidual());
      EXPECT_LT(t.logResidual(), windowed ? kLogFitTolWindowed : kLogFitTolRaw) << order;
      for (int i = 0; i < ExpTables::kThetaEntries; i += 15) {
        const double theta = 0.5 * kPi * i / (ExpTables::kThetaEntries - 1);
        const auto f = t.logZonal(theta);
        EXPECT_LE(f[0], 1e-12);  // a log of visibility ≤ 1: DC ≤ 0
        if (!windowed) continue;
        // Windowed: f ≤ 0 everywhere (no positive lobe), so exp of any sum stays ≤ 1.
        const auto fz = rotateZonal<double>(f, glm::dvec3(0, 0, 1));
        for (int s = 0; s <= 200; ++s) {
          const double z = -1.0 + 2.0 * s / 200.0;
          EXPECT_LE(evalSum(fz, glm::dvec3(std::sqrt(1 - z * z), 0, z)), 1e-9) << order << " θ=" << theta;
        }
      }
      // θ = 0 is no blocker: log = 0, exp = 1.
      for (double x : t.logZonal(0.0)) EXPECT_NEAR(x, 0.0, 1e-12);
    }
  }
}

TEST(ShExp, ExpOfZeroIsOneAndSmallVectorsAreFirstOrder) {
  for (int order : {3, 4}) {
    std::vector<double> z(std::size_t(order * order), 0.0);
    const auto one = expHybrid(z);
    EXPECT_NEAR(one[0], kSqrt4Pi, 1e-12);
    for (std::size_t i = 1; i < one.size(); ++i) EXPECT_NEAR(one[i], 0.0, 1e-12);
    // A tiny f: exp(f) = 1 + f + O(‖f‖²).
    math::Pcg32 rng(3);
    auto f = testutil::randomCoeffs(rng, order * order);
    for (double& x : f) x *= 1e-4;
    const auto e = expHybrid(f);
    const auto ex = expExact(f);
    EXPECT_LT(rmsDiff(e, ex), kSecondOrderTol) << order;
  }
}

// The core check: 1, 2, 4, 16, 64 overlapping blockers. V = exp(Σ G_i) against the projection of
// Π v_i sampled on 40000 directions. The measured RMS errors (printed) are the SH exponentiation
// approximation (OL + log per blocker + truncated squaring); Ren et al. report comparable errors.
TEST(ShExp, OverlappingBlockersMatchBruteForceProduct) {
  // RMS tolerance on [0,1]-valued visibility, per order and blocker count: the measured errors
  // (printed) with ~25 % margin, a regression guard. They grow with the overlap: log-space sums do
  // not saturate where blockers overlap, and each blocker's low-order log is wider than its cap, so
  // dense clusters over-darken around the union (the known limit of Ren et al.'s accumulation;
  // "rms(exactexp-brute)" shows the exact SH exp of the same sum does no better, so the OL table
  // and the squarings add almost nothing).
  auto tol = [](LogKind kind, int order, int k) {
    const int i = k == 1 ? 0 : k == 2 ? 1 : k == 4 ? 2 : k == 16 ? 3 : 4;
    static const double w3[5] = {0.031, 0.13, 0.23, 0.57, 0.93};
    static const double w4[5] = {0.045, 0.18, 0.28, 0.59, 0.94};
    // Raw: accurate for few blockers; the ringing lobes add up in dense clusters (finite, not good).
    static const double r3[5] = {0.001, 0.047, 0.14, 0.67, 3.3};
    static const double r4[5] = {0.0015, 0.074, 0.2, 0.56, 4.8};
    if (kind == LogKind::Windowed) return order == 3 ? w3[i] : w4[i];
    return order == 3 ? r3[i] : r4[i];
  };
  for (LogKind kind : {LogKind::Windowed, LogKind::Raw})
  for (int order : {3, 4}) {
    const ExpTables& t = expTables(order, kind);
    for (int k : {1, 2, 4, 16, 64}) {
      const auto blockers = overlapping(k, 100 + k);
      std::vector<double> sum(std::size_t(order * order), 0.0);
      for (const auto& b : blockers) {
        const auto g = t.logBlocker(b.theta, b.dir);
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += g[i];
      }
      int sq = 0;
      const auto v = expHybrid(sum, &sq, kind);
      const auto ref = bruteProject(
          [&](const glm::dvec3& d) {
            for (const auto& b : blockers)
              if (glm::dot(d, b.dir) > std::cos(b.theta)) return 0.0;
            return 1.0;
          },
          order);
      // The same product's best possible order-n answer is ref itself; the exact SH exp of the
      // same logs separates the OL/squaring error from the log-space approximation.
      const auto exact = expExact(sum, 64);
      const double err = rmsDiff(v, ref), errExact = rmsDiff(exact, ref);
      std::printf("%s order %d blockers %2d |f^|=%6.2f squarings %d  rms(hybrid-brute)=%.4f rms(exactexp-brute)=%.4f\n",
                  kind == LogKind::Windowed ? "windowed" : "raw", order, k, [&] {
                    double s = 0;
                    for (std::size_t i = 1; i < sum.size(); ++i) s += sum[i] * sum[i];
                    return std::sqrt(s);
                  }(), sq, err, errExact);
      for (double x : v) EXPECT_TRUE(std::isfinite(x));
      EXPECT_LT(err, tol(kind, order, k)) << "order " << order << " blockers " << k;
    }
  }
}

// ‖f̂‖ up to 50 stays finite and bounded: sums of many large blockers (the log-visibility shape the
// renderer feeds in). Exact visibility lies in [0, 1], so ‖V‖₂ ≤ √(4π); the approximation may
// overshoot but must stay within kOvershoot of that, and every reconstructed value within
// [−kOvershoot, 1 + kOvershoot].
TEST(ShExp, LargeMagnitudesStayFiniteAndBounded) {
  constexpr double kOvershoot = 0.5;  // generous: this is a stability bound, not an accuracy one
  for (LogKind kind : {LogKind::Windowed, LogKind::Raw})
  for (int order : {3, 4}) {
    const ExpTables& t = expTables(order, kind);
    math::Pcg32 rng(77);
    for (double target : {5.0, 10.0, 20.0, 35.0, 50.0}) {
      std::vector<double> sum(std::size_t(order * order), 0.0);
      double mag = 0.0;
      while (mag < target) {
        const auto g = t.logBlocker(0.3 + 1.2 * rng.nextDouble(), testutil::randomDirection(rng));
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += g[i];
        mag = 0.0;
        for (std::size_t i = 1; i < sum.size(); ++i) mag += sum[i] * sum[i];
        mag = std::sqrt(mag);
      }
      // Rescale the DC-free part to exactly `target` (the DC scales along: same shape).
      for (double& x : sum) x *= target / mag;
      int sq = 0;
      const auto v = expHybrid(sum, &sq, kind);
      double norm = 0.0;
      for (double x : v) {
        ASSERT_TRUE(std::isfinite(x)) << order << " " << target;
        norm += x * x;
      }
      EXPECT_LE(std::sqrt(norm), kSqrt4Pi * (1.0 + kOvershoot)) << order << " " << target;
      for (int i = 0; i < 500; ++i) {
        const double val = evalSum(v, math::fibonacciSphere(i, 500));
        EXPECT_GE(val, -kOvershoot);
        EXPECT_LE(val, 1.0 + kOvershoot);
      }
      EXPECT_GE(sq, target > ExpTables::kMaxMagnitude ? 1 : 0);
      // And the DC-free part alone (DC = 0) at the same magnitude: finite.
      sum[0] = 0.0;
      for (double x : expHybrid(sum, nullptr, kind)) EXPECT_TRUE(std::isfinite(x));
    }
  }
}

TEST(ShExp, RejectsOrdersOtherThanThreeAndFour) {
  std::vector<double> f(4, 0.0);
  EXPECT_THROW(expHybrid(f), InternalError);
  EXPECT_THROW(expTables(2), InternalError);
}

// The hybrid exp is continuous in f: along f = s·u (u a DC-free sum of blocker logs, DC kept at a
// fixed −2 √(4π)), ‖f̂‖ = s from 0.5 to 50 in relative steps of 1e-4, the largest change of exp(f) per
// step is bounded. Ren et al.'s plain hybrid jumps where ‖f̂‖ crosses 4, 8, 16, 32 (OL at 4 ≠ OL at 2
// squared); sh_exp.hpp's blend over [kHybridBlendStart, kMaxMagnitude] closes those jumps.
TEST(ShExp, HybridIsContinuousWhereTheHalvingCountChanges) {
  // ‖Δ exp‖₂ / ‖exp‖₂ per step Δs = 1e-4 s, divided by Δs: exp(s u) changes at a rate ~‖u‖ = 1, so
  // a continuous exp stays O(1) (measured worst 0.43, printed); the plain hybrid's jumps at
  // ‖f̂‖ = 4…32 give 40–115.
  constexpr double kMaxRate = 2.0;
  for (LogKind kind : {LogKind::Windowed, LogKind::Raw})
    for (int order : {3, 4}) {
      const ExpTables& t = expTables(order, kind);
      math::Pcg32 rng(5);
      std::vector<double> u(std::size_t(order * order), 0.0);
      for (int b = 0; b < 6; ++b) {
        const auto g = t.logBlocker(0.3 + 0.9 * rng.nextDouble(), testutil::randomDirection(rng));
        for (std::size_t i = 0; i < u.size(); ++i) u[i] += g[i];
      }
      u[0] = 0.0;
      double norm = 0.0;
      for (double x : u) norm += x * x;
      for (double& x : u) x /= std::sqrt(norm);
      double worst = 0.0, worstAt = 0.0;
      std::vector<double> last;
      for (double s = 0.5; s <= 50.0; s *= 1.0 + 1e-4) {
        std::vector<double> f(u.size());
        for (std::size_t i = 0; i < u.size(); ++i) f[i] = s * u[i];
        f[0] = -2.0 * kSqrt4Pi;
        const auto e = expHybrid(f, nullptr, kind);
        double en = 0.0, dn = 0.0;
        for (std::size_t i = 0; i < e.size(); ++i) {
          ASSERT_TRUE(std::isfinite(e[i]));
          en += e[i] * e[i];
          if (!last.empty()) dn += (e[i] - last[i]) * (e[i] - last[i]);
        }
        const double rate = std::sqrt(dn / en) / (s * 1e-4 / (1.0 + 1e-4));
        if (!last.empty() && rate > worst) worst = rate, worstAt = s;
        last = e;
      }
      std::printf("%s order %d: largest relative change of exp per unit of |f^| = %.3g (at |f^| = %.3f)\n",
                  kind == LogKind::Windowed ? "windowed" : "raw", order, worst, worstAt);
      EXPECT_LT(worst, kMaxRate) << "at |f^| = " << worstAt;
    }
}
