#version 450
#extension GL_GOOGLE_include_directive : require
// "sl.shadow"'s hierarchy tile pass (sl/hierarchy_shadow.glsl; hierarchy.hpp clusterShadowParents):
// per drawn tile τ per object and channel at the tile's cluster centre — the receiver hierarchy_ratio.comp
// picks (the centre pixel or the first non-background quarter centre; none: τ = 1) — with the probes'
// radiance there read as probe_shadow.frag reads it (probes/probe_sh.glsl), every SL uncut
// (kInfluence = 0). One invocation per tile; ratios[4 t + o] = (τ_o, 0).
// Set 0: the frame (FrameUbo). Set 1: 0 gNormal, 1 gDepth, 2 probeSh, 3 probeMoments, 6 the tile
// records, 7 out, 8–10 sl_data.glsl. Push: probes::ProbePush, then tile size and count.
layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;
layout(constant_id = 4) const int kCoeffs = 9;
layout(constant_id = 5) const uint kStep = 1u;  // tiles of the reduced target (G-buffer pixel kStep·j)

#include "frame.glsl"
#include "sh.glsl"
layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gNormal;
layout(set = 1, binding = 1) uniform sampler2D gDepth;
layout(set = 1, binding = 2) uniform sampler2D probeSh;
layout(set = 1, binding = 3) uniform sampler2D probeMoments;
layout(push_constant) uniform Push {
  vec4 originSpacing;
  ivec4 countOrder;
  vec4 bias;
  uint tileSize;
  uint tileCount;
} pc;
#include "probes/probe_sh.glsl"
#define SL_SET 1
#define SL_BINDING 8
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/probe_shadow.glsl"
#include "sl/hierarchy.glsl"
#include "sl/hierarchy_shadow.glsl"
layout(std430, set = 1, binding = 6) readonly buffer SlTiles { uvec4 slTiles[]; };
layout(std430, set = 1, binding = 7) writeonly buffer SlRatios { vec4 slRatios[]; };

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t >= pc.tileCount) return;
  uvec2 tile = slTiles[2u * t].xy;
  const vec2 offsets[5] = vec2[5](vec2(0.5), vec2(0.25), vec2(0.75, 0.25), vec2(0.25, 0.75), vec2(0.75));
  ivec2 last = ivec2(camera.resolution.xy) - 1;
  for (uint k = 0u; k < 5u; ++k) {
    ivec2 pixel = ivec2((vec2(tile) + offsets[k]) * float(pc.tileSize));
    pixel *= int(kStep);
    pixel = min(pixel, last);
    float depth = texelFetch(gDepth, pixel, 0).r;
    if (depth >= 1.0) continue;
    vec3 n = texelFetch(gNormal, pixel, 0).xyz;
    vec3 x = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
    vec3 L[9];
    probeRadianceSh(x, n, normalize(camera.position.xyz - x), L);
    for (uint o = 0u; o < kSlHierObjects; ++o) slRatios[4u * t + o] = vec4(slShadowParentRatio(o, x, n, L), 0.0);
    return;
  }
  for (uint o = 0u; o < kSlHierObjects; ++o) slRatios[4u * t + o] = vec4(1.0, 1.0, 1.0, 0.0);
}
