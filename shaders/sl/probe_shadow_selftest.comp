#version 450
// Self-test of sl/probe_shadow.glsl with probes/probe_sh.glsl: one invocation per receiver (p, n, v)
// reads the probes' radiance SH L as the probes pass does and writes (ΔE, 0) and (E_u, 0) —
// tests/unit/sl/probe_shadow_gpu_test.cpp compares them with sl::probeShadow and the probe volume's
// CPU lookup. Bindings 0–2: sl_data.glsl; 3: probeSh, 4: probeMoments; 5 (std430): {uint count;
// uint pad[3];} then Receiver[count] = 48 bytes (p, n, v in three vec4); 6: vec4 out[2·count];
// 7: sl_data.glsl's SlIndirect (the SLs' radiance SH, read with kBlockedAtSphere, id 5; their
// direction maps with kBlockedMap, id 6).
// Push constants: probe_sh.glsl's. Dispatch ceil(count / 64) groups.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;
layout(constant_id = 4) const int kCoeffs = 9;
layout(constant_id = 5) const bool kBlockedAtSphere = false;  // "blocked_light": "sphere" (binding 7)
layout(constant_id = 6) const bool kBlockedMap = false;       // "blocked_read": "map" (binding 7 holds maps)

#include "sh.glsl"

layout(binding = 3) uniform sampler2D probeSh;
layout(binding = 4) uniform sampler2D probeMoments;
layout(push_constant) uniform Push {
  vec4 originSpacing;
  ivec4 countOrder;
  vec4 bias;
} pc;
#include "probes/probe_sh.glsl"
#define SL_SET 0
#define SL_BINDING 0
#define SL_INDIRECT_BINDING 7
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/probe_shadow.glsl"

struct Receiver {
  vec4 p;
  vec4 n;
  vec4 v;
};
layout(std430, binding = 5) readonly buffer Receivers { uint count; uint pad0; uint pad1; uint pad2; Receiver items[]; } receivers;
layout(std430, binding = 6) writeonly buffer Outputs { vec4 values[]; } outputs;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= receivers.count) return;
  Receiver r = receivers.items[i];
  vec3 L[9];
  probeRadianceSh(r.p.xyz, r.n.xyz, r.v.xyz, L);
  outputs.values[2u * i] = vec4(slProbeShadow(r.p.xyz, r.n.xyz, L, kBlockedAtSphere, kBlockedMap), 0.0);
  outputs.values[2u * i + 1u] = vec4(shIrradiance9(L, r.n.xyz), 0.0);
}
