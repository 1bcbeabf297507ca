#version 450
// Self-test of sl.glsl (pass 2's per-receiver evaluation): one invocation per receiver (p, n) writes
// E(p) (Eq. 14); tests/unit/sl/shade_gpu_test.cpp compares it with sl::evaluate (the C++ reference).
// Receivers (std430, bytes): binding 3 = {uint count; uint pad[3];} then Receiver[count], Receiver =
// 32 (p.xyz, n.xyz in two vec4); binding 4 = vec4 irradiance[count]. Bindings 0–2: sl_data.glsl.
// Dispatch ceil(count / 64) groups.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;
layout(constant_id = 4) const bool kSingleObject = false;  // sl.frag's variant for one object's tiles
#define SL_SINGLE_OBJECT kSingleObject

#define SL_SET 0
#define SL_BINDING 0
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"

struct Receiver {
  vec4 p;
  vec4 n;
};
layout(std430, binding = 3) readonly buffer Receivers { uint count; uint pad0; uint pad1; uint pad2; Receiver items[]; } receivers;
layout(std430, binding = 4) writeonly buffer Outputs { vec4 irradiance[]; } outputs;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= receivers.count) return;
  Receiver r = receivers.items[i];
  outputs.irradiance[i] = vec4(slIrradianceAt(r.p.xyz, r.n.xyz), 0.0);
}
