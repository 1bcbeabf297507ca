// SL pass 2, tiled (engine/gi/sl/tiles.hpp): one instance per 16×16-pixel screen tile that some SL's
// influence bound covers, two triangles each. The tile's list of SLs (4 words of bits, SL i at bit
// i % 32 of word i / 32) goes to the fragment shader as a flat varying: read once per vertex, not per
// pixel (DESIGN.md: flat varyings are the cheapest per-pixel constants on llvmpipe). Tiles no SL
// covers are not drawn, so their pixels do no work. Included by tiles.vert (push block at offset 0:
// sl.upsample), cut_tiles.vert (offset 0: sl without the hierarchy, with SL_TILE_CUT: the list cut by
// the tile's receivers), hierarchy_tiles.vert, local_tiles.vert, shadow_cut_tiles.vert (after the
// fragment shader's probe block: sl.shadow and the fused sl + sl.shadow, with SL_TILE_CUT) and
// shadow_tiles.vert (the same uncut: scene::Sl::tileCut false, a test's), with SL_TILE_PUSH_OFFSET
// defined first (bytes; engine/gi/sl/tiles.hpp TilePush). tiles.vert also draws "sl" uncut then.
// Tile records (std430): tiles[2t] = (tile x, tile y, 0, 0), tiles[2t + 1] = the 4 mask words.
layout(std430, set = 1, binding = 6) readonly buffer SlTiles { uvec4 slTiles[]; };
layout(push_constant) uniform Push {
  layout(offset = SL_TILE_PUSH_OFFSET) vec2 invExtent;  // 1 / the target's pixels (the tiles are in the target's pixels)
  uint tileSize;   // pixels per tile side (gi::kScreenTile)
} pc;

layout(location = 0) flat out uvec4 outCandidates;

#ifdef SL_TILE_CUT
// The tile's list cut by its receivers' world box (sl/tile_cut.glsl, which says why). The receivers
// are reconstructed as sl/receiver.glsl does per pixel (the same G-buffer pixel, the same
// worldFromDepth) — 256 texel reads per vertex, against a walk body per listed SL for every 8-pixel
// block of the tile. The includer declares camera (frame.glsl), gDepth, sl_data.glsl (slSphere),
// kInfluence and kStep (G-buffer pixels per target pixel per axis: the receiver of target pixel j is
// G-buffer pixel min(kStep·j, size − 1)).
#include "upsample.glsl"  // reducedSamplePixel: the one mapping of a reduced sample to its G-buffer pixel
#include "sl/tile_cut.glsl"

// The cut pays only where the tile lists enough SLs. Its cost is fixed per tile: 256 receivers
// rebuilt per vertex batch, in llvmpipe's vertex stage, which runs on one thread (the fragment
// tiles run on every core); its saving is at most one walk body per dropped SL for each of the
// tile's 32 8-pixel blocks. Measured (session 15, README "Tile lists cut …, session 15"): on
// cornell-1 (8 SLs, full resolution, nearly every tile drawn) cutting every tile made "sl" 7–20 %
// slower than main's uncut lists; at 128 SLs (bench sl --fused) both blockings gained. A tile listing fewer
// than kSlCutMinListed keeps its list (exact either way: the cut only drops SLs rule 0 culls).
const uint kSlCutMinListed = 9u;

uvec4 slCutTile(uvec2 tile, uvec4 mask) {
  uvec4 listed = uvec4(bitCount(mask));
  if (listed.x + listed.y + listed.z + listed.w < kSlCutMinListed) return mask;
  uvec2 extent = uvec2(round(1.0 / pc.invExtent));
  uvec2 first = tile * pc.tileSize;
  uvec2 last = min(first + pc.tileSize, extent);  // exclusive
  ivec2 gmax = ivec2(camera.resolution.xy) - 1;
  vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);  // empty: slBoxCut lists nothing
  // One loop over the tile's pixels, row by row, do…while (README "Loop bodies III"); the column
  // and row are counters (a vector integer division is one scalar division per lane on llvmpipe).
  uint w = max(last.x, first.x + 1u) - first.x, h = max(last.y, first.y + 1u) - first.y;
  uint x = 0u, y = 0u;
  do {
    uvec2 j = first + uvec2(x, y);
    ivec2 pixel = kStep > 1u ? reducedSamplePixel(ivec2(j), int(kStep), gmax + 1) : ivec2(j);
    float depth = texelFetch(gDepth, pixel, 0).r;
    if (depth < 1.0 && all(lessThan(j, last))) {
      vec3 p = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
      lo = min(lo, p);
      hi = max(hi, p);
    }
    ++x;
    y += x == w ? 1u : 0u;
    x = x == w ? 0u : x;
  } while (y < h);
  return slBoxCut(lo, hi, mask);
}
#endif
#ifdef SL_TILE_RATIOS
// §7.3 hierarchy (hierarchy_tiles.vert): the tile's Eq. 25 t per object, 4 vec4 per tile record
// (shaders/sl/hierarchy_ratio.comp wrote them), to sl_hierarchy.frag as flat varyings.
layout(std430, set = 1, binding = SL_TILE_RATIOS) readonly buffer SlRatios { vec4 slRatios[]; };
layout(location = 1) flat out vec4 outRatios[4];
#endif

void main() {
  uvec4 tile = slTiles[2 * gl_InstanceIndex];
  // Vertices 0..5: (0,0) (1,0) (0,1), (1,0) (1,1) (0,1). Corners past the target's edge are clipped.
  const uvec2 corners[6] = uvec2[6](uvec2(0, 0), uvec2(1, 0), uvec2(0, 1), uvec2(1, 0), uvec2(1, 1), uvec2(0, 1));
  vec2 pixel = vec2((tile.xy + corners[gl_VertexIndex]) * pc.tileSize);
  gl_Position = vec4(pixel * pc.invExtent * 2.0 - 1.0, 0.0, 1.0);
#ifdef SL_TILE_CUT
  outCandidates = slCutTile(tile.xy, slTiles[2 * gl_InstanceIndex + 1]);
#else
  outCandidates = slTiles[2 * gl_InstanceIndex + 1];
#endif
#ifdef SL_TILE_RATIOS
  for (int o = 0; o < 4; ++o) outRatios[o] = slRatios[4 * gl_InstanceIndex + o];
#endif
}
