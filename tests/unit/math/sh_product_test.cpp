// SH triple products (Gaunt tensor): known values, symmetry, selection rules, and products
// against the projection of the pointwise product.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <tuple>

#include "engine/math/sh_product.hpp"
#include "engine/math/sh_project.hpp"
#include "test_util.hpp"

using namespace bounce;
using namespace bounce::sh;

namespace {

const double kPi = math::kPi;
// Tensor from an exact quadrature and products of O(1) sums: rounding only.
constexpr double kExactTol = 1e-12;

int bandOf(int i) { return static_cast<int>(std::sqrt(double(i))); }

}  // namespace

TEST(ShProduct, TensorKnownValuesAndSelectionRules) {
  const auto& t = gauntTensor();
  std::map<std::tuple<int, int, int>, double> lookup;
  for (const auto& e : t) lookup[{e.i, e.j, e.k}] = e.value;
  const auto at = [&](int i, int j, int k) {
    const auto it = lookup.find({i, j, k});
    return it == lookup.end() ? 0.0 : it->second;
  };
  // C_0jk = δ_jk Y_00 = δ_jk / (2√π).
  for (int j = 0; j < 16; ++j)
    for (int k = 0; k < 16; ++k) {
      EXPECT_NEAR(at(0, j, k), j == k ? 0.5 / std::sqrt(kPi) : 0.0, kExactTol) << j << "," << k;
    }
  // C(Y_1,0, Y_1,0, Y_2,0) = ∫ c1² z² · k20 (3z²-1) = 2/√(20π) (the Clebsch–Gordan value
  // √(3·3·5/(4π)) · (1 1 2; 0 0 0)² = √(45/(4π)) · 2/15).
  EXPECT_NEAR(at(index(1, 0), index(1, 0), index(2, 0)), std::sqrt(45.0 / (4.0 * kPi)) * 2.0 / 15.0, kExactTol);
  for (const auto& e : t) {
    const int a = bandOf(e.i), b = bandOf(e.j), c = bandOf(e.k);
    EXPECT_EQ((a + b + c) % 2, 0) << "parity";
    EXPECT_LE(std::abs(a - b), c) << "triangle";
    EXPECT_LE(c, a + b) << "triangle";
    // Symmetric in all three indices.
    EXPECT_NEAR(at(e.j, e.i, e.k), e.value, kExactTol);
    EXPECT_NEAR(at(e.k, e.j, e.i), e.value, kExactTol);
  }
  // Sorted by (k, i, j) so truncation can stop early.
  for (std::size_t n = 1; n < t.size(); ++n)
    EXPECT_LT(std::tuple(t[n - 1].k, t[n - 1].i, t[n - 1].j), std::tuple(t[n].k, t[n].i, t[n].j));
}

TEST(ShProduct, ProductOfBandLimitedFunctionsIsExact) {
  // Two order-2 functions (l <= 1): the product has l <= 2, so order 3 holds it entirely.
  math::Pcg32 rng(40);
  const auto a = testutil::randomCoeffs(rng, 4), b = testutil::randomCoeffs(rng, 4);
  const auto c = product<double>(a, b, 3);
  const auto f = [&](const glm::dvec3& d) { return evalSum(a, d) * evalSum(b, d); };
  const auto p = projectQuadrature(f, 3, 2);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(c[i], p[i], kExactTol) << i;
  // And the reconstruction equals the pointwise product everywhere.
  for (int s = 0; s < 20; ++s) {
    const glm::dvec3 d = testutil::randomDirection(rng);
    EXPECT_NEAR(evalSum(c, d), f(d), kExactTol);
  }
}

TEST(ShProduct, TruncatedProductIsProjectionOfPointwiseProduct) {
  // Order 4 × order 4 has bands up to 6; truncated to order n it must equal the exact projection
  // of the pointwise product onto order n (nothing lost but the dropped bands).
  math::Pcg32 rng(41);
  const auto a = testutil::randomCoeffs(rng, 16), b = testutil::randomCoeffs(rng, 16);
  const auto f = [&](const glm::dvec3& d) { return evalSum(a, d) * evalSum(b, d); };
  for (int order = 1; order <= 4; ++order) {
    const auto c = product<double>(a, b, order);
    const auto p = projectQuadrature(f, order, 6);
    ASSERT_EQ(c.size(), p.size());
    for (std::size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(c[i], p[i], kExactTol) << order << " " << i;
  }
  // Mixed orders: order-3 × order-2.
  const std::vector<double> a9(a.begin(), a.begin() + 9), b4(b.begin(), b.begin() + 4);
  const auto g = [&](const glm::dvec3& d) { return evalSum(a9, d) * evalSum(b4, d); };
  const auto c = product<double>(a9, b4, 4);
  const auto p = projectQuadrature(g, 4, 3);
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(c[i], p[i], kExactTol) << i;
}

TEST(ShProduct, ProductWithConstantScales) {
  // The constant k has coefficients (2√π k, 0, ...): the product is k·a.
  math::Pcg32 rng(42);
  const auto a = testutil::randomCoeffs(rng, 16);
  const double k = 2.5;
  const std::vector<double> constant = {2.0 * std::sqrt(kPi) * k};
  const auto c = product<double>(a, constant, 4);
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(c[i], k * a[i], kExactTol);
}

TEST(ShProduct, ProductIsSymmetricAndMatrixFormAgrees) {
  math::Pcg32 rng(43);
  const auto a = testutil::randomCoeffs(rng, 16), b = testutil::randomCoeffs(rng, 16);
  const auto ab = product<double>(a, b, 4), ba = product<double>(b, a, 4);
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(ab[i], ba[i], kExactTol);
  const auto m = productMatrix<double>(a, 4);
  for (int k = 0; k < 16; ++k) {
    double sum = 0.0;
    for (int j = 0; j < 16; ++j) sum += m[k * 16 + j] * b[j];
    EXPECT_NEAR(sum, ab[k], kExactTol);
  }
  // Multiplying by a real function is self-adjoint: the matrix is symmetric.
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j < 16; ++j) EXPECT_NEAR(m[k * 16 + j], m[j * 16 + k], kExactTol);
}

TEST(ShProduct, FloatProductAgreesWithDouble) {
  math::Pcg32 rng(44);
  const auto a = testutil::randomCoeffs(rng, 9), b = testutil::randomCoeffs(rng, 9);
  const std::vector<float> af(a.begin(), a.end()), bf(b.begin(), b.end());
  const auto cd = product<double>(a, b, 3);
  const auto cf = product<float>(af, bf, 3);
  constexpr double kFloatTol = 1e-5;  // ~30 float products of magnitude ~0.3 per coefficient
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(cf[i], cd[i], kFloatTol);
}
