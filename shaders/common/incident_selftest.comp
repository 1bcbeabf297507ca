#version 450
// Self-test of incident.glsl: one invocation per case adds one light's SH at one receiver to zero
// coefficients (incidentAddLight) and writes them; tests/unit/incident compares them with the CPU
// face (engine/gi/incident, the same file compiled as C++).
// std430 layouts (bytes): binding 0 = {uint count; uint pad[3];} then Case[count], Case = 112
// (Light at 0 (80 bytes, lights.glsl), pointRadius vec4 at 80 (xyz p, w radius), visibility
// vec4 at 96 (x)); binding 1 = Output[count], Output = 144 (sh[9] vec4, rgb = coefficient).
// Dispatch ceil(count / 64) groups.
#extension GL_GOOGLE_include_directive : require
#include "incident.glsl"

layout(local_size_x = 64) in;

struct Case {
  Light light;
  vec4 pointRadius;
  vec4 visibility;
};
struct Output {
  vec4 sh[9];
};

layout(std430, binding = 0) readonly buffer Cases { uint count; uint pad0; uint pad1; uint pad2; Case items[]; } cases;
layout(std430, binding = 1) writeonly buffer Outputs { Output items[]; } outputs;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= cases.count) return;
  vec3 sh[9];
  for (int k = 0; k < 9; ++k) sh[k] = vec3(0.0);
  Case c = cases.items[i];
  incidentAddLight(c.light, c.pointRadius.xyz, c.pointRadius.w, c.visibility.x, sh);
  for (int k = 0; k < 9; ++k) outputs.items[i].sh[k] = vec4(sh[k], 0.0);
}
