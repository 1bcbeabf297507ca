// Shared inputs of the screen-space AO baselines (engine/gi/ao): G-buffer depth and world normals,
// the frame camera, and the push constants. Output: ambient visibility in [0, 1] (1 = open).
#ifndef BOUNCE_AO_COMMON_GLSL
#define BOUNCE_AO_COMMON_GLSL
#include "frame.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gNormal;
layout(set = 1, binding = 1) uniform sampler2D gDepth;

layout(push_constant) uniform Push {
  float radius;     // world-space radius of the neighbourhood (metres)
  float bias;       // world-space depth bias (SSAO) / sine bias (HBAO) against self-occlusion
  uint samples;     // SSAO: kernel size; HBAO: steps per direction
  uint directions;  // HBAO: screen directions
} pc;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outAo;

vec3 worldAt(vec2 uv, float depth) { return worldFromDepth(camera.invViewProj, uv, depth); }
float viewDepth(vec3 world) { return -(camera.view * vec4(world, 1.0)).z; }

// Interleaved gradient noise (Jimenez 2014): a per-pixel rotation that a small kernel turns into
// fine noise instead of banding (no blur pass: the baselines are measured raw).
float ign(vec2 pixel) { return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715)))); }

#endif
