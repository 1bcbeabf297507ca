// The baked volume's radiance SH at a receiver, read as the probes pass reads it (texelFetch from
// the probe images, DESIGN.md: no SSBOs); shared by probes/probes.frag and the SL shadow on the
// probes' light (sl/probe_shadow.frag), so both see the same L at a pixel.
//
// The includer declares, before including this file:
//   const int kCoeffs (order²: 4 or 9, a specialization constant);
//   sampler2D probeSh (RGBA32F) and probeMoments (RG32F), laid out by engine/gi/probes/node.cpp:
//     probe p = x + count.x·row sits in texel row `row`, its data in `slots` texels from slots·x on:
//     SH, kTexels texels packing L_0.rgb, L_1.rgb, … then the valid flag, 4 floats a texel (order 3:
//     7 texels, not 9: the gathers are most of the pass); moments, texel (bin + PROBE_VIS_BINS·x, row)
//     = (mean, mean square) (m, m²);
//   a push-constant block `pc` with probes::ProbePush's layout (engine/gi/probes/node.hpp):
//     vec4 originSpacing (xyz: probe (0,0,0) position, w: spacing, m), ivec4 countOrder (xyz: probes
//     per axis, w: SH order), vec4 bias (x: normal bias (m), y: view bias (m), z: Chebyshev variance
//     floor (m²), w: includer's flag).
#ifndef BOUNCE_PROBE_SH_GLSL
#define BOUNCE_PROBE_SH_GLSL

const int kTexels = (3 * kCoeffs + 4) / 4;  // SH texels per probe: 3 floats a coefficient + valid

ivec2 probeTexel(int probe, int slot, int slotsPerProbe) {
  return ivec2(slot + slotsPerProbe * (probe % pc.countOrder.x), probe / pc.countOrder.x);
}

// Probe p's SH texel t. An includer that defines PROBE_SH_UBO also declares `const bool kShInUbo`
// and `uniform ProbeShBlock { vec4 probeShUbo[]; }` (texel t of p at [kTexels·p + t], the image's
// floats, engine/gi/probes/node.cpp): a uniform block is cheaper on llvmpipe when the volume fits.
vec4 probeShTexel(int probe, int t) {
#ifdef PROBE_SH_UBO
  if (kShInUbo) return probeShUbo[kTexels * probe + t];
#endif
  return texelFetch(probeSh, probeTexel(probe, t, kTexels), 0);
}

#define PROBE_DATA_PARAM
#define PROBE_VALID(i) (probeShTexel(i, kTexels - 1)[(3 * kCoeffs) % 4] != 0.0)
#define PROBE_MOMENTS(i, b) texelFetch(probeMoments, probeTexel(i, b, PROBE_VIS_BINS), 0).rg
#include "probes/probe_weights.glsl"

// L = Σ_k w_k L^k at surface point x with unit normal n, v the unit vector to the eye (the lookup
// point is biased along both, probe_weights.glsl); coefficients ≥ kCoeffs are 0.
void probeRadianceSh(vec3 x, vec3 n, vec3 v, out vec3 L[9]) {
  vec3 q = x + pc.bias.x * n + pc.bias.y * v;
  int probe[8];
  float weight[8];
  probeWeights(pc.countOrder.xyz, pc.originSpacing.xyz, pc.originSpacing.w, pc.bias.z, q, n, probe, weight);
  for (int i = 0; i < 9; ++i) L[i] = vec3(0.0);
  // No test of weight[k] == 0: a branch is not skipped on llvmpipe, and 0·L adds nothing.
  for (int k = 0; k < 8; ++k) {
    float f[28];  // kTexels · 4 ≤ 28
    for (int t = 0; t < kTexels; ++t) {
      vec4 v = probeShTexel(probe[k], t);
      f[4 * t] = v.x, f[4 * t + 1] = v.y, f[4 * t + 2] = v.z, f[4 * t + 3] = v.w;
    }
    for (int i = 0; i < kCoeffs; ++i) L[i] += weight[k] * vec3(f[3 * i], f[3 * i + 1], f[3 * i + 2]);
  }
}

#endif  // BOUNCE_PROBE_SH_GLSL
