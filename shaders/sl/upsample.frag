#version 450
#extension GL_GOOGLE_include_directive : require
// SL pass 2 at half or quarter resolution, second step (engine/gi/sl/node.cpp): the edge-aware
// upsample of the reduced irradiance "sl.half" / "sl.quarter" (sl.frag with kStep: sample j holds E
// at G-buffer pixel kStep·j) by common/upsample.glsl. The result times ρ/π is ADDED to "lighting.hdr",
// as the full-resolution pass does; drawn over the tiles with any SL (tiles.vert, full-resolution
// tiles).
layout(constant_id = 0) const uint kStep = 2u;  // G-buffer pixels per sample per axis: 2 or 4
#include "frame.glsl"
#include "upsample.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(set = 1, binding = 7) uniform sampler2D slReduced;  // "sl.half" or "sl.quarter"

layout(location = 0) out vec4 outRadiance;

const float kInvPi = 0.31830988618379067;

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
  ivec2 j[4], q[4];
  vec2 f;
  upsampleTaps(pixel, int(kStep), textureSize(slReduced, 0), ivec2(camera.resolution.xy), j, q, f);
  vec3 pq[4], nq[4], e[4];
  bool valid[4];
  for (int k = 0; k < 4; ++k) e[k] = texelFetch(slReduced, j[k], 0).rgb;
  upsampleReceivers(gDepth, gNormal, camera.invViewProj, camera.resolution.zw, q, pq, nq, valid);
  outRadiance = vec4(texelFetch(gAlbedo, pixel, 0).rgb * kInvPi * upsampleBlend(p, n, eye, f, pq, nq, valid, e), 0.0);
}
