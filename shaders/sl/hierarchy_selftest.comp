#version 450
// Self-test of sl/hierarchy.glsl (§7.3 Eq. 25–26 on the GPU) against engine/gi/sl/hierarchy.hpp:
// kRatioPass: one invocation forms Eq. 25's t_o at receiver 0 (x_C) over every SL, uncut
// (kInfluence = 0), into ratios[o]; otherwise one invocation per receiver writes Eq. 26: the flat
// evaluation with the cut (kInfluence = F) plus slHierarchyAt with those ratios.
// Bindings: 0–2 sl_data.glsl; 3 receivers ({uint count; pad[3]} then (p, n) as two vec4); 4 vec4
// irradiance[count]; 5 vec4 ratios[kSlHierObjects]. Dispatch ceil(count / 64) groups.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;
layout(constant_id = 4) const bool kRatioPass = false;

#define SL_SET 0
#define SL_BINDING 0
#define SL_OBJECT_TERMS 4
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/hierarchy.glsl"

struct Receiver {
  vec4 p;
  vec4 n;
};
layout(std430, binding = 3) readonly buffer Receivers { uint count; uint pad0; uint pad1; uint pad2; Receiver items[]; } receivers;
layout(std430, binding = 4) writeonly buffer Outputs { vec4 irradiance[]; } outputs;
layout(std430, binding = 5) buffer Ratios { vec4 ratios[kSlHierObjects]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= receivers.count) return;
  Receiver r = receivers.items[i];
  if (kRatioPass) {
    if (i != 0u) return;
    slIrradianceAt(r.p.xyz, r.n.xyz);  // fills slObjectTerms
    for (uint o = 0u; o < kSlHierObjects; ++o) ratios[o] = vec4(slParentRatio(o, r.p.xyz, r.n.xyz), 0.0);
    return;
  }
  uvec4 all = uvec4(0u);
  uint count = min(slCount() + slParentCount(), 128u);
  for (uint w = 0u; w < 4u; ++w) {
    uint bits = uint(clamp(int(count) - int(32u * w), 0, 32));
    all[w] = bits == 32u ? 0xffffffffu : (1u << bits) - 1u;
  }
  vec4 t[kSlHierObjects];
  for (uint o = 0u; o < kSlHierObjects; ++o) t[o] = ratios[o];
  vec3 e = slIrradianceAt(r.p.xyz, r.n.xyz, all) + slHierarchyAt(r.p.xyz, r.n.xyz, all, t);
  outputs.irradiance[i] = vec4(e, 0.0);
}
