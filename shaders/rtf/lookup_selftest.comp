#version 450
// Self-test of rtf.glsl: one invocation per point q (object frame, units of η) writes the looked-up
// ξ (16 RGB) and OOF (16 floats); tests/unit/rtf/lookup_gpu_test.cpp compares them with
// engine/gi/rtf/evaluate.cpp. std430 (bytes): binding 0 = vec4 points[count]; binding 1 =
// Output[count], Output = 16 vec4 (rgb: ξ_i) then 16 floats (V_i): 320 bytes.
#extension GL_GOOGLE_include_directive : require
#include "rtf.glsl"

layout(local_size_x = 64) in;

struct Output {
  vec4 xi[16];
  float v[16];
};
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) writeonly buffer Outputs { Output outputs[]; };
layout(binding = 2) uniform sampler2DArray xiTex;
layout(binding = 3) uniform sampler2DArray oofTex;

layout(push_constant) uniform Push {
  uint count;
  int spheres;
  int faceSize;
  float innerRadius;
  float outerRadius;
} pc;

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t >= pc.count) return;
  RtfGrid g = RtfGrid(pc.spheres, pc.faceSize, pc.innerRadius, pc.outerRadius);
  vec3 L[16];
  float V[16];
  rtfInterreflection(xiTex, g, points[t].xyz, 16, L);
  rtfOcclusion(oofTex, g, points[t].xyz, V);
  for (int i = 0; i < 16; ++i) {
    outputs[t].xi[i] = vec4(L[i], 0.0);
    outputs[t].v[i] = V[i];
  }
}
