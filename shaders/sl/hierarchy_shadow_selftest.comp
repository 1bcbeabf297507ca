#version 450
// Self-test of sl/hierarchy_shadow.glsl (the §7.3 hierarchy of "sl.shadow") against
// engine/gi/sl/hierarchy.hpp clusterShadowParents / probeShadowHierarchy: kRatioPass: one invocation
// forms τ_o at receiver 0 (x_C) uncut (kInfluence = 0) into ratios[o]; otherwise one invocation per
// receiver writes ΔE with the cut (kInfluence = F) and the parents. The probes' radiance SH is one
// constant L (binding 6, 9 vec4) at every receiver.
// Bindings: 0–2 sl_data.glsl; 3 receivers ({uint count; pad[3]} then (p, n) as two vec4); 4 vec4
// delta[count]; 5 vec4 ratios[kSlHierObjects]; 6 vec4 radiance[9].
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;
layout(constant_id = 4) const bool kRatioPass = false;

#define SL_SET 0
#define SL_BINDING 0
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/probe_shadow.glsl"
#include "sl/hierarchy.glsl"
#include "sl/hierarchy_shadow.glsl"

struct Receiver {
  vec4 p;
  vec4 n;
};
layout(std430, binding = 3) readonly buffer Receivers { uint count; uint pad0; uint pad1; uint pad2; Receiver items[]; } receivers;
layout(std430, binding = 4) writeonly buffer Outputs { vec4 delta[]; } outputs;
layout(std430, binding = 5) buffer Ratios { vec4 ratios[kSlHierObjects]; };
layout(std430, binding = 6) readonly buffer Radiance { vec4 radiance[9]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= receivers.count) return;
  Receiver r = receivers.items[i];
  vec3 L[9];
  for (int k = 0; k < 9; ++k) L[k] = radiance[k].rgb;
  if (kRatioPass) {
    if (i != 0u) return;
    for (uint o = 0u; o < kSlHierObjects; ++o) ratios[o] = vec4(slShadowParentRatio(o, r.p.xyz, r.n.xyz, L), 0.0);
    return;
  }
  uvec4 all = uvec4(0u);
  uint count = min(slCount() + slParentCount(), 128u);
  for (uint w = 0u; w < 4u; ++w) {
    uint bits = uint(clamp(int(count) - int(32u * w), 0, 32));
    all[w] = bits == 32u ? 0xffffffffu : (1u << bits) - 1u;
  }
  vec4 tau[kSlHierObjects];
  for (uint o = 0u; o < kSlHierObjects; ++o) tau[o] = ratios[o];
  vec3 cut = slProbeShadow(r.p.xyz, r.n.xyz, L, all);
  outputs.delta[i] = vec4(slShadowHierarchyAt(r.p.xyz, r.n.xyz, L, all, tau, cut), 0.0);
}
