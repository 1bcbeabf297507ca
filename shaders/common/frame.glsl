// Per-frame data shared by every pass (set 0). Units: metres; radiance is linear HDR.
#ifndef BOUNCE_FRAME_GLSL
#define BOUNCE_FRAME_GLSL

struct Camera {
  mat4 view;
  mat4 proj;         // Vulkan clip space: depth 0..1, +Y down (the C++ side flips proj[1][1])
  mat4 viewProj;
  mat4 invViewProj;
  vec4 position;     // xyz world position of the eye
  vec4 resolution;   // width, height, 1/width, 1/height
};

// One drawn mesh primitive instance (engine/render/render_world.hpp: InstanceGpu).
struct Instance {
  mat4 model;
  mat4 normalMatrix;  // inverse-transpose of model's upper 3x3, in a mat4 for std430 alignment
  vec4 albedo;        // rgb base colour factor (linear), a: 1 when a base colour texture is bound
  vec4 emissive;      // rgb emitted radiance factor (linear), a: 1 when an emissive texture is bound
  uvec4 ids;          // x: entity id (for the id buffer / debug view), yzw unused
};

// Reconstructs the world position of a pixel from its depth-buffer value.
vec3 worldFromDepth(mat4 invViewProj, vec2 uv, float depth) {
  vec4 clip = vec4(uv * 2.0 - 1.0, depth, 1.0);
  vec4 world = invViewProj * clip;
  return world.xyz / world.w;
}

#endif
