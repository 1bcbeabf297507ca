#version 450
#extension GL_GOOGLE_include_directive : require
// SL hierarchy's tile pass (§7.3 Eq. 25; sl/hierarchy.glsl, engine/gi/sl/hierarchy.hpp
// clusterParents): per drawn tile of pass 2 ("sl"), Eq. 25's t per object and RGB channel at the
// tile's cluster centre x_C — the G-buffer receiver at the tile's centre pixel (or, where that is
// background, the first of its four quarter centres that is not; none: t = 1) — from the flat
// evaluation over every SL without the cut (kInfluence = 0: one flat evaluation per tile, cheap next
// to the tile's 256 pixels). One invocation per tile; ratios[4 t + o] = (t_o, 0).
// Bindings (set 0): 0 gNormal, 1 gDepth, 3–5 sl_data.glsl, 6 the tile records (tiles.glsl's), 7 out.
layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;  // 0 here: Eq. 25 is against the uncut children
layout(constant_id = 4) const uint kStep = 1u;  // tiles of the reduced target (G-buffer pixel kStep·j)

#include "frame.glsl"
layout(set = 0, binding = 0) uniform sampler2D gNormal;
layout(set = 0, binding = 1) uniform sampler2D gDepth;
#define SL_SET 0
#define SL_BINDING 3
#define SL_OBJECT_TERMS 4
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/hierarchy.glsl"
layout(std430, set = 0, binding = 6) readonly buffer SlTiles { uvec4 slTiles[]; };
layout(std430, set = 0, binding = 7) writeonly buffer SlRatios { vec4 slRatios[]; };

layout(push_constant) uniform Push {
  mat4 invViewProj;
  vec4 screen;  // G-buffer width, height, 1/width, 1/height
  uint tileSize;
  uint tileCount;
} pc;

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t >= pc.tileCount) return;
  uvec2 tile = slTiles[2u * t].xy;
  const vec2 offsets[5] = vec2[5](vec2(0.5), vec2(0.25), vec2(0.75, 0.25), vec2(0.25, 0.75), vec2(0.75));
  ivec2 last = ivec2(pc.screen.xy) - 1;
  for (uint k = 0u; k < 5u; ++k) {
    ivec2 pixel = ivec2((vec2(tile) + offsets[k]) * float(pc.tileSize));
    pixel *= int(kStep);
    pixel = min(pixel, last);
    float depth = texelFetch(gDepth, pixel, 0).r;
    if (depth >= 1.0) continue;
    vec3 n = texelFetch(gNormal, pixel, 0).xyz;
    vec3 p = worldFromDepth(pc.invViewProj, (vec2(pixel) + 0.5) * pc.screen.zw, depth);
    slIrradianceAt(p, n);  // every SL, uncut: fills slObjectTerms
    for (uint o = 0u; o < kSlHierObjects; ++o) slRatios[4u * t + o] = vec4(slParentRatio(o, p, n), 0.0);
    return;
  }
  for (uint o = 0u; o < kSlHierObjects; ++o) slRatios[4u * t + o] = vec4(1.0, 1.0, 1.0, 0.0);
}
