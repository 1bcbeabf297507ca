#version 450
// Self-test of common/upsample.glsl: one invocation per case runs upsampleTaps and upsampleBlend;
// tests/unit/sl/upsample_gpu_test.cpp compares them with sl::upsampleTaps / sl::upsampleBlend.
// Cases (std430): binding 0 = {uint count; uint pad[3];} then Case[count]; binding 1 = Result[count].
// Dispatch ceil(count / 64) groups (tests/support/compute_selftest.hpp).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;
#include "upsample.glsl"

struct Case {
  ivec4 pixel;  // x, y, step, 0
  ivec4 sizes;  // reduced size xy, full size zw
  vec4 p;       // xyz, w = eye distance
  vec4 n;       // xyz
  vec4 f;       // xy: the bilinear fractions of the blend
  vec4 pq[4];   // xyz, w = 1 valid / 0 background
  vec4 nq[4];
  vec4 e[4];
};
struct Result {
  vec4 e;       // rgb: the blend
  ivec4 j[2];   // taps 0, 1 | 2, 3
  ivec4 q[2];
  vec4 f;       // xy: upsampleTaps' fractions
};
layout(std430, binding = 0) readonly buffer Cases { uint count; uint pad0; uint pad1; uint pad2; Case items[]; } cases;
layout(std430, binding = 1) writeonly buffer Results { Result items[]; } results;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= cases.count) return;
  Case c = cases.items[i];
  ivec2 j[4], q[4];
  vec2 f;
  upsampleTaps(c.pixel.xy, c.pixel.z, c.sizes.xy, c.sizes.zw, j, q, f);
  vec3 pq[4], nq[4], e[4];
  bool valid[4];
  for (int k = 0; k < 4; ++k) {
    pq[k] = c.pq[k].xyz;
    nq[k] = c.nq[k].xyz;
    valid[k] = c.pq[k].w > 0.5;
    e[k] = c.e[k].xyz;
  }
  Result r;
  r.e = vec4(upsampleBlend(c.p.xyz, c.n.xyz, c.p.w, c.f.xy, pq, nq, valid, e), 0.0);
  r.j[0] = ivec4(j[0], j[1]);
  r.j[1] = ivec4(j[2], j[3]);
  r.q[0] = ivec4(q[0], q[1]);
  r.q[1] = ivec4(q[2], q[3]);
  r.f = vec4(f, 0.0, 0.0);
  results.items[i] = r;
}
