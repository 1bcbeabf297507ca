// DNRT hard cases the issue names and the other tests do not reach: probe SH with strong negative
// lobes and very large or tiny magnitudes (Eq. 16 is linear in c_j, so the output must scale
// exactly and stay finite), and 8-bit saturation: coefficients at the edges of their range decode
// to the range ends exactly, and a range too wide for float arithmetic is refused, never decoded
// into Inf or NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/evaluate.hpp"
#include "tests/unit/dnrt/test_meshes.hpp"

namespace bounce::gi::dnrt {
namespace {

// Float rounding of one multiply per term against the same sum at unit scale: 1e-5 relative.
constexpr float kLinearityTol = 1e-5f;

const BakeResult& sphereField() {
  static const BakeResult r = [] {
    FieldSettings s;
    s.shCount = 9;
    s.grid = 8;
    s.samplesPerAxis = 8;
    return bake(testing::sphere(glm::vec3(0.0f), 1.0f, glm::vec3(0.6f, 0.3f, 0.1f), 16), s);
  }();
  return r;
}

// Irradiance coefficients dominated by negative lobes: the constant term is small and every
// higher band is negative and larger, so Σ c_j Y_j(n) is negative over much of the sphere.
std::array<glm::vec3, 9> negativeLobes(float scale) {
  std::array<glm::vec3, 9> c{};
  c[0] = glm::vec3(0.2f);
  for (int j = 1; j < 9; ++j) c[std::size_t(j)] = -glm::vec3(1.5f + 0.1f * j, 1.0f, 0.5f);
  for (auto& v : c) v *= scale;
  return c;
}

}  // namespace

TEST(DnrtHardCases, StrongNegativeLobesAndExtremeMagnitudesScaleLinearly) {
  const BakeResult& r = sphereField();
  const Placement pl = place(r.field, glm::mat4(1.0f));
  const auto unit = negativeLobes(1.0f);
  const glm::vec3 rho(0.5f, 0.7f, 0.9f);
  int nonZero = 0;
  for (const glm::vec3 p : {glm::vec3(1.5f, 0.0f, 0.0f), glm::vec3(0.0f, -1.2f, 0.4f), glm::vec3(-2.0f, 1.0f, 1.0f),
                            glm::vec3(0.0f, 0.0f, 2.9f), glm::vec3(4.0f, 0.0f, 0.0f)}) {
    const glm::vec3 n = -glm::normalize(p);  // facing the object
    const glm::vec3 base = evaluate(r.field, pl, unit, p, n, rho);
    ASSERT_TRUE(std::isfinite(base.x) && std::isfinite(base.y) && std::isfinite(base.z));
    nonZero += glm::length(base) > 0.0f;
    for (const float k : {1e-20f, 1e-6f, 1e4f, 1e20f}) {
      const glm::vec3 scaled = evaluate(r.field, pl, negativeLobes(k), p, n, rho);
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(scaled[c])) << "k " << k;
        EXPECT_NEAR(scaled[c] / k, base[c], kLinearityTol * std::max(1e-6f, std::abs(base[c]))) << "k " << k << " p " << p.x;
      }
    }
  }
  EXPECT_GE(nonZero, 4) << "the probe points must see the field";
}

TEST(DnrtHardCases, CoefficientsAtTheRangeEndsDecodeExactly) {
  FieldSettings s;
  s.shCount = 4;
  s.grid = 2;
  std::vector<glm::vec3> values(8 * 4);
  // Per slot, vertex 0 holds the minimum and vertex 7 the maximum; the rest lie between.
  for (std::size_t v = 0; v < 8; ++v)
    for (std::size_t j = 0; j < 4; ++j) values[v * 4 + j] = glm::vec3(-3.0f + v * (7.0f / 7.0f) + 0.25f * j);
  values[7 * 4 + 1] = glm::vec3(1e6f);  // one huge outlier: every other value of the slot rounds to 0
  const Field f = quantize(s, glm::vec3(0.0f), 1.0f, values);
  std::array<glm::vec3, 4> first{}, last{};
  f.decodeVertex(0, first);
  f.decodeVertex(7, last);
  for (std::size_t j = 0; j < 4; ++j) {
    EXPECT_EQ(first[j], values[j]) << "j " << j;
    EXPECT_EQ(last[j], values[7 * 4 + j]) << "j " << j;
  }
  for (std::size_t v = 0; v < 8; ++v) {
    std::array<glm::vec3, 4> m{};
    f.decodeVertex(v, m);
    for (const auto& x : m) ASSERT_TRUE(std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z));
  }
}

TEST(DnrtHardCases, RangeTooWideForFloatIsRefusedNotDecodedToNaN) {
  FieldSettings s;
  s.shCount = 4;
  s.grid = 2;
  std::vector<glm::vec3> values(8 * 4, glm::vec3(0.0f));
  const float big = 0.9f * std::numeric_limits<float>::max();
  values[0] = glm::vec3(-big);
  values[4] = glm::vec3(big);  // hi − lo overflows a float
  EXPECT_THROW(quantize(s, glm::vec3(0.0f), 1.0f, values), InternalError);
}

}  // namespace bounce::gi::dnrt
