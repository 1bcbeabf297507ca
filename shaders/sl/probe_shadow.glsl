// The SLs' soft shadow on the probes' indirect light at one receiver (issue 13 pass 2, the SL paper
// §5.1 Eq. 3 and 6): the GLSL port of engine/gi/sl/probe_shadow.cpp (whose header derives it), float
// instead of double. Every SL blocks: after the receiver rules (sl.glsl slAdjust) the rotated log ZH
// are summed, exponentiated once (slExp: Eq. 6), multiplied with the clamped cosine about n
// (slProduct9, gaunt.glsl: P = V ∗ ĉ_n) and dotted with the probes' radiance SH L: E_s = Σ_j L_j P_j.
// Returns ΔE = clamp(−k (E_u − E_s), −max(E_u, 0), 0) per channel (W/m², ≤ 0), with k the Ratio
// form's (σ Σ u_o X_j + (1 − σ) Σ X_j) / Σ A_j (exact caps, weighted by their object's union share
// as far as exp acts additively here, over single-blocker exps) clamped to [1/4, 4].
// With `atSphere` ("blocked_light": "sphere", probe_shadow.hpp BlockedLight::Sphere; needs
// SL_INDIRECT_BINDING, sl_data.glsl) E_u − E_s is replaced by the blocked light read at the SLs:
// (π − ρ_n·V) Σ_j w_j max(0, L_j(d_j)) / Σ_j w_j, w_j = (σ u_o + 1 − σ) X_j, L_j the probes' radiance
// SH at SL j's posed centre evaluated in the receiver → SL direction d_j (no V ∗ ĉ_n product then);
// with `mapRead` too ("blocked_read": "map") L_j(d_j) is the texel of SL j's blended direction map
// that holds d_j (sl_data.glsl slIndirectMap; common/oct_map.glsl), not the SH.
// Needs sl.glsl (and what it needs) included first.
#ifndef BOUNCE_SL_PROBE_SHADOW_GLSL
#define BOUNCE_SL_PROBE_SHADOW_GLSL
#include "mask.glsl"

const float kSlShadowEpsilon = 1e-9;  // probe_shadow.hpp kShadowEpsilon (sr)
const float kSlShadowMaxRatio = 4.0;  // probe_shadow.hpp kShadowMaxRatio

// ΔE from the `alive` live SLs that sl.glsl's slWalk left in slLive / slDist / slAdjusted (the
// second loop: the rotation, the exp and the per-lane reads, run as often as the 8 pixels' longest
// live list, README "SL cost, session 8"). sl_shadow.frag calls it after slIrradianceLive on the
// same walk (one walk for both terms); slProbeShadow below walks first.
vec3 slProbeShadowLive(vec3 p, vec3 n, in vec3 L[9], uint alive, bool atSphere, bool mapRead) {
  float sum[16];
  vec3 readExact = vec3(0.0), readShared = vec3(0.0);  // Σ X_j L_j(d_j), Σ u_o X_j L_j(d_j) (atSphere)
  for (uint k = 0u; k < 16u; ++k) sum[k] = 0.0;
  float exact = kSlShadowEpsilon, sharedX = kSlShadowEpsilon, approx = kSlShadowEpsilon;
  // Â_l √((2l+1)/(4π)): ρ_n · (a ZH z rotated to d) = Σ_l Â_l √((2l+1)/(4π)) z_l P_l(n·d) (addition
  // theorem), so one blocker's A_j needs no 16-coefficient rotation.
  const vec4 lobeZonal = vec4(SH_A0 * 0.28209479177387814, SH_A1 * 0.48860251190291992, SH_A2 * 0.63078313050504001, 0.0);
  uint t = 0u;
  do {
    if (t < alive) {
      vec3 c = slAdjusted[t].xyz;
      float r = slAdjusted[t].w;
      float d = slDist[t];
      uint i = slLive[t];
      {
        vec3 dir = (c - p) / d;
        float s = min(1.0, r / d);
        vec4 z = slThetaRow(0, asin(s));
        float lg[16];
        slRotateZonal(z, dir, lg);
        for (uint k = 0u; k < kSlCoeffs; ++k) sum[k] += lg[k];
        // X_j: the cap's exact cosine-weighted solid angle; A_j: ρ_n · (1 − exp(G_j)) with the OL exp
        // (one blocker's ‖f̂‖ ≤ 1.9 < kHybridBlendStart for every θ of the table: no blend, no squarings;
        // SlProbeShadow.OneCapsLogIsBelowTheHybridsBlend checks it).
        float cd = dot(n, dir);
        float capX = slSilhouette(i) * kSlPi * s * s * max(0.0, cd);  // × the set's shadow scale (bounce_scale.hpp)
        exact += capX;
        sharedX += slShare(i) * capX;
#ifdef SL_INDIRECT_BINDING
        if (atSphere) {  // the light SL j blocks, read at its centre: L_j(d_j) ≥ 0 (a blocker adds none)
          vec3 read = vec3(0.0);
          if (mapRead) {
            read = slIndirectMap(i, dir);
          } else {
            float yd[9];
            shEval9(dir, yd);
            for (uint k = 0u; k < 9u; ++k) read += yd[k] * slIndirect(i, k);
          }
          read = max(read, vec3(0.0));
          readExact += capX * read;
          readShared += slShare(i) * capX * read;
        }
#endif
        float m = sqrt(z.y * z.y + z.z * z.z + (kOrder > 3u ? z.w * z.w : 0.0));
        vec2 ab = slOl(m);
        float p2 = 0.5 * (3.0 * cd * cd - 1.0);
        float dotted = ab.x * SH_A0 + ab.y * (lobeZonal.y * z.y * cd + lobeZonal.z * z.z * p2);
        approx += SH_A0 - exp(min(z.x / kSlSqrt4Pi, kSlMaxExponent)) * dotted;
      }
    }
    ++t;
  } while (t < alive);
  float v[16];
  slExp(sum, v);
  float y[9];
  shEval9(n, y);
  float lobe[9];
  lobe[0] = SH_A0 * y[0];
  for (int k = 1; k < 4; ++k) lobe[k] = SH_A1 * y[k];
  for (int k = 4; k < 9; ++k) lobe[k] = SH_A2 * y[k];
  vec3 unshadowed = vec3(0.0);
  for (int k = 0; k < 9; ++k) unshadowed += lobe[k] * L[k];
  vec3 shadowed = unshadowed;  // atSphere: E_u − E_s is set below
  if (!atSphere) {
    float transfer[9];
    slProduct9(v, lobe, transfer);
    shadowed = vec3(0.0);
    for (int k = 0; k < 9; ++k) shadowed += transfer[k] * L[k];
  }
  // σ: how additive exp is here (probe_shadow.hpp), from its blocked amount under uniform light.
  float vDotLobe = 0.0;
  for (int k = 0; k < 9; ++k) vDotLobe += v[k] * lobe[k];
  float additive = sqrt(clamp((SH_A0 - vDotLobe + kSlShadowEpsilon) / approx, 0.0, 1.0));
  float target = additive * sharedX + (1.0 - additive) * exact;
  float ratio = clamp(target / approx, 1.0 / kSlShadowMaxRatio, kSlShadowMaxRatio);
  vec3 blocked = unshadowed - shadowed;
  if (atSphere) blocked = (SH_A0 - vDotLobe) * (additive * readShared + (1.0 - additive) * readExact) / target;
  return clamp(-ratio * blocked, -max(unshadowed, vec3(0.0)), vec3(0.0));
}

vec3 slProbeShadowLive(vec3 p, vec3 n, in vec3 L[9], uint alive, bool atSphere) { return slProbeShadowLive(p, n, L, alive, atSphere, false); }

vec3 slProbeShadowLive(vec3 p, vec3 n, in vec3 L[9], uint alive) { return slProbeShadowLive(p, n, L, alive, false, false); }

// Over the SLs whose bit is set in `candidates` (sl.glsl slIrradianceAt's convention: those left out
// must be culled at p by the receiver rules, so they would add nothing).
// `count`: SLs at indices ≥ count are skipped (slCount(), or past it for the §7.3 parents,
// sl/hierarchy_shadow.glsl). Two loops, as sl.glsl's slIrradianceAt: the walk (slWalk) applies the
// receiver rules to every candidate and keeps those that reach p (llvmpipe runs an untaken branch in
// full, so work inside the walk is paid per candidate); slProbeShadowLive does the rest. The same
// terms in the same order.
vec3 slProbeShadow(vec3 p, vec3 n, in vec3 L[9], uvec4 candidates, uint count, bool atSphere, bool mapRead) {
  return slProbeShadowLive(p, n, L, slWalk(p, n, candidates, count), atSphere, mapRead);
}

vec3 slProbeShadow(vec3 p, vec3 n, in vec3 L[9], uvec4 candidates, uint count, bool atSphere) {
  return slProbeShadow(p, n, L, candidates, count, atSphere, false);
}

vec3 slProbeShadow(vec3 p, vec3 n, in vec3 L[9], uvec4 candidates, bool atSphere, bool mapRead) {
  return slProbeShadow(p, n, L, candidates, min(slCount(), kSpheres), atSphere, mapRead);
}

vec3 slProbeShadow(vec3 p, vec3 n, in vec3 L[9], uvec4 candidates, uint count) {
  return slProbeShadow(p, n, L, candidates, count, false);
}

vec3 slProbeShadow(vec3 p, vec3 n, in vec3 L[9], uvec4 candidates, bool atSphere) {
  return slProbeShadow(p, n, L, candidates, min(slCount(), kSpheres), atSphere);
}

vec3 slProbeShadow(vec3 p, vec3 n, in vec3 L[9], uvec4 candidates) {
  return slProbeShadow(p, n, L, candidates, min(slCount(), kSpheres), false);
}

// Over every SL (the self-test's receivers, which no tile list culls).
vec3 slProbeShadow(vec3 p, vec3 n, in vec3 L[9], bool atSphere, bool mapRead) {
  uvec4 all = uvec4(0u);
  uint count = min(slCount(), kSpheres);
  for (uint w = 0u; w < 4u; ++w) {
    uint bits = uint(clamp(int(count) - int(32u * w), 0, 32));
    all[w] = bits == 32u ? 0xffffffffu : (1u << bits) - 1u;
  }
  return slProbeShadow(p, n, L, all, atSphere, mapRead);
}

vec3 slProbeShadow(vec3 p, vec3 n, in vec3 L[9], bool atSphere) { return slProbeShadow(p, n, L, atSphere, false); }

vec3 slProbeShadow(vec3 p, vec3 n, in vec3 L[9]) { return slProbeShadow(p, n, L, false, false); }

#endif  // BOUNCE_SL_PROBE_SHADOW_GLSL
