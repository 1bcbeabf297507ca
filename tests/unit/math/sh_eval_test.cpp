// SH evaluation: closed forms, fast path vs recurrence, orthonormality, parity, argument checks.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.hpp"
#include "engine/math/quadrature.hpp"
#include "engine/math/sh_eval.hpp"
#include "test_util.hpp"

using namespace bounce;
using namespace bounce::sh;

namespace {

// Double evaluation of short polynomials with O(1) constants: a few ulps.
constexpr double kDoubleEvalTol = 1e-14;
// Float evaluation of the same: each multiply rounds at 6e-8 relative, values are <= ~3, and up
// to ~6 roundings accumulate: 3 · 6 · 6e-8 ≈ 1e-6.
constexpr double kFloatEvalTol = 2e-6;
// The recurrence runs ~l steps of cancelling sums in double; up to l = 8 it keeps ~1e-13.
constexpr double kRecurrenceTol = 1e-12;
// Gauss–Legendre quadrature of degree-16 polynomials: exact up to rounding of ~300 terms.
constexpr double kQuadratureTol = 1e-12;

const double kPi = math::kPi;

}  // namespace

TEST(ShEval, IndexLayout) {
  EXPECT_EQ(index(0, 0), 0);
  EXPECT_EQ(index(1, -1), 1);
  EXPECT_EQ(index(1, 1), 3);
  EXPECT_EQ(index(2, -2), 4);
  EXPECT_EQ(index(3, 3), 15);
  EXPECT_EQ(coeffCount(3), 9);
  EXPECT_EQ(orderFromCount(16), 4);
  EXPECT_EQ(orderFromCount(1), 1);
}

TEST(ShEval, ConstantsMatchClosedForms) {
  using namespace constants;
  EXPECT_NEAR(kY00, 0.5 / std::sqrt(kPi), kDoubleEvalTol);
  EXPECT_NEAR(kY1, std::sqrt(3.0 / (4.0 * kPi)), kDoubleEvalTol);
  EXPECT_NEAR(kY2a, 0.5 * std::sqrt(15.0 / kPi), kDoubleEvalTol);
  EXPECT_NEAR(kY20, 0.25 * std::sqrt(5.0 / kPi), kDoubleEvalTol);
  EXPECT_NEAR(kY22, 0.25 * std::sqrt(15.0 / kPi), kDoubleEvalTol);
  EXPECT_NEAR(kY33, 0.25 * std::sqrt(35.0 / (2.0 * kPi)), kDoubleEvalTol);
  EXPECT_NEAR(kY32a, 0.5 * std::sqrt(105.0 / kPi), kDoubleEvalTol);
  EXPECT_NEAR(kY31, 0.25 * std::sqrt(21.0 / (2.0 * kPi)), kDoubleEvalTol);
  EXPECT_NEAR(kY30, 0.25 * std::sqrt(7.0 / kPi), kDoubleEvalTol);
  EXPECT_NEAR(kY32b, 0.25 * std::sqrt(105.0 / kPi), kDoubleEvalTol);
}

TEST(ShEval, ClosedFormValuesAtChosenDirections) {
  const glm::dvec3 px(1, 0, 0), py(0, 1, 0), pz(0, 0, 1);
  const glm::dvec3 diag = glm::normalize(glm::dvec3(1, 1, 1));
  const glm::dvec3 xy = glm::normalize(glm::dvec3(1, 1, 0));
  const double c1 = std::sqrt(3.0 / (4.0 * kPi));
  // Band 1 is (y, z, x) with positive constants: no Condon–Shortley phase.
  EXPECT_NEAR(evalFast(1, -1, py), c1, kDoubleEvalTol);
  EXPECT_NEAR(evalFast(1, 0, pz), c1, kDoubleEvalTol);
  EXPECT_NEAR(evalFast(1, 1, px), c1, kDoubleEvalTol);
  EXPECT_NEAR(evalFast(1, 1, py), 0.0, kDoubleEvalTol);
  // Y_2,0(+Z) = √(5/π)/4 · (3 - 1); Y_2,0(+X) = -√(5/π)/4.
  EXPECT_NEAR(evalFast(2, 0, pz), 0.5 * std::sqrt(5.0 / kPi), kDoubleEvalTol);
  EXPECT_NEAR(evalFast(2, 0, px), -0.25 * std::sqrt(5.0 / kPi), kDoubleEvalTol);
  // Y_2,2(+Y) = √(15/π)/4 · (0 - 1); Y_2,-2((1,1,0)/√2) = √(15/π)/2 · 1/2.
  EXPECT_NEAR(evalFast(2, 2, py), -0.25 * std::sqrt(15.0 / kPi), kDoubleEvalTol);
  EXPECT_NEAR(evalFast(2, -2, xy), 0.25 * std::sqrt(15.0 / kPi), kDoubleEvalTol);
  // Y_3,0(+Z) = √(7/π)/4 · 2; Y_3,3(+X) = √(35/(2π))/4; Y_3,-3(+Y) = -√(35/(2π))/4.
  EXPECT_NEAR(evalFast(3, 0, pz), 0.5 * std::sqrt(7.0 / kPi), kDoubleEvalTol);
  EXPECT_NEAR(evalFast(3, 3, px), 0.25 * std::sqrt(35.0 / (2.0 * kPi)), kDoubleEvalTol);
  EXPECT_NEAR(evalFast(3, -3, py), -0.25 * std::sqrt(35.0 / (2.0 * kPi)), kDoubleEvalTol);
  // Y_3,-2((1,1,1)/√3) = √(105/π)/2 · (1/√3)³.
  EXPECT_NEAR(evalFast(3, -2, diag), 0.5 * std::sqrt(105.0 / kPi) / (3.0 * std::sqrt(3.0)), kDoubleEvalTol);
  // Y_3,1((1,1,1)/√3) = √(21/(2π))/4 · x(5z²-1) = √(21/(2π))/4 · (1/√3)(5/3 - 1).
  EXPECT_NEAR(evalFast(3, 1, diag), 0.25 * std::sqrt(21.0 / (2.0 * kPi)) / std::sqrt(3.0) * (2.0 / 3.0),
              kDoubleEvalTol);
}

TEST(ShEval, RecurrenceZonalAtPoleIsNormalisation) {
  // P_l(1) = 1, so Y_l,0(+Z) = √((2l+1)/(4π)) for every l; Y_l,m(+Z) = 0 for m ≠ 0.
  for (int l = 0; l <= 8; ++l) {
    EXPECT_NEAR(evalRecurrence(l, 0, glm::dvec3(0, 0, 1)), std::sqrt((2.0 * l + 1.0) / (4.0 * kPi)), kRecurrenceTol)
        << "l=" << l;
    for (int m = -l; m <= l; ++m)
      if (m != 0) {
        EXPECT_NEAR(evalRecurrence(l, m, glm::dvec3(0, 0, 1)), 0.0, kRecurrenceTol);
      }
  }
}

TEST(ShEval, FastPathEqualsRecurrenceDouble) {
  math::Pcg32 rng(1);
  for (int s = 0; s < 1000; ++s) {
    const glm::dvec3 d = testutil::randomDirection(rng);
    for (int l = 0; l <= 3; ++l)
      for (int m = -l; m <= l; ++m)
        ASSERT_NEAR(evalFast(l, m, d), evalRecurrence(l, m, d), kRecurrenceTol) << "l=" << l << " m=" << m;
  }
  // The axes and poles, where atan2 and sin θ = 0 are edge cases for the recurrence.
  for (glm::dvec3 d : {glm::dvec3(1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 0, 1)})
    for (int l = 0; l <= 3; ++l)
      for (int m = -l; m <= l; ++m) EXPECT_NEAR(evalFast(l, m, d), evalRecurrence(l, m, d), kRecurrenceTol);
}

TEST(ShEval, FastPathFloatEqualsDouble) {
  math::Pcg32 rng(2);
  for (int s = 0; s < 1000; ++s) {
    const glm::dvec3 d = testutil::randomDirection(rng);
    const auto yd = evalBasis<double>(4, d);
    const auto yf = evalBasis<float>(4, glm::vec3(d));
    for (int i = 0; i < kMaxCoeffs; ++i) ASSERT_NEAR(yf[i], yd[i], kFloatEvalTol) << "i=" << i;
  }
}

TEST(ShEval, EvalBasisAgreesWithEvalFastForEveryOrder) {
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  for (int order = 1; order <= kMaxOrder; ++order) {
    std::vector<double> y(coeffCount(order));
    evalBasis<double>(order, d, y);
    for (int l = 0; l < order; ++l)
      for (int m = -l; m <= l; ++m) EXPECT_EQ(y[index(l, m)], evalFast(l, m, d));
  }
}

TEST(ShEval, OrthonormalByExactQuadratureFastPath) {
  // Products Y_i Y_j with l <= 3 are polynomials of degree <= 6.
  const auto nodes = math::sphereQuadrature(6);
  for (int i = 0; i < kMaxCoeffs; ++i)
    for (int j = 0; j < kMaxCoeffs; ++j) {
      double sum = 0.0;
      for (const auto& n : nodes) {
        const auto y = evalBasis<double>(4, n.dir);
        sum += n.weight * y[i] * y[j];
      }
      EXPECT_NEAR(sum, i == j ? 1.0 : 0.0, kQuadratureTol) << i << "," << j;
    }
}

TEST(ShEval, OrthonormalByExactQuadratureRecurrenceUpToBand8) {
  constexpr int kBands = 9;  // l = 0..8, 81 functions; products have degree <= 16
  const auto nodes = math::sphereQuadrature(2 * (kBands - 1));
  std::vector<std::vector<double>> y(nodes.size(), std::vector<double>(kBands * kBands));
  for (std::size_t q = 0; q < nodes.size(); ++q)
    for (int l = 0; l < kBands; ++l)
      for (int m = -l; m <= l; ++m) y[q][index(l, m)] = evalRecurrence(l, m, nodes[q].dir);
  for (int i = 0; i < kBands * kBands; ++i)
    for (int j = 0; j <= i; ++j) {
      double sum = 0.0;
      for (std::size_t q = 0; q < nodes.size(); ++q) sum += nodes[q].weight * y[q][i] * y[q][j];
      ASSERT_NEAR(sum, i == j ? 1.0 : 0.0, kQuadratureTol) << i << "," << j;
    }
}

TEST(ShEval, ParityUnderInversion) {
  // Y_lm(-d) = (-1)^l Y_lm(d): band l is a homogeneous polynomial of degree l.
  math::Pcg32 rng(3);
  for (int s = 0; s < 100; ++s) {
    const glm::dvec3 d = testutil::randomDirection(rng);
    for (int l = 0; l <= 3; ++l)
      for (int m = -l; m <= l; ++m)
        EXPECT_NEAR(evalFast(l, m, -d), (l % 2 ? -1.0 : 1.0) * evalFast(l, m, d), kDoubleEvalTol);
  }
}

TEST(ShEval, EvalSumIsLinearAndRgbPerChannel) {
  const std::vector<double> r = {0.5, -0.2, 0.1, 0.3, 0.0, 0.7, -0.4, 0.2, 0.05};
  std::vector<glm::dvec3> rgb;
  for (double v : r) rgb.push_back({v, 2.0 * v, -v});
  const glm::dvec3 d = glm::normalize(glm::dvec3(-0.2, 0.9, 0.4));
  const auto y = evalBasis<double>(3, d);
  double expected = 0.0;
  for (int i = 0; i < 9; ++i) expected += r[i] * y[i];
  EXPECT_NEAR(evalSum(r, d), expected, kDoubleEvalTol);
  const glm::dvec3 c = evalSum(rgb, d);
  EXPECT_NEAR(c.x, expected, kDoubleEvalTol);
  EXPECT_NEAR(c.y, 2.0 * expected, kDoubleEvalTol);
  EXPECT_NEAR(c.z, -expected, kDoubleEvalTol);
}

TEST(ShEval, BadArgumentsThrowInternalError) {
  EXPECT_THROW(orderFromCount(5), InternalError);
  EXPECT_THROW(orderFromCount(25), InternalError);
  EXPECT_THROW(orderFromCount(0), InternalError);
  EXPECT_THROW(checkOrder(5), InternalError);
  EXPECT_THROW(evalFast(4, 0, glm::dvec3(0, 0, 1)), InternalError);
  EXPECT_THROW(evalFast(2, 3, glm::dvec3(0, 0, 1)), InternalError);
  EXPECT_THROW(evalRecurrence(2, -3, glm::dvec3(0, 0, 1)), InternalError);
  std::vector<double> small(3);
  EXPECT_THROW(evalBasis<double>(2, glm::dvec3(0, 0, 1), small), InternalError);
}
