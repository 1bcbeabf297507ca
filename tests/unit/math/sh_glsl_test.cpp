// shaders/common/sh.glsl compiled as C++ against glm and compared with engine/math. The file
// keeps to the GLSL/C++ common subset for exactly this purpose; the GPU run of
// sh_selftest.comp checks the compiled shader on a device.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "engine/math/sh_convolve.hpp"
#include "engine/math/sh_eval.hpp"
#include "test_util.hpp"

namespace glsl {
using namespace glm;
// GLSL parameter qualifiers: `out float y[9]` becomes a decayed pointer, so writes reach the
// caller as they do in GLSL; `in` is the default.
#define in
#define out
#include "shaders/common/sh.glsl"
#undef in
#undef out
}  // namespace glsl

using namespace bounce;
using namespace bounce::sh;

namespace {
// Both sides evaluate the same float polynomials; the compiler may contract or reorder
// differently: a few float ulps of values <= ~3.
constexpr double kFloatTol = 2e-6;
// Irradiance sums 9 terms of magnitude up to ~π·3: a few ulps of ~10.
constexpr double kIrradianceTol = 1e-5;
}  // namespace

TEST(ShGlsl, ConstantsEqualEngineConstants) {
  using namespace constants;
  EXPECT_EQ(glsl::SH_Y00, float(kY00));
  EXPECT_EQ(glsl::SH_Y1, float(kY1));
  EXPECT_EQ(glsl::SH_Y2A, float(kY2a));
  EXPECT_EQ(glsl::SH_Y20, float(kY20));
  EXPECT_EQ(glsl::SH_Y22, float(kY22));
  EXPECT_EQ(glsl::SH_Y33, float(kY33));
  EXPECT_EQ(glsl::SH_Y32A, float(kY32a));
  EXPECT_EQ(glsl::SH_Y31, float(kY31));
  EXPECT_EQ(glsl::SH_Y30, float(kY30));
  EXPECT_EQ(glsl::SH_Y32B, float(kY32b));
  EXPECT_EQ(glsl::SH_A0, float(cosineLobeBand(0)));
  EXPECT_EQ(glsl::SH_A1, float(cosineLobeBand(1)));
  EXPECT_EQ(glsl::SH_A2, float(cosineLobeBand(2)));
}

TEST(ShGlsl, EvaluationMatchesEngineForEveryOrder) {
  math::Pcg32 rng(50);
  for (int s = 0; s < 500; ++s) {
    const glm::vec3 d(testutil::randomDirection(rng));
    const auto e = evalBasis<float>(4, d);
    float y4[4], y9[9], y16[16];
    glsl::shEval4(d, y4);
    glsl::shEval9(d, y9);
    glsl::shEval16(d, y16);
    for (int i = 0; i < 4; ++i) ASSERT_NEAR(y4[i], e[i], kFloatTol);
    for (int i = 0; i < 9; ++i) ASSERT_NEAR(y9[i], e[i], kFloatTol);
    for (int i = 0; i < 16; ++i) ASSERT_NEAR(y16[i], e[i], kFloatTol);
  }
}

TEST(ShGlsl, EvalSumAndIrradianceMatchEngine) {
  math::Pcg32 rng(51);
  std::vector<glm::vec3> c(16);
  for (auto& v : c) {
    const double y = rng.nextDouble() - 0.5, x = rng.nextDouble();  // sequenced (see Pcg32::nextFloat3)
    v = glm::vec3(float(x), float(y), 1.0f);
  }
  for (int s = 0; s < 200; ++s) {
    const glm::vec3 n(testutil::randomDirection(rng));
    for (int order : {2, 3, 4}) {
      const std::span<const glm::vec3> cs(c.data(), coeffCount(order));
      const glm::vec3 eSum = evalSum<glm::vec3, float>(cs, n);
      const glm::vec3 eIrr = evalIrradiance<glm::vec3, float>(cs, n);
      glm::vec3 gSum, gIrr;
      if (order == 2) gSum = glsl::shEvalSum4(c.data(), n), gIrr = glsl::shIrradiance4(c.data(), n);
      if (order == 3) gSum = glsl::shEvalSum9(c.data(), n), gIrr = glsl::shIrradiance9(c.data(), n);
      if (order == 4) gSum = glsl::shEvalSum16(c.data(), n), gIrr = glsl::shIrradiance16(c.data(), n);
      for (int k = 0; k < 3; ++k) {
        ASSERT_NEAR(gSum[k], eSum[k], kIrradianceTol) << "order " << order;
        ASSERT_NEAR(gIrr[k], eIrr[k], kIrradianceTol) << "order " << order;
      }
    }
  }
}
