#version 450
#extension GL_GOOGLE_include_directive : require
// Depth-only rendering into one layer of the shadow atlas (a 2D array: one layer per directional or
// spot light, six per point light — one per cube face). The layer's light view-projection matrix
// comes from the shadow-matrix buffer, which the lighting pass reads too.
#include "frame.glsl"

layout(std430, set = 0, binding = 1) readonly buffer Instances { Instance instances[]; };
layout(std430, set = 0, binding = 2) readonly buffer ShadowMatrices { mat4 shadowMatrices[]; };
layout(push_constant) uniform Push { uint instance; uint layer; } pc;

layout(location = 0) in vec3 inPosition;

void main() {
  gl_Position = shadowMatrices[pc.layer] * (instances[pc.instance].model * vec4(inPosition, 1.0));
}
