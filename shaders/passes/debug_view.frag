#version 450
#extension GL_GOOGLE_include_directive : require
// Debug views, written straight to the display target (sRGB-encoded):
//   1 albedo, 2 normal (n·0.5+0.5), 3 depth (linear distance, depthMin..depthMax → white..black:
//     the scene bounds' nearest point..farthest corner, render::depthViewRange),
//   4 shadow (visibility of light 0), 5 entity id (a distinct colour per entity, black background).
#include "frame.glsl"
#include "color.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform usampler2D gEntity;
layout(set = 1, binding = 3) uniform sampler2D gDepth;
layout(set = 1, binding = 4) uniform sampler2DArrayShadow shadowAtlas;
#include "lights.glsl"
// Uniform blocks, not storage buffers (lights.glsl kMaxLights says why).
layout(std140, set = 1, binding = 5) uniform ShadowMatrices { mat4 shadowMatrices[kMaxShadowLayers]; };
#include "shadow.glsl"
layout(std140, set = 1, binding = 6) uniform Lights { Light lights[kMaxLights]; };

layout(push_constant) uniform Push { uint mode; uint lightCount; float depthMin; float depthMax; } pc;
layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

vec3 idColor(uint id) {
  uint h = id * 2654435761u;  // Knuth multiplicative hash: neighbouring ids get distant hues
  return vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  bool background = depth >= 1.0;
  vec3 c = vec3(0.0);
  if (pc.mode == 1u) {
    c = linearToSrgb(texelFetch(gAlbedo, pixel, 0).rgb);
  } else if (pc.mode == 2u) {
    c = background ? vec3(0.0) : texelFetch(gNormal, pixel, 0).xyz * 0.5 + 0.5;
  } else if (pc.mode == 3u) {
    vec3 p = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
    float t = (distance(p, camera.position.xyz) - pc.depthMin) / (pc.depthMax - pc.depthMin);
    c = background ? vec3(0.0) : vec3(1.0 - clamp(t, 0.0, 1.0));
  } else if (pc.mode == 4u) {
    if (!background && pc.lightCount > 0u) {
      vec3 p = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
      vec3 l;
      float dist;
      incidentIrradiance(lights[0], p, l, dist);
      c = vec3(shadowVisibility(lights[0], p, texelFetch(gNormal, pixel, 0).xyz, dist));
    }
  } else if (pc.mode == 5u) {
    uint id = texelFetch(gEntity, pixel, 0).r;
    c = id == 0u ? vec3(0.0) : idColor(id);
  }
  outColor = vec4(c, 1.0);
}
