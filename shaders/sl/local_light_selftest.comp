#version 450
// Self-test of sl/local_light.glsl: one invocation per receiver writes the visible fraction v of its
// light; tests/unit/sl/local_light_gpu_test.cpp compares it with sl::localLightVisibility (Cap form).
// Receivers (std430): binding 3 = {uint count; uint pad[3];} then Receiver[count], Receiver = 48 bytes
// (p.xyz, n.xyz, light centre xyz + radius w in three vec4); binding 4 = vec4 out[count] (x = v).
// Bindings 0–2: sl_data.glsl. Dispatch ceil(count / 64) groups.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;

#define SL_SET 0
#define SL_BINDING 0
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/local_light.glsl"

struct Receiver {
  vec4 p;
  vec4 n;
  vec4 light;
};
layout(std430, binding = 3) readonly buffer Receivers { uint count; uint pad0; uint pad1; uint pad2; Receiver items[]; } receivers;
layout(std430, binding = 4) writeonly buffer Outputs { vec4 v[]; } outputs;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= receivers.count) return;
  Receiver r = receivers.items[i];
  uint count = min(slCount(), kSpheres);
  uvec4 all = uvec4(0u);
  for (uint w = 0u; w < 4u; ++w) {
    uint bits = uint(clamp(int(count) - int(32u * w), 0, 32));
    all[w] = bits == 32u ? 0xffffffffu : (1u << bits) - 1u;
  }
  outputs.v[i] = vec4(slLocalVisibility(r.p.xyz, r.n.xyz, r.light.xyz, r.light.w, all), 0.0, 0.0, 0.0);
}
