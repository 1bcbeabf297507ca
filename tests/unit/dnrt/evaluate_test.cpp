// Runtime math (evaluate.hpp, mirrored by shaders/dnrt): rotating the object and the lighting
// together leaves L_DNRT unchanged, including 180° turns and quaternion sign flips; uniform scale
// 1e-3 and 1e3; the §5.2.2 fall-off is continuous at both boundaries.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/evaluate.hpp"
#include "engine/gi/dnrt/gpu_object.hpp"
#include "engine/gi/dnrt/irradiance_source.hpp"
#include "engine/math/sh.hpp"
#include "engine/math/sh_eval.hpp"
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
  expectInvariant(q, glm::vec3(0.0f), 1e-12f);  // det 1e-36: threw "singular" before session 13
}

// A tiny object is a valid object (gi::place): any uniform scale whose inverse a float holds places
// as at unit scale — the same rotation and mirror flag, radius × s, worldToLocal the inverse —
// where a float determinant (s³) underflowed below s ≈ 1e-10 and threw. Singular or non-finite
// transforms and scales past the float range (the inverse overflows) still throw InternalError.
TEST(DnrtPlacement, TinyUniformScalesPlaceAsAtUnitScale) {
  const glm::quat q = glm::angleAxis(0.9f, glm::normalize(glm::vec3(0.4f, -1, 0.3f)));
  const glm::vec3 centre(0.3f, -0.2f, 0.1f);
  const auto world = [&](float s, float mirror) {
    return glm::translate(glm::mat4(1.0f), s * glm::vec3(1, 0.5f, -2)) * glm::mat4_cast(q) *
           glm::scale(glm::mat4(1.0f), s * glm::vec3(mirror, 1, 1));
  };
  for (const float mirror : {1.0f, -1.0f}) {
    const Placement unit = gi::place(centre, 2.0f, world(1.0f, mirror), "test");
    EXPECT_EQ(unit.mirrored, mirror < 0.0f);
    for (const float s : {1e-10f, 1e-15f, 1e-20f, 1e-29f}) {
      const Placement p = gi::place(centre, 2.0f, world(s, mirror), "test");
      const std::string at = "scale " + std::to_string(s) + " mirror " + std::to_string(mirror);
      EXPECT_EQ(p.mirrored, unit.mirrored) << at;
      for (int c = 0; c < 3; ++c) EXPECT_LE(glm::length(p.localToWorldRotation[c] - unit.localToWorldRotation[c]), 1e-6f) << at;
      EXPECT_NEAR(p.radiusWorld / s, 2.0f, 2e-6f) << at;
      EXPECT_LE(glm::length(p.centreWorld / s - unit.centreWorld), 1e-5f) << at;
      const glm::mat4 id = p.worldToLocal * world(s, mirror);
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(id[c][r], c == r ? 1.0f : 0.0f, 1e-5f) << at << " [" << c << "][" << r << "]";
    }
  }
  const float inf = std::numeric_limits<float>::infinity();
  // A world radius 2s under 1e-30: the unit-frame map's entries 1/(2s) pass kMaxToUnit.
  EXPECT_THROW(gi::place(centre, 2.0f, world(1e-31f, 1.0f), "test"), InternalError);
  EXPECT_THROW(gi::place(centre, 2.0f, world(1e-40f, 1.0f), "test"), InternalError);  // 1/s overflows a float
  EXPECT_THROW(gi::place(centre, 2.0f, glm::scale(glm::mat4(1.0f), glm::vec3(1, 0, 1)), "test"), InternalError);
  EXPECT_THROW(gi::place(centre, 2.0f, glm::scale(glm::mat4(1.0f), glm::vec3(1, inf, 1)), "test"), InternalError);
  EXPECT_THROW(gi::place(centre, 2.0f, glm::translate(glm::mat4(1.0f), glm::vec3(std::nanf(""), 0, 0)), "test"),
               InternalError);
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

namespace bounce::gi::dnrt {
namespace {

// What the shader reads (fold) is the record regrouped: q from the folded rows equals
// (worldToLocal·r − o_local)/R_local, and a + Σ_slot dot(k, t) equals Σ_j c_j (lo + (hi − lo)·t)
// per channel for any unorm texels t (Table 2's slot layout), 9 SH and 4 SH.
TEST(DnrtEvaluate, FoldedShaderRecordRegroupsTheRecord) {
  const BakeResult& r = twoTone();
  const glm::quat rot = glm::angleAxis(-1.3f, glm::normalize(glm::vec3(0.2f, 1, -0.7f)));
  const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(-1, 2, 0.5f)) * glm::mat4_cast(rot) *
                          glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
  for (const int shCount : {9, 4}) {
    DnrtObjectGpu g = packObject(r.field, world, skyRadiance(), 41);
    if (shCount == 4)
      for (int j = 4; j < 9; ++j) g.c[j] = glm::vec4(0.0f);  // packObject's 4-SH record
    const DnrtShaderObject f = fold(g);
    EXPECT_EQ(f.ids.x, 42u);
    EXPECT_EQ(f.extents, g.extents);
    EXPECT_EQ(f.boxToWorld, g.boxToWorld);
    for (const glm::vec3 p : {glm::vec3(0.0f), glm::vec3(1.5f, -2.0f, 0.25f), glm::vec3(-3, 1, 4)}) {
      const glm::vec4 p4(p, 1.0f);
      const glm::vec3 expected = (glm::vec3(g.worldToLocal * p4) - glm::vec3(g.centreLocal)) / g.centreLocal.w;
      const glm::vec3 got(glm::dot(f.worldToQ[0], p4), glm::dot(f.worldToQ[1], p4), glm::dot(f.worldToQ[2], p4));
      EXPECT_LT(glm::length(got - expected), kRelTol * (1.0f + glm::length(expected))) << shCount;
    }
    std::uint32_t seed = 12345u;
    const auto unorm = [&] { return float((seed = seed * 1664525u + 1013904223u) >> 24) / 255.0f; };
    for (int trial = 0; trial < 20; ++trial) {
      glm::vec4 t[7];
      for (auto& v : t) v = glm::vec4(unorm(), unorm(), unorm(), unorm());
      // The record's decode, slot by slot (Table 2), then Σ_j c_j M_j per channel.
      glm::vec4 m[7];
      for (int s = 0; s < 7; ++s) m[s] = g.lo[s] + (g.hi[s] - g.lo[s]) * t[s];
      glm::vec3 expected(0.0f), got(f.a);
      for (int ch = 0; ch < 3; ++ch) {
        for (int i = 0; i < 4; ++i) expected[ch] += g.c[i][ch] * m[ch][i] + g.c[4 + i][ch] * m[3 + ch][i];
        expected[ch] += g.c[8][ch] * m[6][ch];
      }
      got += glm::vec3(glm::dot(f.k[0], t[0]), glm::dot(f.k[1], t[1]), glm::dot(f.k[2], t[2]));
      got += glm::vec3(glm::dot(f.k[3], t[3]), glm::dot(f.k[4], t[4]), glm::dot(f.k[5], t[5]));
      got += glm::vec3(f.k[6]) * glm::vec3(t[6]);
      float scale = 0.0f;  // Σ |c·lo| + |c·hi|: the size of the terms that cancel
      for (int s = 0; s < 7; ++s) scale += glm::length(g.lo[s]) + glm::length(g.hi[s]);
      float cmax = 0.0f;
      for (int j = 0; j < 9; ++j) cmax = std::max(cmax, glm::length(glm::vec3(g.c[j])));
      EXPECT_LT(glm::length(got - expected), kRelTol * scale * cmax) << "SH " << shCount << " trial " << trial;
      if (shCount == 4) {
        for (int s = 3; s < 7; ++s) EXPECT_EQ(f.k[s], glm::vec4(0.0f)) << "4 SH: slots 3..6 never count";
      }
    }
  }
}

}  // namespace
}  // namespace bounce::gi::dnrt

namespace bounce::gi::dnrt {
namespace {

// A mirrored object (det(world) < 0): its c_j are the world irradiance seen through the mirror,
// Σ c_j Y_j(n) = Σ c_world_j Y_j(M n) for every local direction n (M: world's normalised columns),
// and its box keeps a positive determinant (its back faces stay back faces, gpu_object.cpp).
TEST(DnrtEvaluate, MirroredObjectSeesTheWorldThroughItsMirror) {
  const BakeResult& r = twoTone();
  const glm::quat q = glm::angleAxis(0.9f, glm::normalize(glm::vec3(0.4f, -1, 0.3f)));
  const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(1, 0.5f, -2)) * glm::mat4_cast(q) *
                          glm::scale(glm::mat4(1.0f), glm::vec3(-0.5f, 0.5f, 0.5f));
  const DnrtObjectGpu g = packObject(r.field, world, skyRadiance());
  const auto cWorld = irradianceSH(skyRadiance());
  const glm::mat3 M = glm::mat3(glm::mat4_cast(q)) * glm::mat3(glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1)));
  EXPECT_TRUE(place(r.field, world).mirrored);
  EXPECT_GT(glm::determinant(glm::mat3(g.boxToWorld)), 0.0f);
  // The same at a scale place() accepts but whose float det(world) is 0 (1e-16³ underflows): the box
  // flip follows the placement's flag, so the box's determinant (in double) stays positive.
  const glm::mat4 tiny = world * glm::scale(glm::mat4(1.0f), glm::vec3(1e-16f));
  ASSERT_EQ(glm::determinant(glm::mat3(tiny)), 0.0f);
  EXPECT_GT(glm::determinant(glm::dmat3(glm::mat3(packObject(r.field, tiny, skyRadiance()).boxToWorld))), 0.0);
  float worst = 0.0f, largest = 0.0f;
  for (const glm::vec3 n : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::normalize(glm::vec3(1, 2, -3)),
                            glm::normalize(glm::vec3(-2, 0.5f, 1)), glm::normalize(glm::vec3(0.3f, -1, -0.2f))}) {
    const auto yl = sh::evalBasis<float>(3, n), yw = sh::evalBasis<float>(3, M * n);
    glm::vec3 local(0.0f), seen(0.0f);
    for (std::size_t j = 0; j < 9; ++j) local += glm::vec3(g.c[j]) * yl[j], seen += cWorld[j] * yw[j];
    worst = std::max(worst, glm::length(local - seen));
    largest = std::max(largest, glm::length(seen));
  }
  EXPECT_LT(worst, 1e-4f * largest) << "largest " << largest;
}

}  // namespace
}  // namespace bounce::gi::dnrt
