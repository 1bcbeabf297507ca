#version 450
#extension GL_GOOGLE_include_directive : require
// Intrusion map of one DNRT object: every other drawn mesh seen from o through one cube face.
#include "frame.glsl"

layout(std430, set = 0, binding = 1) readonly buffer Instances { Instance instances[]; };
layout(push_constant) uniform Push {
  mat4 viewProj;  // the face's view-projection (node.cpp: cubeFaceViewProj)
  vec4 origin;    // xyz o (world)
  uint instance;
} pc;

layout(location = 0) in vec3 inPosition;
layout(location = 0) out vec3 outWorld;

void main() {
  vec4 world = instances[pc.instance].model * vec4(inPosition, 1.0);
  outWorld = world.xyz;
  gl_Position = pc.viewProj * world;
}
