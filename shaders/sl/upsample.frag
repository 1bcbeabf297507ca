#version 450
#extension GL_GOOGLE_include_directive : require
// SL pass 2 at half resolution, second step (engine/gi/sl/node.cpp): a joint bilateral upsample of
// the half-size irradiance "sl.half" (sl.frag with kHalf: sample j holds E at G-buffer pixel 2j).
// Each full-resolution pixel blends its up to 4 nearest samples with bilinear weights times how well
// each sample's receiver matches its own: the distance of the sample's point from this pixel's
// tangent plane, relative to the distance from the eye (Gaussian, kPlaneScale), and the normals'
// agreement (max(0, n·n_j)^kNormalPower) — so light does not bleed across depth or crease edges. When
// every sample is rejected with its bilinear weight (a thin feature between samples) the best-matching
// sample alone is used. The result times ρ/π is ADDED to "lighting.hdr", as the full-resolution pass
// does; drawn over the tiles with any SL (tiles.vert, full-resolution tiles).
#include "frame.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(set = 1, binding = 7) uniform sampler2D slHalf;

layout(location = 0) out vec4 outRadiance;

const float kInvPi = 0.31830988618379067;
const float kPlaneScale = 0.01;  // plane distance / eye distance at which the weight is e^-1
const float kNormalPower = 8.0;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) {
    outRadiance = vec4(0.0);
    return;
  }
  vec3 n = texelFetch(gNormal, pixel, 0).xyz;
  vec3 p = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
  float eye = max(length(p - camera.position.xyz), 1e-6);
  ivec2 full = ivec2(camera.resolution.xy);
  ivec2 halfSize = textureSize(slHalf, 0);
  // Sample j sits at G-buffer pixel 2j: this pixel lies between samples j0 and j0 + 1 per axis.
  vec2 u = vec2(pixel) * 0.5;
  ivec2 j0 = ivec2(floor(u));
  vec2 f = u - vec2(j0);
  vec3 sum = vec3(0.0), best = vec3(0.0);
  float weight = 0.0, bestMatch = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 j = min(j0 + ivec2(k & 1, k >> 1), halfSize - 1);
    ivec2 q = min(2 * j, full - 1);
    float dq = texelFetch(gDepth, q, 0).r;
    vec3 nq = texelFetch(gNormal, q, 0).xyz;
    vec3 pq = worldFromDepth(camera.invViewProj, (vec2(q) + 0.5) * camera.resolution.zw, dq);
    float plane = abs(dot(n, pq - p)) / (eye * kPlaneScale);
    float match = dq < 1.0 ? exp(-plane * plane) * pow(max(dot(n, nq), 0.0), kNormalPower) : 0.0;
    float bilinear = ((k & 1) != 0 ? f.x : 1.0 - f.x) * ((k >> 1) != 0 ? f.y : 1.0 - f.y);
    vec3 e = texelFetch(slHalf, j, 0).rgb;
    sum += bilinear * match * e;
    weight += bilinear * match;
    if (match > bestMatch) {
      bestMatch = match;
      best = e;
    }
  }
  vec3 e = weight > 1e-4 ? sum / weight : best;
  outRadiance = vec4(texelFetch(gAlbedo, pixel, 0).rgb * kInvPi * e, 0.0);
}
