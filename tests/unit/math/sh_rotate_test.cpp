// SH rotation (Ivanic & Ruedenberg): against projection of the rotated function, composition,
// identity, orthogonality, band 1 as a vector rotation, zonal functions and the zonal shortcut.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.hpp"
#include "engine/math/sh_project.hpp"
#include "engine/math/sh_rotate.hpp"
#include "test_util.hpp"

using namespace bounce;
using namespace bounce::sh;

namespace {

// Double rotation matrices are built by ~3 levels of recurrence of O(1) products and the
// projection is an exact quadrature: agreement to ~1e-14, asserted with margin.
constexpr double kRotationTol = 1e-12;
// Float matrices: entries rounded at 6e-8, 7-term dot products, values ~1: ~1e-6.
constexpr double kFloatRotationTol = 5e-6;

glm::dmat3 rotationAboutZ(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return glm::dmat3(c, s, 0, -s, c, 0, 0, 0, 1);  // columns
}

}  // namespace

TEST(ShRotate, IdentityIsIdentity) {
  const auto rot = Rotation<double>::fromMatrix(glm::dmat3(1.0));
  for (int l = 1; l <= 3; ++l) {
    const auto m = rot.band(l);
    const int n = 2 * l + 1;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) EXPECT_NEAR(m[i * n + j], i == j ? 1.0 : 0.0, kRotationTol) << l;
  }
}

TEST(ShRotate, RotateThenProjectEqualsProjectThenRotate) {
  math::Pcg32 rng(20);
  for (int trial = 0; trial < 20; ++trial) {
    const glm::dmat3 R = testutil::randomRotation(rng);
    const auto c = testutil::randomCoeffs(rng, 16);
    // Rotated function g(ω) = f(Rᵀω), projected exactly (degree 3 polynomial).
    const auto g = [&](const glm::dvec3& w) { return evalSum(c, glm::transpose(R) * w); };
    const auto projected = projectQuadrature(g, 4, 3);
    const auto rotated = Rotation<double>::fromMatrix(R).apply(c);
    for (int i = 0; i < 16; ++i) ASSERT_NEAR(rotated[i], projected[i], kRotationTol) << "trial " << trial << " i " << i;
  }
}

TEST(ShRotate, RotatedFunctionTakesOldValueAtRotatedDirection) {
  // g(Rω) = f(ω) for every order (lower orders use the leading bands only).
  math::Pcg32 rng(21);
  for (int order = 1; order <= 4; ++order) {
    const glm::dmat3 R = testutil::randomRotation(rng);
    const auto c = testutil::randomCoeffs(rng, coeffCount(order));
    const auto g = Rotation<double>::fromMatrix(R).apply(c);
    for (int s = 0; s < 20; ++s) {
      const glm::dvec3 w = testutil::randomDirection(rng);
      EXPECT_NEAR(evalSum(g, R * w), evalSum(c, w), kRotationTol);
    }
  }
}

TEST(ShRotate, CompositionMatchesProductOfRotations) {
  math::Pcg32 rng(22);
  for (int trial = 0; trial < 10; ++trial) {
    const glm::dmat3 R1 = testutil::randomRotation(rng), R2 = testutil::randomRotation(rng);
    const auto c = testutil::randomCoeffs(rng, 16);
    const auto both = Rotation<double>::fromMatrix(R1 * R2).apply(c);
    const auto inTurn = Rotation<double>::fromMatrix(R1).apply(Rotation<double>::fromMatrix(R2).apply(c));
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(both[i], inTurn[i], kRotationTol);
  }
}

TEST(ShRotate, BandMatricesAreOrthogonal) {
  math::Pcg32 rng(23);
  const auto rot = Rotation<double>::fromMatrix(testutil::randomRotation(rng));
  for (int l = 1; l <= 3; ++l) {
    const auto m = rot.band(l);
    const int n = 2 * l + 1;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        double dot = 0.0;
        for (int k = 0; k < n; ++k) dot += m[i * n + k] * m[j * n + k];
        EXPECT_NEAR(dot, i == j ? 1.0 : 0.0, kRotationTol);
      }
  }
}

TEST(ShRotate, BandOneIsTheVectorRotation) {
  // Band 1 of f(ω) = v·ω is c1·(v_y, v_z, v_x) with c1 = √(4π/3); rotating f gives (Rv)·ω.
  math::Pcg32 rng(24);
  const glm::dmat3 R = testutil::randomRotation(rng);
  const glm::dvec3 v(0.3, -1.2, 0.7);
  const std::vector<double> c = {0.0, v.y, v.z, v.x};
  const auto g = Rotation<double>::fromMatrix(R).apply(c);
  const glm::dvec3 rv = R * v;
  EXPECT_NEAR(g[0], 0.0, kRotationTol);
  EXPECT_NEAR(g[1], rv.y, kRotationTol);
  EXPECT_NEAR(g[2], rv.z, kRotationTol);
  EXPECT_NEAR(g[3], rv.x, kRotationTol);
}

TEST(ShRotate, ZonalFunctionsAreInvariantUnderRotationAboutZ) {
  std::vector<double> c(16, 0.0);
  for (int l = 0; l < 4; ++l) c[index(l, 0)] = 1.0 + l;
  for (double angle : {0.1, 1.0, 2.5, -3.0}) {
    const auto g = Rotation<double>::fromMatrix(rotationAboutZ(angle)).apply(c);
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(g[i], c[i], kRotationTol) << "angle " << angle << " i " << i;
  }
}

TEST(ShRotate, RotationAboutZMixesOnlyPlusMinusM) {
  // About Z, (Y_l,m, Y_l,-m) rotate by the angle m·α: the cos(mφ)/sin(mφ) pair.
  const double a = 0.7;
  const auto rot = Rotation<double>::fromMatrix(rotationAboutZ(a));
  for (int l = 1; l <= 3; ++l) {
    const auto m = rot.band(l);
    const int n = 2 * l + 1;
    for (int mm = 1; mm <= l; ++mm) {
      EXPECT_NEAR(m[(l + mm) * n + (l + mm)], std::cos(mm * a), kRotationTol);
      EXPECT_NEAR(m[(l - mm) * n + (l - mm)], std::cos(mm * a), kRotationTol);
      EXPECT_NEAR(std::abs(m[(l + mm) * n + (l - mm)]), std::abs(std::sin(mm * a)), kRotationTol);
    }
  }
}

TEST(ShRotate, ZonalShortcutEqualsFullRotation) {
  math::Pcg32 rng(25);
  const std::vector<double> zonal = {0.9, -0.4, 0.3, 0.2};
  std::vector<double> c(16, 0.0);
  for (int l = 0; l < 4; ++l) c[index(l, 0)] = zonal[l];
  for (int trial = 0; trial < 10; ++trial) {
    const glm::dvec3 d = testutil::randomDirection(rng);
    const auto full = Rotation<double>::fromMatrix(testutil::rotationZTo(d)).apply(c);
    const auto shortcut = rotateZonal<double>(zonal, d);
    ASSERT_EQ(shortcut.size(), 16u);
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(shortcut[i], full[i], kRotationTol) << i;
  }
  // Axis -Z (the half turn): odd bands flip sign.
  const auto down = rotateZonal<double>(zonal, glm::dvec3(0, 0, -1));
  for (int l = 0; l < 4; ++l) EXPECT_NEAR(down[index(l, 0)], (l % 2 ? -1.0 : 1.0) * zonal[l], kRotationTol);
}

TEST(ShRotate, QuaternionEqualsMatrixAndAcceptsUnnormalised) {
  math::Pcg32 rng(26);
  const glm::dquat q = testutil::randomQuaternion(rng);
  const auto a = Rotation<double>::fromQuaternion(q * 3.0);
  const auto b = Rotation<double>::fromMatrix(glm::mat3_cast(q));
  for (int l = 1; l <= 3; ++l)
    for (std::size_t i = 0; i < a.band(l).size(); ++i) EXPECT_NEAR(a.band(l)[i], b.band(l)[i], kRotationTol);
  EXPECT_THROW(Rotation<double>::fromQuaternion(glm::dquat(0, 0, 0, 0)), InternalError);
}

TEST(ShRotate, RejectsScaleAndReflection) {
  EXPECT_THROW(Rotation<double>::fromMatrix(glm::dmat3(2.0)), InternalError);
  EXPECT_THROW(Rotation<double>::fromMatrix(glm::dmat3(1, 0, 0, 0, 1, 0, 0, 0, -1)), InternalError);
  EXPECT_THROW(Rotation<double>::fromMatrix(rotationAboutZ(0.3)).band(4), InternalError);
}

TEST(ShRotate, FloatAndRgbAgreeWithDouble) {
  math::Pcg32 rng(27);
  const glm::dmat3 R = testutil::randomRotation(rng);
  const auto c = testutil::randomCoeffs(rng, 16);
  const auto gd = Rotation<double>::fromMatrix(R).apply(c);
  std::vector<float> cf(c.begin(), c.end());
  const auto gf = Rotation<float>::fromMatrix(glm::mat3(R)).apply(cf);
  std::vector<glm::vec3> rgb;
  for (double v : c) rgb.push_back(glm::vec3(float(v), float(2 * v), 0.0f));
  const auto grgb = Rotation<float>::fromMatrix(glm::mat3(R)).apply(rgb);
  for (int i = 0; i < 16; ++i) {
    EXPECT_NEAR(gf[i], gd[i], kFloatRotationTol);
    EXPECT_NEAR(grgb[i].x, gd[i], kFloatRotationTol);
    EXPECT_NEAR(grgb[i].y, 2 * gd[i], 2 * kFloatRotationTol);
    EXPECT_NEAR(grgb[i].z, 0.0, kFloatRotationTol);
  }
}
