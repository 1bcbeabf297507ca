#version 450
#extension GL_GOOGLE_include_directive : require
// Shared vertex stage for the G-buffer pass: world position, normal and UV0 per instance.
#include "frame.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(std430, set = 0, binding = 1) readonly buffer Instances { Instance instances[]; };
layout(push_constant) uniform Push { uint instance; } pc;

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec2 outUv;
layout(location = 2) out vec3 outWorld;

void main() {
  Instance inst = instances[pc.instance];
  vec4 world = inst.model * vec4(inPosition, 1.0);
  outWorld = world.xyz;
  outNormal = mat3(inst.normalMatrix) * inNormal;
  outUv = inUv;
  gl_Position = camera.viewProj * world;
}
