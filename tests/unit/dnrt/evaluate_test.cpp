// Runtime math (evaluate.hpp, mirrored by shaders/dnrt): rotating the object and the lighting
// together leaves L_DNRT unchanged, including 180° turns and quaternion sign flips; uniform scale
// 1e-3 and 1e3; the §5.2.2 fall-off is continuous at both boundaries.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/evaluate.hpp"
#include "engine/gi/dnrt/gpu_object.hpp"
#include "engine/gi/dnrt/irradiance_source.hpp"
#include "engine/math/sh.hpp"
#include "tests/unit/dnrt/test_meshes.hpp"

namespace bounce::gi::dnrt {
namespace {

// float rounding through the 4×4 inverse, SH rotation (≤ 1e-5 per entry) and trilinear weights:
// 1e-4 of the largest value checked.
constexpr float kRelTol = 1e-4f;

const BakeResult& twoTone() {
  static const BakeResult r = [] {
    FieldSettings s;
    s.shCount = 9;
    s.grid = 10;
    s.samplesPerAxis = 8;
    return bake(testing::twoToneSphere(glm::vec3(0.3f, -0.2f, 0.1f), 1.0f, glm::vec3(0.9f, 0.2f, 0.1f),
                                       glm::vec3(0.1f, 0.3f, 0.9f), 24),
                s);
  }();
  return r;
}

// Radiance with strong l = 1 and l = 2 content (negative lobes included: nothing here needs L > 0).
std::array<glm::vec3, 9> skyRadiance() {
  std::array<glm::vec3, 9> L{};
  const float v[9] = {3.0f, 0.8f, 1.4f, -0.6f, 0.5f, -0.9f, 0.7f, 0.4f, -1.1f};
  for (int i = 0; i < 9; ++i) L[std::size_t(i)] = v[i] * glm::vec3(1.0f, 0.7f + 0.05f * i, 0.5f);
  return L;
}

std::array<glm::vec3, 9> rotateRadiance(const std::array<glm::vec3, 9>& L, const glm::quat& q) {
  const auto r = sh::Rotationf::fromQuaternion(q);
  std::array<glm::vec3, 9> out{};
  r.apply<glm::vec3>(std::span<const glm::vec3>(L), std::span<glm::vec3>(out));
  return out;
}

struct Probe {
  glm::vec3 local, normal;
};
std::vector<Probe> probes() {
  std::vector<Probe> p;
  math::Pcg32 rng(11);
  for (int i = 0; i < 40; ++i) {
    const glm::vec3 dir = glm::vec3(math::uniformSphere(rng.next2D()));
    const float d = 1.3f + 3.5f * rng.nextFloat();  // in units of R, inner cube and outer shell
    const glm::vec3 n = glm::normalize(-dir + 0.5f * glm::vec3(math::uniformSphere(rng.next2D())));
    p.push_back({glm::vec3(0.3f, -0.2f, 0.1f) + d * dir, n});
  }
  return p;
}

void expectInvariant(const glm::quat& q, glm::vec3 translate, float scale) {
  const BakeResult& r = twoTone();
  const auto L = skyRadiance();
  const auto cRef = toLocal(irradianceSH(L), glm::mat3(1.0f));
  const Placement ref = place(r.field, glm::mat4(1.0f));
  const glm::mat4 world =
      glm::translate(glm::mat4(1.0f), translate) * glm::mat4_cast(q) * glm::scale(glm::mat4(1.0f), glm::vec3(scale));
  const Placement pl = place(r.field, world);
  const auto c = toLocal(irradianceSH(rotateRadiance(L, q)), pl.localToWorldRotation);
  const glm::mat3 rot = glm::mat3_cast(q);
  float largest = 0.0f, worst = 0.0f;
  int nonzero = 0;
  for (const Probe& p : probes()) {
    const glm::vec3 want = evaluate(r.field, ref, cRef, p.local, p.normal, glm::vec3(0.8f));
    const glm::vec3 got =
        evaluate(r.field, pl, c, glm::vec3(world * glm::vec4(p.local, 1.0f)), rot * p.normal, glm::vec3(0.8f));
    largest = std::max(largest, glm::length(want));
    worst = std::max(worst, glm::length(got - want));
    nonzero += glm::length(want) > 0.0f ? 1 : 0;
  }
  EXPECT_GT(nonzero, 20);
  EXPECT_LE(worst, kRelTol * largest) << "q " << q.w << " " << q.x << " " << q.y << " " << q.z << " scale " << scale;
}

TEST(DnrtEvaluate, RotatingObjectAndLightingTogetherChangesNothing) {
  expectInvariant(glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3))), glm::vec3(4, -1, 2), 1.0f);
  expectInvariant(glm::angleAxis(2.9f, glm::normalize(glm::vec3(-1, 0.2f, 0.5f))), glm::vec3(0), 1.0f);
}

TEST(DnrtEvaluate, HalfTurnsAndQuaternionSignFlips) {
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1),
                               glm::normalize(glm::vec3(1, 1, 0))}) {
    const glm::quat q = glm::angleAxis(glm::pi<float>(), axis);
    expectInvariant(q, glm::vec3(1, 2, 3), 1.0f);
    expectInvariant(-q, glm::vec3(1, 2, 3), 1.0f);
  }
  const glm::quat q = glm::angleAxis(1.1f, glm::normalize(glm::vec3(0.3f, -1, 0.2f)));
  expectInvariant(-q, glm::vec3(0), 1.0f);
}

TEST(DnrtEvaluate, ScaleInvariance) {
  const glm::quat q = glm::angleAxis(0.4f, glm::normalize(glm::vec3(0, 1, 1)));
  expectInvariant(q, glm::vec3(0.01f, 0.0f, -0.02f), 1e-3f);
  expectInvariant(q, glm::vec3(1000.0f, 50.0f, 0.0f), 1e3f);
}

TEST(DnrtEvaluate, FalloffIsContinuousAndMonotone) {
  FieldSettings s;
  s.innerExtent = 2.0f;
  s.outerExtent = 5.0f;
  EXPECT_EQ(falloff(s, glm::vec3(0.0f, 2.0f, 0.0f)), 1.0f);
  EXPECT_NEAR(falloff(s, glm::vec3(0.0f, 2.0001f, 0.0f)), 1.0f, 1e-3f);
  EXPECT_NEAR(falloff(s, glm::vec3(0.0f, 0.0f, -4.9999f)), 0.0f, 1e-4f);
  EXPECT_EQ(falloff(s, glm::vec3(5.0f, 0.0f, 0.0f)), 0.0f);
  float prev = 1.0f;
  for (float u = 2.0f; u <= 5.0f; u += 0.01f) {
    const float f = falloff(s, glm::vec3(u, 0.3f, -1.0f));
    EXPECT_LE(f, prev);
    EXPECT_GE(f, 0.0f);
    prev = f;
  }
}

TEST(DnrtEvaluate, OutputIsFiniteNearTheSurfaceCentreAndBoundaries) {
  const BakeResult& r = twoTone();
  const Placement pl = place(r.field, glm::mat4(1.0f));
  const auto c = toLocal(irradianceSH(skyRadiance()), glm::mat3(1.0f));
  const glm::vec3 o = r.field.centre;
  const float inner = r.field.settings.innerExtent, outer = r.field.settings.outerExtent, R = r.field.radius;
  for (const glm::vec3 p : {o, o + glm::vec3(R, 0, 0), o + glm::vec3(0, -R * 1.0001f, 0), o + glm::vec3(inner * R, 0, 0),
                            o + glm::vec3(0, 0, outer * R), o + glm::vec3(outer * R * 2.0f, 0, 0)}) {
    const glm::vec3 n = glm::length(o - p) > 0.0f ? glm::normalize(o - p) : glm::vec3(0, 1, 0);
    const glm::vec3 v = evaluate(r.field, pl, c, p, n, glm::vec3(1.0f));
    EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
    EXPECT_LT(glm::length(v), 100.0f);
  }
  EXPECT_EQ(evaluate(r.field, pl, c, o, glm::vec3(0, 1, 0), glm::vec3(1.0f)), glm::vec3(0.0f));
  EXPECT_EQ(evaluate(r.field, pl, c, o + glm::vec3(outer * R, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(1.0f)),
            glm::vec3(0.0f));
}

}  // namespace
}  // namespace bounce::gi::dnrt

namespace bounce::gi::dnrt {
namespace {

// The GPU record holds what evaluate() uses: ranges per slot, c_j in the local frame, and a box
// whose corners are the outer cube's (so rasterising it covers every pixel with s > 0).
TEST(DnrtEvaluate, GpuRecordMatchesPlacement) {
  const BakeResult& r = twoTone();
  const glm::quat q = glm::angleAxis(0.9f, glm::normalize(glm::vec3(1, -2, 0.5f)));
  const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, -1)) * glm::mat4_cast(q) *
                          glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
  const DnrtObjectGpu g = packObject(r.field, world, skyRadiance());
  const Placement pl = place(r.field, world);
  const auto c = toLocal(irradianceSH(skyRadiance()), pl.localToWorldRotation);
  for (int j = 0; j < 9; ++j) EXPECT_LT(glm::length(glm::vec3(g.c[j]) - c[std::size_t(j)]), 1e-5f);
  EXPECT_EQ(g.extents, glm::vec4(r.field.settings.innerExtent, r.field.settings.outerExtent, 9.0f, 10.0f));
  EXPECT_EQ(g.lo[6][2], r.field.ranges[6 * 4 + 2].lo);
  EXPECT_NEAR(g.centreWorld.w, 0.5f * r.field.radius, 1e-6f);
  for (const glm::vec3 corner : {glm::vec3(1, 1, 1), glm::vec3(-1, 1, -1)}) {
    const glm::vec3 w = glm::vec3(g.boxToWorld * glm::vec4(corner, 1.0f));
    const glm::vec3 qLocal = (glm::vec3(pl.worldToLocal * glm::vec4(w, 1.0f)) - r.field.centre) / r.field.radius;
    EXPECT_NEAR(std::max({std::abs(qLocal.x), std::abs(qLocal.y), std::abs(qLocal.z)}), r.field.settings.outerExtent, 1e-4f);
  }
}

}  // namespace
}  // namespace bounce::gi::dnrt
