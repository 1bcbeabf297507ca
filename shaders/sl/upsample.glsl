// SL pass 2's edge-aware upsample (README "SL cost", "SL at quarter resolution, session 10"), shared by
// shaders/sl/upsample.frag and its self-test (upsample_selftest.comp); C++ reference
// engine/gi/sl/upsample.hpp (sl::upsampleTaps, sl::upsampleBlend), the same operations in the same order.
// A joint bilateral upsample: the reduced target ("sl.half" / "sl.quarter") holds E at G-buffer pixel
// step·j (engine/gi/sl/resolution.hpp); a full-resolution pixel blends its up to 4 nearest samples with
// bilinear weights times how well each sample's receiver matches its own — the distance of the sample's
// point from this pixel's tangent plane relative to the distance from the eye (Gaussian, e^-1 at
// kSlUpPlaneScale) and the normals' agreement (max(0, n·n_j)^kSlUpNormalPower) — so light does not
// bleed across depth or crease edges. When every sample is rejected with its bilinear weight (a thin
// feature between samples) the best-matching sample alone is used. One code path for step 2 and 4.
#ifndef BOUNCE_SL_UPSAMPLE_GLSL
#define BOUNCE_SL_UPSAMPLE_GLSL

const float kSlUpPlaneScale = 0.01;  // plane distance / eye distance at which the weight is e^-1
const float kSlUpNormalPower = 8.0;  // written out as three squarings in slUpsampleMatch
const float kSlUpMinWeight = 1e-4;   // below: the best-matching sample alone

// The 4 taps of full-resolution pixel `pixel` (≥ 0): reduced samples j = j0 + (k & 1, k >> 1), j0 =
// pixel / step (integer), clamped to the reduced size; the G-buffer pixel q = min(step·j, full − 1)
// each holds; f = (pixel − step·j0) / step, the bilinear fractions — exact: step is a power of two
// and the division an ldexp (a float division may round on llvmpipe, which multiplies by a reciprocal).
// Only right for powers of two: the C++ side admits steps 1, 2 and 4 alone (sl::checkedStep,
// engine/gi/sl/resolution.hpp, where every step enters: the level, `bounce bench`, the passes).
void slUpsampleTaps(ivec2 pixel, int step, ivec2 reducedSize, ivec2 full, out ivec2 j[4], out ivec2 q[4], out vec2 f) {
  ivec2 j0 = pixel / step;
  f = ldexp(vec2(pixel - step * j0), ivec2(-findLSB(step)));
  for (int k = 0; k < 4; ++k) {
    j[k] = min(j0 + ivec2(k & 1, k >> 1), reducedSize - 1);
    q[k] = min(step * j[k], full - 1);
  }
}

// How well tap k's receiver (point pq, normal nq; valid: not background) matches this pixel's (p, n,
// eye = |p − eye position|): exp(−(|n·(pq − p)| / (eye·kSlUpPlaneScale))²) · max(0, n·nq)^8 — the
// 8th power (kSlUpNormalPower) as three squarings, not pow(): llvmpipe's pow is a log2 and an exp2
// polynomial each (session 10, for the upsample's cost; the same value to rounding).
float slUpsampleMatch(vec3 p, vec3 n, float eye, vec3 pq, vec3 nq, bool valid) {
  float plane = abs(dot(n, pq - p)) / (eye * kSlUpPlaneScale);
  float c = max(dot(n, nq), 0.0);
  float c2 = c * c, c4 = c2 * c2;
  return valid ? exp(-plane * plane) * (c4 * c4) : 0.0;
}

// The blend of the 4 taps' E (W/m²) for one pixel: Σ b_k m_k E_k / Σ b_k m_k, or the best match's E.
vec3 slUpsampleBlend(vec3 p, vec3 n, float eye, vec2 f, vec3 pq[4], vec3 nq[4], bool valid[4], vec3 e[4]) {
  vec3 sum = vec3(0.0), best = vec3(0.0);
  float weight = 0.0, bestMatch = 0.0;
  for (int k = 0; k < 4; ++k) {
    float match = slUpsampleMatch(p, n, eye, pq[k], nq[k], valid[k]);
    float bilinear = ((k & 1) != 0 ? f.x : 1.0 - f.x) * ((k >> 1) != 0 ? f.y : 1.0 - f.y);
    sum += bilinear * match * e[k];
    weight += bilinear * match;
    if (match > bestMatch) {
      bestMatch = match;
      best = e[k];
    }
  }
  return weight > kSlUpMinWeight ? sum / weight : best;
}

#endif
