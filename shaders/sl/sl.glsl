// SL pass 2 per receiver (Guerrero, Jeschke, Wimmer 2008, §5.2 and §6–7): the irradiance a receiver
// point p with unit normal n gets from every SL, E(p) = Σ_i L̃_i Ṽ_i (Eq. 14), with L̃_i the average
// radiance (Eq. 16–18, the weight ZH rotated into the SL's local frame, §7.1) and Ṽ_i the
// cosine-weighted SH-exponentiated visibility (Eq. 23–24) in the Ratio form, after the receiver rules.
// The GLSL port of engine/gi/sl/evaluate.cpp (the double-precision reference, whose header derives
// every rule): same steps in the same order, float instead of double. tests/unit/sl compares the two
// through shaders/sl/evaluate_selftest.comp; shaders/sl/sl.frag runs it per pixel.
//
// The includer defines before including this file:
//   const uint kOrder (3 or 4), const bool kPerObject (§7.2 per-object blocking, else per-sphere),
//   const uint kSpheres (≥ the SL count: sizes the per-receiver arrays), const float kInfluence
//   (evaluate.hpp rule 0's F; 0: off) — specialization constants;
//   sampler2D slTables: rgba32f, 256×3, read with texelFetch — row 0 texel i: the blocker log ZH
//     (sh_exp.hpp ExpTables::logTable) at θ_i = i/255 · π/2, row 1: Eq. 16's weight ZH
//     (evaluate.hpp averageRadianceTable) at θ_i, row 2 texel i < 128: the optimal-linear (a, b)
//     at ‖f̂‖ = i/127 · 4 (ExpTables::olTable);
//   uint slCount(); vec4 slSphere(uint i) (world centre, radius, metres); mat3 slRotation(uint i)
//     (SL local → world); uint slObject(uint i); vec3 slIntensity(uint i, uint k) (L^c_k, pass 1);
//     uint slObjectCount() (ids 0 … count − 1); vec4 slObjectCentre(uint o) (mean sphere centre, count);
// Includes sh.glsl and sl/gaunt.glsl (the SH square, generated from sh_product.hpp's tensor).
#ifndef BOUNCE_SL_GLSL
#define BOUNCE_SL_GLSL

#include "sh.glsl"

const uint kSlCoeffs = kOrder * kOrder;
const float kSlPi = 3.14159265358979324;
const float kSlSqrt4Pi = 3.54490770181103205;
const float kSlCullFraction = 0.5;  // evaluate.hpp kCullFraction
const float kSlMinOpen = 1e-9;      // evaluate.cpp kMinOpen
const int kSlThetaEntries = 256;
const int kSlMagEntries = 128;
const float kSlMaxMagnitude = 4.0;
const float kSlBlendStart = 3.0;    // sh_exp.hpp ExpTables::kHybridBlendStart
const float kSlMaxExponent = 80.0;  // e^80 < FLT_MAX: the DC factor stays finite (C++: 700, double)

#include "sl/gaunt.glsl"

// Rules 0 (influence), 1 (containment) and 2 (tangent plane) of evaluate.hpp; false when culled.
bool slAdjust(inout vec3 c, inout float r, vec3 p, vec3 n) {
  float d = length(c - p);
  r = max(0.0, r);
  if (kInfluence > 0.0 && d > 0.5 * kInfluence * r) r *= clamp((kInfluence - d / r) / (0.5 * kInfluence), 0.0, 1.0);
  if (d < r) {
    float t = d / r;
    r = d * clamp((t - kSlCullFraction) / (1.0 - kSlCullFraction), 0.0, 1.0);
  }
  float h = dot(n, c - p);
  if (h < r) {
    float top = h + r;
    if (top <= 0.0) return false;
    float r2 = 0.5 * top;
    c += (r2 - h) * n;
    r = r2;
  }
  return r > 0.0;
}

// Linear interpolation in a 256-entry θ row of slTables (θ clamped to [0, π/2]).
vec4 slThetaRow(int row, float theta) {
  float x = clamp(theta, 0.0, 0.5 * kSlPi) / (0.5 * kSlPi) * float(kSlThetaEntries - 1);
  int i0 = min(int(x), kSlThetaEntries - 2);
  float w = x - float(i0);
  return (1.0 - w) * texelFetch(slTables, ivec2(i0, row), 0) + w * texelFetch(slTables, ivec2(i0 + 1, row), 0);
}

// f_lm = √(4π/(2l+1)) z_l Y_lm(d) (sh_rotate.hpp rotateZonal).
void slRotateZonal(vec4 z, vec3 d, out float f[16]) {
  float y[16];
  shEval16(d, y);
  const float s[4] = float[4](3.54490770181103205, 2.04665341589297697, 1.58533091904240551, 1.33984917138736218);
  for (uint i = 0u; i < 16u; ++i) {
    uint l = i < 1u ? 0u : (i < 4u ? 1u : (i < 9u ? 2u : 3u));
    f[i] = i < kSlCoeffs ? s[l] * z[l] * y[i] : 0.0;
  }
}

// E = Σ Â_l v_lm Y_lm(n) for a scalar SH vector (sh_convolve.hpp evalIrradiance, Â_3 = 0).
float slIrradiance(in float v[16], vec3 n) {
  float y[16];
  shEval16(n, y);
  float e = SH_A0 * v[0] * y[0];
  for (uint i = 1u; i < 4u; ++i) e += SH_A1 * v[i] * y[i];
  for (uint i = 4u; i < 9u; ++i) e += SH_A2 * v[i] * y[i];
  return e;
}

// The optimal-linear (a, b) at ‖f̂‖ = m (sh_exp.hpp ExpTables::olCoefficients; m clamped to [0, 4]).
vec2 slOl(float m) {
  float x = clamp(m, 0.0, kSlMaxMagnitude) / kSlMaxMagnitude * float(kSlMagEntries - 1);
  int i0 = min(int(x), kSlMagEntries - 2);
  float w = x - float(i0);
  return (1.0 - w) * texelFetch(slTables, ivec2(i0, 2), 0).xy + w * texelFetch(slTables, ivec2(i0 + 1, 2), 0).xy;
}

// The hybrid exp (sh_exp.hpp expHybrid): DC isolation, optimal-linear on f̂ halved k times until
// ‖f̂‖ ≤ 4, blended over ‖f̂‖/2^k in [3, 4] towards one more halving (continuity, sh_exp.hpp), then k
// squarings (slSquare: the Gaunt tensor, unrolled).
void slExp(in float f[16], out float g[16]) {
  float m2 = 0.0;
  for (uint i = 1u; i < kSlCoeffs; ++i) m2 += f[i] * f[i];
  float m = sqrt(m2);
  int k = 0;
  while (m > kSlMaxMagnitude && k < 30) {
    m *= 0.5;
    ++k;
  }
  vec2 ab = slOl(m);
  float scale = exp2(-float(k));
  g[0] = ab.x * kSlSqrt4Pi;
  for (uint i = 1u; i < 16u; ++i) g[i] = i < kSlCoeffs ? ab.y * (f[i] * scale) : 0.0;
  float x = clamp((m - kSlBlendStart) / (kSlMaxMagnitude - kSlBlendStart), 0.0, 1.0);
  float blend = x * x * (3.0 - 2.0 * x);
  if (blend > 0.0) {
    vec2 abHalf = slOl(0.5 * m);
    float q[16], q2[16];
    q[0] = abHalf.x * kSlSqrt4Pi;
    for (uint i = 1u; i < 16u; ++i) q[i] = i < kSlCoeffs ? abHalf.y * (f[i] * (0.5 * scale)) : 0.0;
    slSquare(q, q2);
    for (uint i = 0u; i < 16u; ++i) g[i] = (1.0 - blend) * g[i] + blend * q2[i];
  }
  for (int s = 0; s < k; ++s) {
    float h[16];
    slSquare(g, h);
    g = h;
  }
  float dc = exp(min(f[0] / kSlSqrt4Pi, kSlMaxExponent));
  for (uint i = 0u; i < 16u; ++i) g[i] *= dc;
}

// Eq. 23–24: Ṽ = ρ_n · [exp(B) − exp(B + G_i)] for blocker sum B and the light's own log G.
float slEq23(in float blockers[16], in float own[16], vec3 n) {
  float with[16];
  for (uint i = 0u; i < 16u; ++i) with[i] = blockers[i] + own[i];
  float a[16], b[16];
  slExp(blockers, a);
  slExp(with, b);
  for (uint i = 0u; i < 16u; ++i) a[i] -= b[i];
  return slIrradiance(a, n);
}

// Lights i and j of one object whose spheres overlap ignore each other (baked occlusion, §6.2).
bool slIntersects(uint i, uint j) {
  vec4 a = slSphere(i), b = slSphere(j);
  return slObject(i) == slObject(j) && length(a.xyz - b.xyz) < a.w + b.w;
}

// Per-light state at this receiver (evaluate.cpp's Prepared).
bool slCulled[kSpheres];
float slDist[kSpheres];
float slLogs[kSpheres * 16u];
float slRatio[kSpheres];       // exact Ṽ / Eq. 23 Ṽ of the unoccluded cap, when formed
float slExactOpen[kSpheres];   // the exact Ṽ, used alone when the ratio is not formed
bool slRatioFormed[kSpheres];
vec3 slAverage[kSpheres];
uint slOrder[kSpheres];

// Ṽ_i from the blockers' summed log, with the Ratio form; adds L̃ Ṽ to e.
void slFinish(uint i, in float blockers[16], vec3 n, inout vec3 e) {
  float own[16];
  for (uint k = 0u; k < 16u; ++k) own[k] = slLogs[i * 16u + k];
  float vis = slEq23(blockers, own, n);
  vis = slRatioFormed[i] ? vis * slRatio[i] : slExactOpen[i];
  e += slAverage[i] * vis;
}

// E(p) (Eq. 14), W/m² per channel for L^c in W/(m²·sr).
vec3 slIrradianceAt(vec3 p, vec3 n) {
  uint count = min(slCount(), kSpheres);
  float zero[16];
  for (uint k = 0u; k < 16u; ++k) zero[k] = 0.0;
  for (uint i = 0u; i < count; ++i) {
    vec4 sp = slSphere(i);
    vec3 c = sp.xyz;
    float r = sp.w;
    bool kept = slAdjust(c, r, p, n);
    float d = length(c - p);
    slDist[i] = d;
    slCulled[i] = !kept || !(d > 0.0);
    slOrder[i] = i;
    if (slCulled[i]) continue;
    vec3 dir = (c - p) / d;
    float theta = asin(min(1.0, r / d));
    float lg[16];
    slRotateZonal(slThetaRow(0, theta), dir, lg);
    for (uint k = 0u; k < 16u; ++k) slLogs[i * 16u + k] = lg[k];
    // The unoccluded cap's Ṽ: exact (1 − cap's closed-form ZH, sh_exp.hpp capVisibilityZonal) and
    // as Eq. 23 sees it (exp(0) − exp(G_i)).
    float t = cos(theta);
    float p2 = 0.5 * (3.0 * t * t - 1.0), p3 = 0.5 * t * (5.0 * t * t - 3.0), p4 = (35.0 * t * t * t * t - 30.0 * t * t + 3.0) / 8.0;
    vec4 z = vec4(kSlSqrt4Pi - sqrt(kSlPi) * (1.0 + t), -sqrt(3.0 * kSlPi) * (p2 - 1.0) / 3.0,
                  -sqrt(5.0 * kSlPi) * (p3 - t) / 5.0, -sqrt(7.0 * kSlPi) * (p4 - p2) / 7.0);
    float cap[16];
    slRotateZonal(z, dir, cap);
    float exactOpen = slIrradiance(cap, n);
    float eq23Open = slEq23(zero, lg, n);
    slRatioFormed[i] = eq23Open > kSlMinOpen;
    slRatio[i] = slRatioFormed[i] ? exactOpen / eq23Open : 0.0;
    slExactOpen[i] = exactOpen;
    // Eq. 18: the weight rotated to the SL-local direction from its centre to p (§7.1).
    float wz[16];
    slRotateZonal(slThetaRow(1, theta), transpose(slRotation(i)) * (-dir), wz);
    vec3 avg = vec3(0.0);
    for (uint k = 0u; k < kSlCoeffs; ++k) avg += wz[k] * slIntensity(i, k);
    slAverage[i] = avg;
  }
  // Closest first; insertion sort is stable, as evaluate.cpp's stable_sort.
  for (uint a = 1u; a < count; ++a) {
    uint v = slOrder[a];
    uint b = a;
    while (b > 0u && slDist[slOrder[b - 1u]] > slDist[v]) {
      slOrder[b] = slOrder[b - 1u];
      --b;
    }
    slOrder[b] = v;
  }
  vec3 e = vec3(0.0);
  if (!kPerObject) {
    for (uint a = 0u; a < count; ++a) {
      uint i = slOrder[a];
      if (slCulled[i]) continue;
      float blockers[16] = zero;
      for (uint b = 0u; b < a; ++b) {
        uint j = slOrder[b];
        if (slCulled[j] || slIntersects(i, j)) continue;
        for (uint k = 0u; k < kSlCoeffs; ++k) blockers[k] += slLogs[j * 16u + k];
      }
      slFinish(i, blockers, n, e);
    }
  } else {
    // §7.2: objects by the distance from p to the mean of their (unadjusted) sphere centres; each
    // object's spheres see the closer objects' summed logs plus their own closer spheres.
    float closer[16] = zero;
    uint done = 0u;  // objects handled: ids are small (0..count), visited nearest first
    float last = -1.0;
    uint lastId = 0xffffffffu;
    for (;;) {
      // The next object: least (distance, id) above (last, lastId) — evaluate.cpp sorts (dist, id).
      float best = 3.4e38;
      uint bestId = 0xffffffffu;
      for (uint id = 0u; id < slObjectCount(); ++id) {
        vec4 oc = slObjectCentre(id);
        if (oc.w < 0.5) continue;  // no sphere has this id
        float d = length(oc.xyz - p);
        bool after = d > last || (d == last && id > lastId);
        if (after && (d < best || (d == best && id < bestId))) {
          best = d;
          bestId = id;
        }
      }
      if (bestId == 0xffffffffu) break;
      float objectSum[16] = zero;
      for (uint a = 0u; a < count; ++a) {
        uint i = slOrder[a];
        if (slObject(i) != bestId || slCulled[i]) continue;
        float blockers[16] = closer;
        for (uint b = 0u; b < a; ++b) {
          uint j = slOrder[b];
          if (slObject(j) != bestId || slCulled[j] || slIntersects(i, j)) continue;
          for (uint k = 0u; k < kSlCoeffs; ++k) blockers[k] += slLogs[j * 16u + k];
        }
        slFinish(i, blockers, n, e);
        for (uint k = 0u; k < kSlCoeffs; ++k) objectSum[k] += slLogs[i * 16u + k];
      }
      for (uint k = 0u; k < 16u; ++k) closer[k] += objectSum[k];
      last = best;
      lastId = bestId;
      ++done;
      if (done > count) break;
    }
  }
  return e;
}

#endif  // BOUNCE_SL_GLSL
