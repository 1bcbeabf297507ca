#version 450
// Distance from o (metres) of the nearest surface in this texel (the depth test keeps the nearest).
layout(push_constant) uniform Push {
  mat4 viewProj;
  vec4 origin;
  uint instance;
} pc;
layout(location = 0) in vec3 inWorld;
layout(location = 0) out float outDistance;
void main() { outDistance = length(inWorld - pc.origin.xyz); }
