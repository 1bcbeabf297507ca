// The objects' shared occlusion (overlap.hpp, README RTF "Seventh pass"): per sample of A,
// s = 1 − ½ W_B(p)·∫(1 − V_A)(1 − V_B) dω / ∫(1 − V_A) dω, with OOFs set by hand so the integrals are
// known numbers: (1 − V) = c_0·Y_00 + c_z·Y_1,0 at every sample of a field (coefficient 2 is the z
// lobe), W_B(p) the sum of B's lookup weights at p (1 inside B's field, its end's fraction past r_N).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gi/rtf/overlap.hpp"

namespace bounce::gi::rtf {
namespace {

constexpr float kU = kUnitVisibility;  // √(4π)

// A field of 5 spheres (0.5–4 η), 6·3² directions, radius 0.5 m, every sample's (1 − V) = (c0, 0, cz, 0, …).
Field handField(float c0, float cz, int lobe = 2) {
  Field f;
  f.settings.spheres = 5;
  f.settings.faceSize = 3;
  f.settings.innerRadius = 0.5f;
  f.settings.outerRadius = 4.0f;
  f.centre = glm::vec3(0.0f);
  f.radius = 0.5f;
  f.oof.assign(sampleCount(f.settings) * kShCount, 0.0f);
  for (std::size_t s = 0; s < sampleCount(f.settings); ++s) {
    f.oof[s * kShCount + 0] = kU - c0;  // V = u·Y_00 − (1 − V)
    f.oof[s * kShCount + std::size_t(lobe)] = -cz;
  }
  return f;
}

TEST(RtfOverlap, OneObjectAloneOrOutOfReachKeepsTheLightAtO) {
  const Field a = handField(2.0f, 0.8f), b = handField(1.5f, 0.6f);
  const std::vector<Object> alone = {{&a, glm::mat4(1.0f), 0.0f}};
  const OcclusionShares one = sharedOcclusion(alone, 0);
  for (const glm::vec4& s : one.scale) EXPECT_EQ(s, glm::vec4(1.0f));
  for (float w : one.onObjects) EXPECT_EQ(w, 1.0f);
  // B's centre 9.5 m away: A's samples reach 4.875·0.5 m, B's field as far: no sample shares.
  const std::vector<Object> apart = {{&a, glm::mat4(1.0f), 0.0f}, {&b, glm::translate(glm::mat4(1.0f), glm::vec3(9.5f, 0, 0)), 0.0f}};
  const OcclusionShares far = sharedOcclusion(apart, 0);
  for (const glm::vec4& s : far.scale) EXPECT_EQ(s, glm::vec4(1.0f));
  for (float w : far.onObjects) EXPECT_EQ(w, 1.0f);
}

// Checks every sample of A (world wa) against B (world wb): s = 1 − ½ W_B(p)·(2·1.5 + lobe)/(2√(4π)) with
// W_B(p) from B's lookup at p, `full` where W_B = 1, and all three kinds of sample (W_B = 1, its end, beyond).
// The share of A's light B lets through, 1 − W_B(p)·(2·1.5 + lobe)/(2√(4π)): off the objects (the 4th
// component, w_off) where B's centre is nearer to p than A's (Algorithm 1's order), else 1; on an object
// (onObjects, w_on) only where p also lies outside B's bounding sphere (inside it the receivers are B's own
// surface, which Algorithm 1 leaves B out for), else 1. Every kind occurs, inside B's sphere too.
void expectShared(const Field& a, const glm::mat4& wa, const Field& b, const glm::mat4& wb, float lobe, float fullValue,
                  const std::string& what) {
  const std::vector<Object> objects = {{&a, wa, 0.0f}, {&b, wb, 0.0f}};
  const OcclusionShares shares = sharedOcclusion(objects, 0);
  const std::vector<glm::vec4>& s = shares.scale;
  ASSERT_EQ(s.size(), sampleCount(a.settings));
  ASSERT_EQ(shares.onObjects.size(), sampleCount(a.settings));
  int full = 0, partial = 0, none = 0, nearer = 0, farther = 0, insideB = 0;
  for (std::size_t r = 0; r < s.size(); ++r) {
    const glm::vec3 p(wa * glm::vec4(a.radius * samplePosition(a.settings, r), 1.0f));
    const glm::vec3 qb = glm::vec3(glm::inverse(wb) * glm::vec4(p, 1.0f)) / b.radius;
    float w = 0.0f;
    for (float x : lookup(b.settings, qb).weight) w += x;
    const float want = 1.0f - 0.5f * w * (2.0f * 1.5f + lobe) / (2.0f * kU);
    EXPECT_NEAR(s[r].x, want, 2e-5f) << what << " " << r;
    EXPECT_EQ(s[r].x, s[r].y);
    EXPECT_EQ(s[r].x, s[r].z);
    const glm::vec3 oa(wa * glm::vec4(a.centre, 1.0f)), ob(wb * glm::vec4(b.centre, 1.0f));
    const float letThrough = std::max(0.0f, 1.0f - w * (2.0f * 1.5f + lobe) / (2.0f * kU));
    const bool bNearer = glm::length(p - ob) < glm::length(p - oa), outsideB = glm::length(p - ob) >= b.radius;
    if (bNearer) {  // off the objects: Algorithm 1 at p, B counted wherever it is the nearer
      EXPECT_NEAR(s[r].w, letThrough, 4e-5f) << what << " " << r;
    } else {
      EXPECT_EQ(s[r].w, 1.0f) << what << " " << r;
    }
    if (bNearer && outsideB) {  // on an object: B left out inside its bounding sphere
      EXPECT_NEAR(shares.onObjects[r], letThrough, 4e-5f) << what << " " << r;
      nearer += w > 0.0f;
    } else {
      EXPECT_EQ(shares.onObjects[r], 1.0f) << what << " " << r;
      farther += w > 0.0f && !bNearer;
      insideB += w > 0.0f && bNearer;
    }
    if (w > 1.0f - 1e-6f) {
      ++full;
      EXPECT_NEAR(s[r].x, fullValue, 2e-5f) << what << " " << r;
    } else if (w > 0.0f) {
      ++partial;
    } else {
      ++none;
    }
  }
  EXPECT_GT(full, 0) << what;
  EXPECT_GT(partial, 0) << what;
  EXPECT_GT(none, 0) << what;
  EXPECT_GT(nearer, 0) << what;   // samples in B's field nearer B: A's light there partly hidden
  EXPECT_GT(farther, 0) << what;  // and nearer A: its light whole
  EXPECT_GT(insideB, 0) << what;  // and inside B's sphere, where the two factors differ
}

// B 1 m (2 η) from A along x, turned about x by 0, 90 and 180 degrees: its z lobe lands on world z, −y and
// −z, so with A's lobe on z the l = 1 part of ∫(1 − V_A)(1 − V_B) is +0.8·0.6, 0 and −0.8·0.6; with A's lobe
// on y (coefficient 1) and B turned 90 degrees, −0.8·0.6 (+0.48 if the rotation went the wrong way). Where
// B's field holds p fully (W = 1) s = 1 − ½(2·1.5 + lobe)/(2√(4π)) = 0.75458 / 0.78843 / 0.82228.
// Both turned: A 90 degrees about (1, 1, 0)/√2 (its y lobe to world (½, ½, √½)), B 90 degrees about
// (0, 1, 1)/√2 (its z lobe to (√½, ½, ½)): lobe = 0.48·(¼ + √½) = +0.45941, s = 0.75603; each wrong
// order of the frame change (R_B R_Aᵀ, R_Bᵀ R_A, R_A R_Bᵀ for R_Aᵀ R_B) gives a negative lobe (−0.070,
// −0.410, −0.219), s ≥ 0.7934.
TEST(RtfOverlap, SharedPartIsHalfTheSphericalProductOverWhatAHides) {
  const Field az = handField(2.0f, 0.8f), ay = handField(2.0f, 0.8f, 1), b = handField(1.5f, 0.6f);
  const glm::vec3 x(1.0f, 0.0f, 0.0f), xy = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)), yz = glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f));
  const struct {
    const Field* a;
    float degreesA;
    glm::vec3 axisA;
    float degreesB;
    glm::vec3 axisB;
    float lobe, full;
  } cases[] = {{&az, 0.0f, x, 0.0f, x, 0.48f, 0.75458f},
               {&az, 0.0f, x, 90.0f, x, 0.0f, 0.78843f},
               {&az, 0.0f, x, 180.0f, x, -0.48f, 0.82228f},
               {&ay, 0.0f, x, 90.0f, x, -0.48f, 0.82228f},
               {&ay, 90.0f, xy, 90.0f, yz, 0.45941f, 0.75603f}};
  for (const auto& c : cases) {
    const glm::mat4 wa = glm::rotate(glm::mat4(1.0f), glm::radians(c.degreesA), c.axisA);
    const glm::mat4 wb = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f)), glm::radians(c.degreesB), c.axisB);
    expectShared(*c.a, wa, b, wb, c.lobe, c.full, std::to_string(c.degreesA) + " " + std::to_string(c.degreesB));
  }
}

// A mirror among the two: B's local → A's local directions are M_A⁻¹M_B = s_A s_B R_Aᵀ R_B (gi::Placement),
// so B's (1 − V_B) must be turned by R_Aᵀ R_B and inverted ((−1)^l) exactly when one of the two is mirrored.
// Same A and B as above, B 1 m along x; X, Z flip world x, z (det −1; R = −X is 180 degrees about x, −Z 180 degrees about z).
//  - B = T·X, both lobes z: X keeps z, lobe +0.48, s = 0.75458 (the turn R alone sends z to −z: −0.48).
//  - A = Z, B = T, both lobes z: A's lobe on world −z, lobe −0.48, s = 0.82228 (without the inversion +0.48).
//  - A = Z, B = T·Z: both lobes on world −z, lobe +0.48 (inverting whenever either is mirrored gives −0.48).
//  - A's lobe y, B = T·rot(90°, x)·X, lobe z: z → z → −y, lobe −0.48 (without the inversion +0.48).
//  - both lobes on coefficient 9, y(3x² − y²) (l = 3, even in x), B = T·X: lobe +0.48 (R alone flips y: −0.48).
TEST(RtfOverlap, ExactlyOneMirroredInvertsTheOtherFieldsOcclusion) {
  const Field az = handField(2.0f, 0.8f), ay = handField(2.0f, 0.8f, 1), a9 = handField(2.0f, 0.8f, 9);
  const Field bz = handField(1.5f, 0.6f), b9 = handField(1.5f, 0.6f, 9);
  const glm::mat4 id(1.0f), t = glm::translate(id, glm::vec3(1.0f, 0.0f, 0.0f));
  const glm::mat4 flipX = glm::scale(id, glm::vec3(-1.0f, 1.0f, 1.0f)), flipZ = glm::scale(id, glm::vec3(1.0f, 1.0f, -1.0f));
  const glm::mat4 turnX = glm::rotate(id, glm::radians(90.0f), glm::vec3(1.0f, 0.0f, 0.0f));
  const struct {
    const Field *a, *b;
    glm::mat4 wa, wb;
    float lobe, full;
    bool mixed;
    const char* what;
  } cases[] = {{&az, &bz, id, t * flipX, 0.48f, 0.75458f, true, "B mirrored in x"},
               {&az, &bz, flipZ, t, -0.48f, 0.82228f, true, "A mirrored in z"},
               {&az, &bz, flipZ, t * flipZ, 0.48f, 0.75458f, false, "both mirrored in z"},
               {&ay, &bz, id, t * turnX * flipX, -0.48f, 0.82228f, true, "B mirrored in x and turned"},
               {&a9, &b9, id, t * flipX, 0.48f, 0.75458f, true, "B mirrored in x, l = 3 lobes"}};
  for (const auto& c : cases) {
    // The cases reach the branch they are about: one mirrored placement of the two, except the control.
    ASSERT_EQ(place(*c.a, c.wa).mirrored != place(*c.b, c.wb).mirrored, c.mixed) << c.what;
    expectShared(*c.a, c.wa, *c.b, c.wb, c.lobe, c.full, c.what);
  }
}

// Two nearer objects at the same place (B and its copy C, 1 m from A along x): where both are nearer to a
// sample than A and it lies outside their bounding spheres, A's light gets through each, w = (1 − x)² with x
// one object's share — Algorithm 1's visibilities multiply —, not 1 − 2x; the blocked term's s loses half of
// both shares, 1 − x. Where B's lookup holds p fully x = (2·1.5 + 0.48)/(2√(4π)) = 0.49084.
TEST(RtfOverlap, SeveralNearerObjectsMultiplyTheirShares) {
  const Field a = handField(2.0f, 0.8f), b = handField(1.5f, 0.6f);
  const glm::mat4 wb = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f));
  const std::vector<Object> objects = {{&a, glm::mat4(1.0f), 0.0f}, {&b, wb, 0.0f}, {&b, wb, 0.0f}};
  const OcclusionShares shares = sharedOcclusion(objects, 0);
  const std::vector<glm::vec4>& s = shares.scale;
  int both = 0;
  for (std::size_t r = 0; r < s.size(); ++r) {
    const glm::vec3 p(a.radius * samplePosition(a.settings, r));
    float w = 0.0f;
    for (float weight : lookup(b.settings, (p - glm::vec3(1.0f, 0.0f, 0.0f)) / b.radius).weight) w += weight;
    const float x = w * (2.0f * 1.5f + 0.48f) / (2.0f * kU);
    EXPECT_NEAR(s[r].x, 1.0f - x, 4e-5f) << r;
    const float toB = glm::length(p - glm::vec3(1.0f, 0.0f, 0.0f));
    if (toB < glm::length(p)) {
      EXPECT_NEAR(s[r].w, (1.0f - x) * (1.0f - x), 4e-5f) << r;
    } else {
      EXPECT_EQ(s[r].w, 1.0f) << r;
    }
    if (toB < glm::length(p) && toB >= b.radius) {
      EXPECT_NEAR(shares.onObjects[r], (1.0f - x) * (1.0f - x), 4e-5f) << r;
      both += w > 1.0f - 1e-6f;
    } else {
      EXPECT_EQ(shares.onObjects[r], 1.0f) << r;
    }
  }
  EXPECT_GT(both, 0);
}

// A hides nothing from a sample (1 − V_A = 0): nothing to share, s = 1 whatever B hides.
TEST(RtfOverlap, SampleThatAHidesNothingFromIsOne) {
  const Field a = handField(0.0f, 0.0f), b = handField(1.5f, 0.6f);
  const std::vector<Object> objects = {{&a, glm::mat4(1.0f), 0.0f}, {&b, glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0, 0)), 0.0f}};
  const OcclusionShares shares = sharedOcclusion(objects, 0);
  for (const glm::vec4& s : shares.scale) EXPECT_EQ(s, glm::vec4(1.0f));
  for (float w : shares.onObjects) EXPECT_EQ(w, 1.0f);
}

}  // namespace
}  // namespace bounce::gi::rtf
