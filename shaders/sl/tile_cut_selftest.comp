#version 450
// Self-test of sl/tile_cut.glsl: one invocation per crafted tile box writes its cut candidate list;
// tests/unit/sl/tile_cut_gpu_test.cpp checks each list bit for bit. Bindings 0–2: sl_data.glsl;
// binding 3 = {uint count; uint pad[3];} then Box[count], Box = (lo.xyz, hi.xyz, mask) in 48 bytes;
// binding 4 = uvec4 kept[count]. Dispatch ceil(count / 64) groups.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;
layout(constant_id = 0) const float kInfluence = 0.0;

#define SL_SET 0
#define SL_BINDING 0
#include "sl/sl_data.glsl"
#include "sl/tile_cut.glsl"

struct Box {
  vec4 lo;
  vec4 hi;
  uvec4 mask;
};
layout(std430, binding = 3) readonly buffer Boxes { uint count; uint pad0; uint pad1; uint pad2; Box items[]; } boxes;
layout(std430, binding = 4) writeonly buffer Outputs { uvec4 kept[]; } outputs;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= boxes.count) return;
  Box b = boxes.items[i];
  outputs.kept[i] = slBoxCut(b.lo.xyz, b.hi.xyz, b.mask);
}
