// SamplingJob against hand-computed values: STEP, LINEAR (normalised slerp for rotations) and
// CUBICSPLINE (tangents × key interval), before the first key, after the last and single keys.
#include <cmath>

#include <gtest/gtest.h>

#include "engine/anim/sampling.hpp"

namespace bounce::anim {
namespace {

// Exact in fp32 for the linear cases (values chosen to be representable); the slerp and Hermite
// cases go through sin/acos and a few products, within a few ulps of 1.
constexpr float kExact = 0.0f;
constexpr float kUlps = 4e-7f;

asset::AnimationSampler scalar(asset::Interpolation i, std::vector<float> in, std::vector<float> out) {
  asset::AnimationSampler s;
  s.input = std::move(in);
  s.output = std::move(out);
  s.components = 1;
  s.interpolation = i;
  return s;
}

float sample(const asset::AnimationSampler& s, float t) {
  float v = NAN;
  EXPECT_TRUE((SamplingJob{&s, t, ValueKind::Vector, std::span<float>(&v, 1)}.run()));
  return v;
}

TEST(Sampling, StepHoldsTheKeyAtOrBefore) {
  const auto s = scalar(asset::Interpolation::Step, {1, 2, 4}, {10, 20, 40});
  EXPECT_EQ(sample(s, 0.5f), 10.0f);  // before the first key
  EXPECT_EQ(sample(s, 1.0f), 10.0f);
  EXPECT_EQ(sample(s, 1.999f), 10.0f);
  EXPECT_EQ(sample(s, 2.0f), 20.0f);
  EXPECT_EQ(sample(s, 3.9f), 20.0f);
  EXPECT_EQ(sample(s, 4.0f), 40.0f);
  EXPECT_EQ(sample(s, 9.0f), 40.0f);  // after the last key
}

TEST(Sampling, LinearInterpolatesEachComponent) {
  const auto s = scalar(asset::Interpolation::Linear, {1, 2, 4}, {10, 20, 40});
  EXPECT_NEAR(sample(s, 0.0f), 10.0f, kExact);
  EXPECT_NEAR(sample(s, 1.5f), 15.0f, kExact);
  EXPECT_NEAR(sample(s, 3.0f), 30.0f, kExact);
  EXPECT_NEAR(sample(s, 3.5f), 35.0f, kExact);
  EXPECT_NEAR(sample(s, 5.0f), 40.0f, kExact);
  // Vectors: every component, one time.
  asset::AnimationSampler v;
  v.input = {0, 2};
  v.output = {0, 0, 0, 2, 4, -8};
  v.components = 3;
  float out[3];
  ASSERT_TRUE((SamplingJob{&v, 0.5f, ValueKind::Vector, out}.run()));
  EXPECT_EQ(out[0], 0.5f);
  EXPECT_EQ(out[1], 1.0f);
  EXPECT_EQ(out[2], -2.0f);
}

TEST(Sampling, LinearRotationIsNormalisedSlerpAlongTheShorterArc) {
  // Identity to 90° about Z: half way is 45° about Z = (0, 0, sin 22.5°, cos 22.5°).
  const float h = std::sqrt(0.5f);
  asset::AnimationSampler r;
  r.input = {0, 1};
  r.output = {0, 0, 0, 1, 0, 0, h, h};
  r.components = 4;
  float q[4];
  ASSERT_TRUE((SamplingJob{&r, 0.5f, ValueKind::Rotation, q}.run()));
  EXPECT_NEAR(q[0], 0.0f, kUlps);
  EXPECT_NEAR(q[1], 0.0f, kUlps);
  EXPECT_NEAR(q[2], 0.38268343f, kUlps);
  EXPECT_NEAR(q[3], 0.92387953f, kUlps);
  // A quarter of the way: 22.5° about Z (slerp, not lerp: a normalised lerp would give z = 0.18737).
  ASSERT_TRUE((SamplingJob{&r, 0.25f, ValueKind::Rotation, q}.run()));
  EXPECT_NEAR(q[2], 0.19509032f, kUlps);
  EXPECT_NEAR(q[3], 0.98078528f, kUlps);
  // The second key negated (same rotation): the shorter arc gives the same result.
  r.output = {0, 0, 0, 1, 0, 0, -h, -h};
  ASSERT_TRUE((SamplingJob{&r, 0.5f, ValueKind::Rotation, q}.run()));
  EXPECT_NEAR(q[2], 0.38268343f, kUlps);
  EXPECT_NEAR(q[3], 0.92387953f, kUlps);
  EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0f, 2 * kUlps);
}

TEST(Sampling, CubicSplineScalesTangentsByTheKeyInterval) {
  // Keys at t = 1 and 3 (td = 2), each [in-tangent, value, out-tangent]:
  // key 0: a=0, v=0, b=1; key 1: a=2, v=1, b=0. At s = 0.5 the Hermite basis is h00 = 0.5,
  // h10 = 0.125, h01 = 0.5, h11 = −0.125, so p = 0.5·0 + 2·0.125·1 + 0.5·1 + 2·(−0.125)·2 = 0.25.
  const auto s = scalar(asset::Interpolation::CubicSpline, {1, 3}, {0, 0, 1, 2, 1, 0});
  EXPECT_NEAR(sample(s, 2.0f), 0.25f, kUlps);
  // s = 0.25: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = −0.046875 →
  // 2·0.140625 + 0.15625 − 2·0.046875·2 = 0.25.
  EXPECT_NEAR(sample(s, 1.5f), 0.25f, kUlps);
  EXPECT_EQ(sample(s, 1.0f), 0.0f);  // the values, never the tangents, at and outside the keys
  EXPECT_EQ(sample(s, 0.0f), 0.0f);
  EXPECT_EQ(sample(s, 3.0f), 1.0f);
  EXPECT_EQ(sample(s, 7.0f), 1.0f);
}

TEST(Sampling, CubicSplineRotationIsNormalised) {
  const float h = std::sqrt(0.5f);
  asset::AnimationSampler r;
  r.input = {0, 1};
  r.output = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0,   // key 0: a, v = identity, b
              0, 0, 0, 0, 0, 0, h, h, 0, 0, 0, 0};  // key 1: a, v = 90° about Z, b
  r.components = 4;
  r.interpolation = asset::Interpolation::CubicSpline;
  float q[4];
  ASSERT_TRUE((SamplingJob{&r, 0.5f, ValueKind::Rotation, q}.run()));
  // Zero tangents: 0.5·(identity + q1) normalised = 45° about Z.
  EXPECT_NEAR(q[2], 0.38268343f, kUlps);
  EXPECT_NEAR(q[3], 0.92387953f, kUlps);
}

TEST(Sampling, SingleKeyIsConstant) {
  for (auto i : {asset::Interpolation::Step, asset::Interpolation::Linear}) {
    const auto s = scalar(i, {2}, {7});
    for (float t : {-1.0f, 0.0f, 2.0f, 100.0f}) EXPECT_EQ(sample(s, t), 7.0f);
  }
  const auto c = scalar(asset::Interpolation::CubicSpline, {2}, {9, 7, 9});
  for (float t : {-1.0f, 2.0f, 100.0f}) EXPECT_EQ(sample(c, t), 7.0f);
}

TEST(Sampling, ValidateRejectsMismatchedShapes) {
  const auto s = scalar(asset::Interpolation::Linear, {0, 1}, {0, 1});
  float two[2];
  EXPECT_FALSE((SamplingJob{&s, 0.5f, ValueKind::Vector, two}.validate()));      // span of 2 for 1 component
  EXPECT_FALSE((SamplingJob{&s, 0.5f, ValueKind::Rotation, std::span<float>(two, 1)}.validate()));  // not 4 components
  EXPECT_FALSE((SamplingJob{nullptr, 0.5f, ValueKind::Vector, std::span<float>(two, 1)}.validate()));
  EXPECT_FALSE((SamplingJob{&s, NAN, ValueKind::Vector, std::span<float>(two, 1)}.validate()));
  auto bad = s;
  bad.interpolation = asset::Interpolation::CubicSpline;  // 2 values for 2 keys × 3
  EXPECT_FALSE((SamplingJob{&bad, 0.5f, ValueKind::Vector, std::span<float>(two, 1)}.run()));
  EXPECT_TRUE((SamplingJob{&s, 0.5f, ValueKind::Vector, std::span<float>(two, 1)}.validate()));
}

TEST(Sampling, ClipDurationIsTheLastKeyOverAllSamplers) {
  asset::Animation a;
  a.samplers = {scalar(asset::Interpolation::Linear, {0, 1.5f}, {0, 1}), scalar(asset::Interpolation::Step, {0.5f, 2.25f}, {0, 1})};
  EXPECT_EQ(clipDuration(a), 2.25f);
  EXPECT_EQ(clipDuration(asset::Animation{}), 0.0f);
}

}  // namespace
}  // namespace bounce::anim
