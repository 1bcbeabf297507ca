// Windowing: weights, and the minimal window that removes the negative lobes of a small bright
// light's projection.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/math/sampling.hpp"
#include "engine/math/sh_window.hpp"
#include "test_util.hpp"

using namespace bounce;
using namespace bounce::sh;

namespace {

constexpr double kExactTol = 1e-12;
// The light's reconstruction peaks at Σ_i Y_i(s)² = 16/(4π) ≈ 1.27; "non-negative" is asserted
// to 1e-9 of that (bisection ends on the non-negative side, so only rounding remains).
constexpr double kNonNegativeEps = 1e-9;
// Directions for the negativity check: 4000 Fibonacci points are ~0.06 rad apart, finer than the
// narrowest order-4 lobe (~π/4), so a lobe missed between points is below ~1e-3 of the peak;
// the test re-checks on an independent 20000-point set with that slack.
constexpr int kCheckDirections = 4000;
constexpr double kDenseRecheckSlack = 2e-3;

}  // namespace

TEST(ShWindow, WeightsShape) {
  for (Window w : {Window::Hann, Window::Sloan}) {
    EXPECT_EQ(windowWeight(w, 0, 0.5), 1.0);
    EXPECT_EQ(windowWeight(w, 1, 1.0), 0.0);  // width 1 keeps band 0 only
    EXPECT_EQ(windowWeight(w, 3, 3.0), 0.0);
    EXPECT_EQ(windowWeight(w, 3, std::numeric_limits<double>::infinity()), 1.0);
    for (int l = 1; l < 6; ++l) EXPECT_LT(windowWeight(w, l, 6.0), windowWeight(w, l - 1, 6.0));
  }
  EXPECT_NEAR(windowWeight(Window::Hann, 2, 4.0), 0.5, kExactTol);           // half-way point of cos²
  const double s = std::sin(math::kPi / 2.0) / (math::kPi / 2.0);            // sinc at x = π/2
  EXPECT_NEAR(windowWeight(Window::Sloan, 2, 4.0), s * s * s * s, kExactTol);
}

TEST(ShWindow, MinimalWindowRemovesNegativeLobesOfSmallBrightLight) {
  // A delta light of unit power from s projects to c_i = Y_i(s): the most ringing input there is.
  const glm::dvec3 s = glm::normalize(glm::dvec3(0.3, -0.4, 0.8));
  const auto y = evalBasis<double>(4, s);
  const std::vector<double> c(y.begin(), y.end());
  const auto dirs = math::fibonacciSphere(kCheckDirections);
  const double peak = evalSum(c, s);
  const double before = minValue(c, dirs);
  EXPECT_LT(before, -0.1 * peak);  // the unwindowed order-4 delta rings by >10 % of its peak
  for (Window kind : {Window::Hann, Window::Sloan}) {
    const auto width = minimalWindow(c, kind, dirs, kNonNegativeEps * peak);
    ASSERT_TRUE(width.has_value());
    ASSERT_TRUE(std::isfinite(*width));
    EXPECT_GT(*width, 1.0);  // more than band 0 survives
    const auto w = applyWindow<double>(c, kind, *width);
    EXPECT_GE(minValue(w, dirs), -kNonNegativeEps * peak);
    EXPECT_GE(minValue(w, math::fibonacciSphere(20000)), -kDenseRecheckSlack * peak);
    // Minimal: 1 % less filtering brings a negative lobe back.
    const auto w2 = applyWindow<double>(c, kind, *width * 1.01);
    EXPECT_LT(minValue(w2, dirs), -kNonNegativeEps * peak);
    // Band 0 (the light's power) is untouched, and the peak still points at the light.
    EXPECT_EQ(w[0], c[0]);
    EXPECT_GT(evalSum(w, s), evalSum(w, -s));
  }
}

TEST(ShWindow, NoWindowNeededOrNoneHelps) {
  const auto dirs = math::fibonacciSphere(500);
  // 1 + 0.5·z ≥ 0.5 > 0 everywhere: no window.
  const std::vector<double> positive = {2.0 * std::sqrt(math::kPi), 0.0, 0.5 / constants::kY1, 0.0};
  const auto none = minimalWindow(positive, Window::Sloan, dirs);
  ASSERT_TRUE(none.has_value());
  EXPECT_TRUE(std::isinf(*none));
  // Negative mean: no window can make it non-negative.
  const std::vector<double> negative = {-1.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(minimalWindow(negative, Window::Hann, dirs).has_value());
}

TEST(ShWindow, RgbWindowIsTheNarrowestChannel) {
  const auto dirs = math::fibonacciSphere(2000);
  const auto y = evalBasis<double>(3, glm::dvec3(0, 0, 1));
  std::vector<glm::dvec3> rgb;
  std::vector<double> red, green;
  for (int i = 0; i < 9; ++i) {
    // Red: a delta (rings); green: a delta on a bright constant (rings less); blue: constant.
    const double base = i == 0 ? 2.0 * std::sqrt(math::kPi) : 0.0;
    red.push_back(y[i]);
    green.push_back(y[i] + 0.3 * base);
    rgb.push_back({red.back(), green.back(), base});
  }
  const auto wr = minimalWindow(red, Window::Sloan, dirs);
  const auto wg = minimalWindow(green, Window::Sloan, dirs);
  const auto w = minimalWindow(rgb, Window::Sloan, dirs);
  ASSERT_TRUE(wr && wg && w);
  EXPECT_LE(*wr, *wg);
  EXPECT_EQ(*w, std::min(*wr, *wg));
}
