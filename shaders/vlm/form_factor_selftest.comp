#version 450
#extension GL_GOOGLE_include_directive : require
// Evaluates vlmFormFactor for a list of cases so tests/unit/vlm can compare it with the C++
// engine/gi/vlm/form_factor.hpp (float instantiation) on the same inputs.
#include "vlm/form_factor.glsl"

layout(local_size_x = 64) in;

struct Case {
  vec4 x, n, v0, v1, v2;  // xyz used
};
layout(std430, set = 0, binding = 0) readonly buffer Inputs {
  uint count;
  uint pad0, pad1, pad2;
  Case cases[];
};
layout(std430, set = 0, binding = 1) writeonly buffer Outputs { float results[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  Case c = cases[i];
  results[i] = vlmFormFactor(c.x.xyz, c.n.xyz, c.v0.xyz, c.v1.xyz, c.v2.xyz);
}
