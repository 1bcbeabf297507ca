#version 450
#extension GL_GOOGLE_include_directive : require
// Pass `probes.relight` (engine/gi/probes/relight_pass.hpp): the baked probes plus the change the
// dynamic objects make to them this frame, written in the probes pass's own uniform-block format.
// Three stages (push constant `stage`), each a dispatch, barriers between them:
//  0  one invocation per surfel: ΔE = Σ_l relightDirectLoss(V_now from the shadow atlas — it holds
//     the dynamic objects —, V_static baked) [+ E_SL, the SLs' bounce at the surfel] + the irradiance
//     of the previous iteration's ΔSH at the surfel (probe_weights.glsl, the volume's own weights and
//     visibility), ΔL = ρ/π ΔE;
//  1  one invocation per probe: ΔSH = 4π/R Σ_dirs Y(ω) ΔL(hit surfel) (relightGatherAdd);
//  2  one invocation per probe: baked + ΔSH packed as engine/gi/probes/node.cpp shPackedWords does
//     (L_0 halves, scale s rounded up to a half, L_i/(s·L_0) as snorm bytes), into the buffer the
//     probes pass binds as ProbeShBlock (outputs.x; the valid bits after the probes are not
//     touched), and as the probe image's floats (outputs.y: node.cpp shTexelFloats' layout,
//     probe-major, copied into the "probes.sh" image after the dispatch, relight_pass.cpp). The
//     image is what probes.frag reads when the volume does not fit the block (> 2016 probes) and
//     what the SL shadow on the probes' light reads always (probes/probe_sh.glsl), so both see the
//     relit light.
// The math is shaders/probes/relight.glsl (compiled as C++ too: engine/gi/probes/relight.cpp).
// SSBOs are fine here: a compute pass (DESIGN's machine facts keep them out of fragment shaders).
#include "lights.glsl"
#include "sh.glsl"

layout(local_size_x = 64) in;

#include "probes/surfel.glsl"

layout(std430, binding = 0) readonly buffer Surfels { Surfel surfels[]; };
layout(std430, binding = 1) readonly buffer Rays { vec4 rays[]; };           // probe·R + k: xyz dir, w surfel bits
layout(std430, binding = 2) readonly buffer StaticVis { float vStatic[]; };  // surfel·lightCount + l
layout(std140, binding = 3) uniform Lights { Light lights[kMaxLights]; };
layout(std140, binding = 4) uniform ShadowMatrices { mat4 shadowMatrices[kMaxShadowLayers]; };
layout(binding = 5) uniform sampler2DArrayShadow shadowAtlas;
#include "shadow.glsl"
layout(std430, binding = 6) buffer SurfelRadiance { vec4 surfelRadiance[]; };  // ΔL rgb
layout(std430, binding = 7) buffer Delta { vec4 delta[]; };                    // probe·9 + i: ΔSH rgb
layout(std430, binding = 8) readonly buffer Baked { vec4 baked[]; };          // probe·9 + i: baked SH rgb (0 past order²)
layout(std430, binding = 9) writeonly buffer Packed { uint packedWords[]; };  // the probes pass's ProbeShBlock
layout(std430, binding = 10) readonly buffer Valid { uint validFlags[]; };    // per probe, 0 or 1
layout(std430, binding = 11) readonly buffer Moments { vec2 momentsBuf[]; };  // probe·64 + bin (m, m²)
layout(std430, binding = 12) readonly buffer TestVis { float vTest[]; };      // surfel·lightCount + l (tests)
layout(std430, binding = 13) writeonly buffer Texels { vec4 texels[]; };      // probe·kTexels + t: the image's texels
layout(std430, binding = 14) readonly buffer SlBounce { vec4 slBounce[]; };   // surfel: E_SL rgb (sl.relight_bounce)

layout(push_constant) uniform Push {
  vec4 originSpacing;  // xyz: probe (0,0,0), w: spacing (m)
  ivec4 countOrder;    // xyz: probes per axis, w: SH order of the baked volume (2 or 3)
  vec4 params;         // x: normal bias (m), y: Chebyshev variance floor (m²), z: 4π/R
  uvec4 sizes;         // x: surfels, y: probes, z: R, w: lights
  uvec4 flags;         // x: stage, y: shadows on, z: V_now from vTest (tests), w: feedback on
  uvec4 outputs;       // stage 2 writes: x: the packed block, y: the image's texels; z: stage 0 adds E_SL
} pc;

#include "probes/relight.glsl"

#define PROBE_DATA_PARAM
#define PROBE_DATA_ARG
#define PROBE_VALID(i) (validFlags[i] != 0u)
#define PROBE_MOMENTS(i, b) momentsBuf[(i) * PROBE_VIS_BINS + (b)]
#include "probes/probe_weights.glsl"

const uint kMiss = 0xffffffffu;

void surfelStage(uint s) {
  Surfel sf = surfels[s];
  vec3 p = sf.position.xyz, n = sf.normal.xyz;
  vec3 e = vec3(0.0);
  for (uint l = 0u; l < pc.sizes.w; ++l) {
    vec3 toLight;
    float dist;
    incidentIrradiance(lights[l], p, toLight, dist);
    uint idx = s * pc.sizes.w + l;
    float vNow = pc.flags.z != 0u ? vTest[idx] : (pc.flags.y != 0u ? shadowVisibility(lights[l], p, n, dist) : 1.0);
    e += relightDirectLoss(lights[l], p, n, vNow, vStatic[idx]);
  }
  // Level "probes": {"sl_bounce": true}: the irradiance the posed SLs send the surfel (their first
  // bounce, Eq. 14, written by sl.relight_bounce from pass 1's intensities). The surfel re-emits it,
  // so the probes carry the SLs' 2nd+ bounces; pass 2 keeps the 1st at the receiver.
  if (pc.outputs.z != 0u) e += slBounce[s].rgb;
  if (pc.flags.w != 0u) {  // the room's bounce: the previous iteration's ΔSH at the surfel
    int probe[8];
    float weight[8];
    probeWeights(pc.countOrder.xyz, pc.originSpacing.xyz, pc.originSpacing.w, pc.params.y, p + pc.params.x * n, n,
                 probe, weight);
    vec3 L[9];
    for (int i = 0; i < 9; ++i) L[i] = vec3(0.0);
    for (int k = 0; k < 8; ++k)
      for (int i = 0; i < 9; ++i) L[i] += weight[k] * delta[9 * probe[k] + i].rgb;
    e += shIrradiance9(L, n);
  }
  surfelRadiance[s] = vec4(relightSurfelRadiance(sf.albedo.rgb, e), 0.0);
}

void gatherStage(uint probe) {
  vec3 sh[9];
  for (int i = 0; i < 9; ++i) sh[i] = vec3(0.0);
  if (validFlags[probe] != 0u) {
    uint R = pc.sizes.z;
    for (uint k = 0u; k < R; ++k) {
      vec4 r = rays[probe * R + k];
      uint s = floatBitsToUint(r.w);
      if (s != kMiss) relightGatherAdd(r.xyz, surfelRadiance[s].rgb, pc.params.z, sh);
    }
  }
  for (int i = 0; i < 9; ++i) delta[9 * probe + i] = vec4(sh[i], 0.0);
}

// The smallest half ≥ x (x ≥ 0), as node.cpp packedShScale rounds s.
float halfUp(float x) {
  uint h = packHalf2x16(vec2(x, 0.0)) & 0xffffu;
  if (unpackHalf2x16(h).x < x) h += 1u;
  return unpackHalf2x16(h).x;
}

void packStage(uint probe) {
  int coeffs = pc.countOrder.w * pc.countOrder.w;
  vec3 L[9];
  for (int i = 0; i < 9; ++i) L[i] = i < coeffs ? baked[9 * probe + i].rgb + delta[9 * probe + i].rgb : vec3(0.0);
  // L_0 is a mean radiance: a loss larger than the baked light (shadow-map noise) clamps at 0.
  L[0] = max(L[0], vec3(0.0));
  if (pc.outputs.y != 0u) {
    // The image's texels (node.cpp shTexelFloats): L_0.rgb, L_1.rgb, … then the valid flag, 4 floats
    // a texel, kTexels = (3·coeffs + 4)/4 texels a probe (probe_sh.glsl).
    float t[28];
    for (int i = 0; i < 28; ++i) t[i] = 0.0;
    for (int i = 0; i < coeffs; ++i)
      for (int c = 0; c < 3; ++c) t[3 * i + c] = L[i][c];
    t[3 * coeffs] = validFlags[probe] != 0u ? 1.0 : 0.0;
    uint texelsPerProbe = uint(3 * coeffs + 4) / 4u;
    for (uint k = 0u; k < texelsPerProbe; ++k)
      texels[texelsPerProbe * probe + k] = vec4(t[4 * k], t[4 * k + 1], t[4 * k + 2], t[4 * k + 3]);
  }
  if (pc.outputs.x == 0u) return;
  vec3 l0h = vec3(unpackHalf2x16(packHalf2x16(L[0].rg)), unpackHalf2x16(packHalf2x16(vec2(L[0].b, 0.0))).x);
  float s = 0.0;
  for (int i = 1; i < coeffs; ++i)
    for (int c = 0; c < 3; ++c)
      if (l0h[c] > 0.0) s = max(s, abs(L[i][c]) / l0h[c]);
  s = halfUp(s);
  uint base = 8u * probe;  // kPackedTexels (2) uvec4 a probe
  packedWords[base] = packHalf2x16(L[0].rg);
  packedWords[base + 1u] = packHalf2x16(vec2(L[0].b, s));
  float f[24];
  for (int i = 0; i < 24; ++i) f[i] = 0.0;
  for (int i = 1; i < coeffs; ++i)
    for (int c = 0; c < 3; ++c) {
      float d = s * l0h[c];
      f[3 * (i - 1) + c] = d != 0.0 ? L[i][c] / d : 0.0;  // an L_0.c of 0 carries no L_i.c (clamped above)
    }
  int words = (3 * (coeffs - 1) + 3) / 4;
  for (int w = 0; w < words; ++w) packedWords[base + 2u + uint(w)] = packSnorm4x8(vec4(f[4 * w], f[4 * w + 1], f[4 * w + 2], f[4 * w + 3]));
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (pc.flags.x == 0u) {
    if (i < pc.sizes.x) surfelStage(i);
  } else if (pc.flags.x == 1u) {
    if (i < pc.sizes.y) gatherStage(i);
  } else {
    if (i < pc.sizes.y) packStage(i);
  }
}
