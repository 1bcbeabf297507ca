#version 450
// Self-test of sh.glsl: one invocation per direction writes the 16 basis values, the RGB
// reconstruction of 16 coefficients, and the irradiance from 4, 9 and 16 coefficients. The GPU
// cross-check test compares these with engine/math.
// std430 layouts (bytes): binding 0 = {uint count; uint pad[3];} then Input[count], Input = 272
// (dir vec4 at 0, coeff[16] vec4 at 16); binding 1 = Output[count], Output = 128 (basis[16]
// floats at 0, evalSum at 64, irradiance4 at 80, irradiance9 at 96, irradiance16 at 112).
// Dispatch ceil(count / 64) groups.
#extension GL_GOOGLE_include_directive : require
#include "sh.glsl"

layout(local_size_x = 64) in;

struct Input {
  vec4 dir;        // xyz: unit direction; w unused
  vec4 coeff[16];  // rgb: radiance SH coefficient i; a unused
};
struct Output {
  float basis[16];
  vec4 evalSum;     // rgb: Σ c_i Y_i(dir) over 16 coefficients
  vec4 irradiance4;
  vec4 irradiance9;
  vec4 irradiance16;
};

layout(std430, binding = 0) readonly buffer Inputs { uint count; uint pad0; uint pad1; uint pad2; Input items[]; } inputs;
layout(std430, binding = 1) writeonly buffer Outputs { Output items[]; } outputs;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= inputs.count) return;
  vec3 d = inputs.items[i].dir.xyz;
  float y[16];
  shEval16(d, y);
  for (int k = 0; k < 16; ++k) outputs.items[i].basis[k] = y[k];
  vec3 c16[16];
  for (int k = 0; k < 16; ++k) c16[k] = inputs.items[i].coeff[k].rgb;
  vec3 c9[9];
  for (int k = 0; k < 9; ++k) c9[k] = c16[k];
  vec3 c4[4];
  for (int k = 0; k < 4; ++k) c4[k] = c16[k];
  outputs.items[i].evalSum = vec4(shEvalSum16(c16, d), 0.0);
  outputs.items[i].irradiance4 = vec4(shIrradiance4(c4, d), 0.0);
  outputs.items[i].irradiance9 = vec4(shIrradiance9(c9, d), 0.0);
  outputs.items[i].irradiance16 = vec4(shIrradiance16(c16, d), 0.0);
}
