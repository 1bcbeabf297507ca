// The edge-aware upsample of a reduced-resolution irradiance target (README "SL cost", "SL at quarter
// resolution, session 10", "DNRT at half resolution, session 15"), one copy for SL pass 2
// (shaders/sl/upsample.frag, self-test sl/upsample_selftest.comp) and DNRT and RTF at reduced
// resolution (shaders/passes/reduced_upsample.frag); C++ reference engine/gi/upsample.hpp
// (gi::upsampleTaps, gi::upsampleBlend), the same operations in the same order.
// A joint bilateral upsample: the reduced target ("sl.half" / "sl.quarter", "dnrt.half" / "dnrt.quarter",
// "rtf.half" / "rtf.quarter") holds E at G-buffer pixel step·j (engine/gi/resolution.hpp); a
// full-resolution pixel blends its up to 4 nearest samples with bilinear weights times how well each
// sample's receiver matches its own — the distance of the sample's point from this pixel's tangent
// plane relative to the distance from the eye (Gaussian, e^-1 at kUpPlaneScale) and the normals'
// agreement (max(0, n·n_j)^kUpNormalPower) — so light does not bleed across depth or crease edges.
// When every sample is rejected with its bilinear weight (a thin feature between samples) the
// best-matching sample alone is used. One code path for step 2 and 4.
#ifndef BOUNCE_UPSAMPLE_GLSL
#define BOUNCE_UPSAMPLE_GLSL
#include "frame.glsl"  // worldFromDepth, for upsampleReceivers

const float kUpPlaneScale = 0.01;  // plane distance / eye distance at which the weight is e^-1
const float kUpNormalPower = 8.0;  // written out as three squarings in upsampleMatch
const float kUpMinWeight = 1e-4;   // below: the best-matching sample alone

// The 4 taps of full-resolution pixel `pixel` (≥ 0): reduced samples j = j0 + (k & 1, k >> 1), j0 =
// pixel / step (integer), clamped to the reduced size; the G-buffer pixel q = min(step·j, full − 1)
// each holds; f = (pixel − step·j0) / step, the bilinear fractions — exact: step is a power of two
// and the division an ldexp (a float division may round on llvmpipe, which multiplies by a reciprocal).
// Only right for powers of two: the C++ side admits steps 1, 2 and 4 alone (gi::checkedStep,
// engine/gi/resolution.hpp, where every step enters: the level, `bounce bench`, the passes).
// The G-buffer pixel that reduced sample j stands for: step·j, clamped to the image (the reduced size
// is ⌈full/step⌉, engine/gi/resolution.hpp reducedSize). The passes that shade a reduced target
// (DNRT's dnrt.frag / clustered.frag and RTF's rtf.frag with kStep) and upsampleTaps share this one
// mapping.
ivec2 reducedSamplePixel(ivec2 j, int step, ivec2 full) { return min(step * j, full - 1); }

void upsampleTaps(ivec2 pixel, int step, ivec2 reducedSize, ivec2 full, out ivec2 j[4], out ivec2 q[4], out vec2 f) {
  ivec2 j0 = pixel / step;
  f = ldexp(vec2(pixel - step * j0), ivec2(-findLSB(step)));
  for (int k = 0; k < 4; ++k) {
    j[k] = min(j0 + ivec2(k & 1, k >> 1), reducedSize - 1);
    q[k] = reducedSamplePixel(j[k], step, full);
  }
}

// The 4 taps' receivers, as the upsample's fragment shaders read them from the G-buffer (one copy for
// SL's, DNRT's and RTF's): tap k's world point pq (m) from the depth at G-buffer pixel q[k]
// (worldFromDepth, frame.glsl, at the pixel's centre; invResolution = 1 / full size), its normal nq,
// and valid = not background (depth < 1, the cleared far plane).
void upsampleReceivers(sampler2D depthTex, sampler2D normalTex, mat4 invViewProj, vec2 invResolution, ivec2 q[4],
                       out vec3 pq[4], out vec3 nq[4], out bool valid[4]) {
  for (int k = 0; k < 4; ++k) {
    float dq = texelFetch(depthTex, q[k], 0).r;
    nq[k] = texelFetch(normalTex, q[k], 0).xyz;
    pq[k] = worldFromDepth(invViewProj, (vec2(q[k]) + 0.5) * invResolution, dq);
    valid[k] = dq < 1.0;
  }
}

// How well tap k's receiver (point pq, normal nq; valid: not background) matches this pixel's (p, n,
// eye = |p − eye position|): exp(−(|n·(pq − p)| / (eye·kUpPlaneScale))²) · max(0, n·nq)^8 — the
// 8th power (kUpNormalPower) as three squarings, not pow(): llvmpipe's pow is a log2 and an exp2
// polynomial each (session 10, for the upsample's cost; the same value to rounding).
float upsampleMatch(vec3 p, vec3 n, float eye, vec3 pq, vec3 nq, bool valid) {
  float plane = abs(dot(n, pq - p)) / (eye * kUpPlaneScale);
  float c = max(dot(n, nq), 0.0);
  float c2 = c * c, c4 = c2 * c2;
  return valid ? exp(-plane * plane) * (c4 * c4) : 0.0;
}

// The blend of the 4 taps' E (W/m²) for one pixel: Σ b_k m_k E_k / Σ b_k m_k, or the best match's E.
vec3 upsampleBlend(vec3 p, vec3 n, float eye, vec2 f, vec3 pq[4], vec3 nq[4], bool valid[4], vec3 e[4]) {
  vec3 sum = vec3(0.0), best = vec3(0.0);
  float weight = 0.0, bestMatch = 0.0;
  for (int k = 0; k < 4; ++k) {
    float match = upsampleMatch(p, n, eye, pq[k], nq[k], valid[k]);
    float bilinear = ((k & 1) != 0 ? f.x : 1.0 - f.x) * ((k >> 1) != 0 ? f.y : 1.0 - f.y);
    sum += bilinear * match * e[k];
    weight += bilinear * match;
    if (match > bestMatch) {
      bestMatch = match;
      best = e[k];
    }
  }
  return weight > kUpMinWeight ? sum / weight : best;
}

#endif
