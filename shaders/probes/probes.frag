#version 450
#extension GL_GOOGLE_include_directive : require
// Static indirect diffuse from the baked irradiance volume (effect `probes`), added to
// "lighting.hdr" with additive blending:
//   L_o += ρ(x)/π · E_ind(x, n),   E_ind = Σ_k w_k Σ_lm Â_l L^k_lm Y_lm(n)
// with w_k from probes/probe_weights.glsl (trilinear × backface × Chebyshev visibility), the same
// code the CPU API (engine/gi/probes/probe_volume.cpp) runs.
#include "frame.glsl"
#include "sh.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(std430, set = 1, binding = 3) readonly buffer ProbeSh { float probeSh[]; };      // probe × order² × RGB
layout(std430, set = 1, binding = 4) readonly buffer ProbeMoments { vec2 probeMoments[]; };
layout(std430, set = 1, binding = 5) readonly buffer ProbeValid { uint probeValid[]; };
layout(set = 1, binding = 6) uniform sampler2D aoTerm;  // "ao.term" (1 = unoccluded) when bias.w = 1

layout(push_constant) uniform Push {
  vec4 originSpacing;  // xyz: probe (0,0,0) position, w: spacing (m)
  ivec4 countOrder;    // xyz: probes per axis, w: SH order (2 or 3)
  vec4 bias;           // x: normal bias (m), y: view bias (m), z: Chebyshev variance floor (m²), w: 1 = multiply by aoTerm
} pc;

#define PROBE_DATA_PARAM
#define PROBE_VALID(i) (probeValid[i] != 0u)
#define PROBE_MOMENTS(i, b) probeMoments[(i) * PROBE_VIS_BINS + (b)]
#include "probes/probe_weights.glsl"

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outRadiance;

const float kInvPi = 0.31830988618379067;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) {
    outRadiance = vec4(0.0);
    return;
  }
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  vec3 n = texelFetch(gNormal, pixel, 0).xyz;
  vec3 x = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
  vec3 v = normalize(camera.position.xyz - x);
  vec3 q = x + pc.bias.x * n + pc.bias.y * v;
  int probe[8];
  float weight[8];
  probeWeights(pc.countOrder.xyz, pc.originSpacing.xyz, pc.originSpacing.w, pc.bias.z, q, n, probe, weight);
  int coeffs = pc.countOrder.w * pc.countOrder.w;
  vec3 L[9];
  for (int i = 0; i < 9; ++i) L[i] = vec3(0.0);
  for (int k = 0; k < 8; ++k) {
    if (weight[k] == 0.0) continue;
    int base = probe[k] * coeffs * 3;
    for (int i = 0; i < coeffs; ++i)
      L[i] += weight[k] * vec3(probeSh[base + 3 * i], probeSh[base + 3 * i + 1], probeSh[base + 3 * i + 2]);
  }
  float ao = pc.bias.w > 0.5 ? texelFetch(aoTerm, pixel, 0).r : 1.0;
  outRadiance = vec4(albedo * kInvPi * ao * max(shIrradiance9(L, n), vec3(0.0)), 0.0);
}
