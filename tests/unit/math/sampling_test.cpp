// Sampling, quadrature and geometry helpers.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "engine/core/error.hpp"
#include "engine/math/geometry.hpp"
#include "engine/math/quadrature.hpp"
#include "engine/math/sampling.hpp"
#include "test_util.hpp"

using namespace bounce;
using namespace bounce::math;

namespace {

// Monte Carlo means over N = 256² stratified samples of functions with σ <= 0.5: the plain
// (unstratified) standard error is 0.5/256 ≈ 2e-3; stratification only lowers it. 5σ.
constexpr int kStrata = 256;
constexpr double kMeanTol = 1e-2;
// Orthonormality of the Duff et al. basis: a handful of double roundings (float: of floats).
constexpr double kBasisTolDouble = 1e-14;
constexpr double kBasisTolFloat = 1e-6;
// Gauss–Legendre integrals of polynomials within their exact degree: rounding only.
constexpr double kExactTol = 1e-13;

}  // namespace

TEST(Pcg32, MatchesReferenceSequence) {
  // pcg32-demo from pcg-c-basic, seeded with pcg32_srandom_r(&rng, 42u, 54u).
  Pcg32 rng(42u, 54u);
  const std::uint32_t expected[] = {0xa15c02b7, 0x7b47f409, 0xba1d3330, 0x83d2f293, 0xbfa4784b, 0xcbed606e};
  for (std::uint32_t e : expected) EXPECT_EQ(rng.nextU32(), e);
}

TEST(Pcg32, UnitIntervalAndIndexSeeding) {
  Pcg32 rng(7);
  double sum = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double d = rng.nextDouble();
    const float f = rng.nextFloat();
    ASSERT_GE(d, 0.0);
    ASSERT_LT(d, 1.0);
    ASSERT_GE(f, 0.0f);
    ASSERT_LT(f, 1.0f);
    sum += d;
  }
  // Mean of 1e5 uniforms: σ = 0.29/√1e5 ≈ 9e-4; 5σ.
  EXPECT_NEAR(sum / 100000.0, 0.5, 5e-3);
  // fromIndex: deterministic, and neighbouring indices start differently.
  std::set<std::uint32_t> firsts;
  for (std::uint64_t i = 0; i < 1000; ++i) firsts.insert(Pcg32::fromIndex(i).nextU32());
  EXPECT_EQ(firsts.size(), 1000u);
  EXPECT_EQ(Pcg32::fromIndex(5).nextU32(), Pcg32::fromIndex(5).nextU32());
}

TEST(Sampling, CosineWeightedHemisphereHasPdfCosOverPi) {
  for (glm::dvec3 n : {glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1), glm::normalize(glm::dvec3(1, -2, 0.5))}) {
    Pcg32 rng(60);
    const auto u = stratified2D(kStrata, rng);
    double meanCos = 0.0, meanCos2 = 0.0, above = 0.0;
    for (const auto& p : u) {
      const glm::dvec3 w = cosineHemisphere(p, n);
      ASSERT_NEAR(glm::length(w), 1.0, 1e-12);
      const double c = glm::dot(w, n);
      ASSERT_GE(c, -1e-12);
      meanCos += c;
      meanCos2 += c * c;
      above += c > 0.5 ? 1.0 : 0.0;
    }
    const double N = double(u.size());
    // Under pdf cos/π: E[cos] = ∫cos²/π dω = 2/3, E[cos²] = 1/2, P(cos > 1/2) = 1 - 1/4 = 3/4.
    EXPECT_NEAR(meanCos / N, 2.0 / 3.0, kMeanTol);
    EXPECT_NEAR(meanCos2 / N, 0.5, kMeanTol);
    EXPECT_NEAR(above / N, 0.75, kMeanTol);
    // ∫_H cos dω = π estimated with cosine samples and uniform-hemisphere samples (pdf 1/(2π)).
    double uniformEstimate = 0.0;
    for (const auto& p : u) uniformEstimate += std::max(0.0, glm::dot(uniformHemisphere(p, n), n)) / uniformHemispherePdf();
    EXPECT_NEAR(uniformEstimate / N, kPi, kPi * kMeanTol);
    EXPECT_NEAR(cosineHemispherePdf(0.5), 0.5 / kPi, kExactTol);
    EXPECT_EQ(cosineHemispherePdf(-0.1), 0.0);
  }
}

TEST(Sampling, UniformSphereMoments) {
  Pcg32 rng(61);
  glm::dvec3 mean(0.0);
  double z2 = 0.0;
  const auto u = stratified2D(kStrata, rng);
  for (const auto& p : u) {
    const glm::dvec3 w = uniformSphere(p);
    mean += w;
    z2 += w.z * w.z;
  }
  mean /= double(u.size());
  EXPECT_NEAR(glm::length(mean), 0.0, kMeanTol);
  EXPECT_NEAR(z2 / u.size(), 1.0 / 3.0, kMeanTol);
  EXPECT_NEAR(uniformSpherePdf() * 4.0 * kPi, 1.0, kExactTol);
}

TEST(Sampling, StratifiedPointsFillEveryStratumOnce) {
  Pcg32 rng(62);
  const int n = 8;
  const auto u = stratified2D(n, rng);
  ASSERT_EQ(u.size(), 64u);
  std::set<int> cells;
  for (const auto& p : u) cells.insert(int(p.y * n) * n + int(p.x * n));
  EXPECT_EQ(cells.size(), 64u);
  EXPECT_TRUE(stratified2D(0, rng).empty());
}

TEST(Sampling, FibonacciSphereIsUnitAndBalanced) {
  const int n = 1001;
  const auto pts = fibonacciSphere(n);
  ASSERT_EQ(pts.size(), std::size_t(n));
  glm::dvec3 mean(0.0);
  for (const auto& p : pts) {
    EXPECT_NEAR(glm::length(p), 1.0, 1e-12);
    mean += p;
  }
  // Lattice points are equal-area; the mean vanishes to O(1/n).
  EXPECT_LT(glm::length(mean / double(n)), 2.0 / n);
}

TEST(Geometry, OrthonormalBasisNearPolesAndEverywhere) {
  std::vector<glm::dvec3> normals;
  for (double s : {1.0, -1.0})
    for (double e : {0.0, 1e-12, 1e-8, 1e-4, 1e-2}) {
      normals.push_back(glm::normalize(glm::dvec3(e, e, s)));
      normals.push_back(glm::normalize(glm::dvec3(-e, 0.5 * e, s)));
    }
  Pcg32 rng(63);
  for (int i = 0; i < 200; ++i) normals.push_back(testutil::randomDirection(rng));
  for (const auto& n : normals) {
    const auto f = orthonormalBasis(n);
    EXPECT_NEAR(glm::length(f.t), 1.0, kBasisTolDouble);
    EXPECT_NEAR(glm::length(f.b), 1.0, kBasisTolDouble);
    EXPECT_NEAR(glm::dot(f.t, f.b), 0.0, kBasisTolDouble);
    EXPECT_NEAR(glm::dot(f.t, n), 0.0, kBasisTolDouble);
    EXPECT_NEAR(glm::dot(f.b, n), 0.0, kBasisTolDouble);
    EXPECT_NEAR(glm::length(glm::cross(f.t, f.b) - n), 0.0, 4 * kBasisTolDouble);  // right-handed
    const glm::dvec3 v(0.3, -0.2, 0.9);
    EXPECT_NEAR(glm::length(f.toLocal(f.toWorld(v)) - v), 0.0, 4 * kBasisTolDouble);
    const auto ff = orthonormalBasis(glm::vec3(n));
    EXPECT_NEAR(glm::dot(ff.t, ff.b), 0.0f, kBasisTolFloat);
    EXPECT_NEAR(glm::length(ff.t), 1.0f, kBasisTolFloat);
    EXPECT_NEAR(glm::dot(ff.b, glm::vec3(n)), 0.0f, kBasisTolFloat);
  }
}

TEST(Geometry, SphericalTriangleSolidAngle) {
  const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  EXPECT_NEAR(sphericalTriangleSolidAngle(x, y, z), kPi / 2.0, kExactTol);  // an octant
  EXPECT_NEAR(sphericalTriangleSolidAngle(x, z, y), kPi / 2.0, kExactTol);  // orientation-free
  EXPECT_NEAR(sphericalTriangleSolidAngle(x, x, y), 0.0, kExactTol);        // degenerate
}

TEST(Quadrature, GaussLegendreIntegratesPolynomialsExactly) {
  for (int n : {1, 2, 5, 12}) {
    const auto gl = gaussLegendre(n);
    double wsum = 0.0;
    for (const auto& g : gl) wsum += g.weight;
    EXPECT_NEAR(wsum, 2.0, kExactTol);
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double sum = 0.0;
      for (const auto& g : gl) sum += g.weight * std::pow(g.x, k);
      EXPECT_NEAR(sum, k % 2 ? 0.0 : 2.0 / (k + 1), kExactTol) << "n=" << n << " k=" << k;
    }
  }
  EXPECT_THROW(gaussLegendre(0), InternalError);
}

TEST(Quadrature, SphereRuleIntegratesMonomialsExactly) {
  // ∫ x² = 4π/3, ∫ x⁴ = 4π/5, ∫ x²y²z² = 4π/105, ∫ x²y⁴z² = 4π/315 (degree 8).
  const auto q = sphereQuadrature(8);
  double s0 = 0, s2 = 0, s4 = 0, s222 = 0, s242 = 0, odd = 0;
  for (const auto& n : q) {
    const auto d = n.dir;
    s0 += n.weight;
    s2 += n.weight * d.x * d.x;
    s4 += n.weight * std::pow(d.x, 4);
    s222 += n.weight * d.x * d.x * d.y * d.y * d.z * d.z;
    s242 += n.weight * d.x * d.x * std::pow(d.y, 4) * d.z * d.z;
    odd += n.weight * d.x * d.y * d.y * d.z * d.z * d.z;
  }
  EXPECT_NEAR(s0, 4 * kPi, kExactTol);
  EXPECT_NEAR(s2, 4 * kPi / 3, kExactTol);
  EXPECT_NEAR(s4, 4 * kPi / 5, kExactTol);
  EXPECT_NEAR(s222, 4 * kPi / 105, kExactTol);
  EXPECT_NEAR(s242, 4 * kPi / 315, kExactTol);
  EXPECT_NEAR(odd, 0.0, kExactTol);
}
