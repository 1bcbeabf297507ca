#version 450
#extension GL_GOOGLE_include_directive : require
// DNRT clustered mode: refines this frame's CPU tile masks (engine/gi/dnrt/cluster.hpp, each
// object's screen hull) by the depth range of the tile's pixels, before clustered.frag reads them.
// One workgroup per 16×16 tile and batch. The tile's visible surface lies inside the frustum slab
// between its nearest and farthest depth; an object whose outer cube |q|∞ < outer does not meet the
// q-space box around that slab's 8 corners cannot reach any of its pixels (s(r) = 0, Eq. 16), so its
// bit is cleared. A superset still: clustered.frag tests every pixel exactly, the masks only decide
// which objects a pixel visits, never what it adds (the images are the same).
// Why: the fragment shader's first loop visits every object of its tile's mask with per-lane loads
// of the record (llvmpipe; README "What costs what on lavapipe"); on cornell-10 the screen hulls
// gave 8.2 objects a pixel where 4.1 have the pixel inside their outer cube (README "DNRT and probes
// cost, session 9").
#include "dnrt/dnrt.glsl"

// One invocation per tile, its 256 depths read in a loop: no barriers or shared atomics, which
// llvmpipe runs as coroutine switches per invocation (a 16×16 workgroup per tile with them cost more
// than the masks saved; README "DNRT and probes cost, session 9").
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D gDepth;
layout(std430, set = 0, binding = 1) buffer Tiles { uint tileMasks[]; };
layout(std140, set = 0, binding = 2) uniform Objects { DnrtClusterObject objects[kDnrtClusterBatch]; };
layout(push_constant) uniform Push {
  mat4 invViewProj;  // the frame's camera (frame.glsl Camera.invViewProj)
  vec2 invSize;      // 1 / the render target's pixels
  uint tileBase;     // this batch's first mask
  uint tilesX;
  uint tilesY;
} pc;

// frame.glsl's worldFromDepth (not included: its Camera block is the graphics passes' set 0).
vec3 worldAt(vec2 uv, float depth) {
  vec4 world = pc.invViewProj * vec4(uv * 2.0 - 1.0, depth, 1.0);
  return world.xyz / world.w;
}

void main() {
  const ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
  if (tile.x >= int(pc.tilesX) || tile.y >= int(pc.tilesY)) return;
  const uint index = pc.tileBase + uint(tile.y) * pc.tilesX + uint(tile.x);
  const uint mask = tileMasks[index];
  if (mask == 0u) return;
  const ivec2 size = textureSize(gDepth, 0);
  const ivec2 p0 = tile * (1 << kDnrtClusterTileShift);
  const ivec2 p1 = min(p0 + (1 << kDnrtClusterTileShift), size);
  float zMin = 1.0, zMax = 0.0;
  // 2×2 texels a fetch: textureGather at the corner they share (texels (x, y) … (x + 1, y + 1)); on a
  // tile with an odd last row or column the clamp repeats an edge texel, which only widens the range.
  for (int y = p0.y; y < p1.y; y += 2)
    for (int x = p0.x; x < p1.x; x += 2) {
      const vec4 d = textureGather(gDepth, vec2(x + 1, y + 1) * pc.invSize, 0);
      // Background texels (depth 1) are discarded by clustered.frag and bound nothing.
      const vec4 lo = mix(d, vec4(1.0), greaterThanEqual(d, vec4(1.0)));
      const vec4 hi = mix(d, vec4(0.0), greaterThanEqual(d, vec4(1.0)));
      zMin = min(zMin, min(min(lo.x, lo.y), min(lo.z, lo.w)));
      zMax = max(zMax, max(max(hi.x, hi.y), max(hi.z, hi.w)));
    }
  uint kept = 0u;
  if (zMin <= zMax) {
    // The slab's corners: the tile's pixel rectangle (its pixel centres lie inside) at the nearest
    // and farthest depth; the slab is their convex hull (the map from clip space to the world is
    // projective and the slab lies in front of the eye), so the q-space box of the 8 corners holds
    // the q of every pixel of the tile.
    const vec2 lo = vec2(p0) * pc.invSize, hi = vec2(p1) * pc.invSize;
    vec3 corner[8];
    for (int c = 0; c < 8; ++c)
      corner[c] = worldAt(vec2((c & 1) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y), (c & 4) != 0 ? zMax : zMin);
    uint m = mask;
    do {
      const int i = findLSB(m);
      vec3 qLo = vec3(3.0e38), qHi = vec3(-3.0e38);
      for (int c = 0; c < 8; ++c) {
        const vec4 r = vec4(corner[c], 1.0);
        const vec3 q = vec3(dot(objects[i].worldToQ[0], r), dot(objects[i].worldToQ[1], r), dot(objects[i].worldToQ[2], r));
        qLo = min(qLo, q);
        qHi = max(qHi, q);
      }
      // Margin for the float rounding of the corners' reconstruction and transform against the
      // pixels' own (relative ~10⁻⁶): 10⁻³ of the outer half-size, so the test stays a superset.
      const float outer = objects[i].extents.y * 1.001;
      if (all(lessThan(qLo, vec3(outer))) && all(greaterThan(qHi, vec3(-outer)))) kept |= 1u << uint(i);
      m &= m - 1u;
    } while (m != 0u);
  }
  tileMasks[index] = kept;
}
