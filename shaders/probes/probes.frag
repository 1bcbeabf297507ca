#version 450
#extension GL_GOOGLE_include_directive : require
// Static indirect diffuse from the baked irradiance volume (effect `probes`), added to
// "lighting.hdr" with additive blending:
//   L_o += ρ(x)/π · E_ind(x, n),   E_ind = Σ_k w_k Σ_lm Â_l L^k_lm Y_lm(n)
// with w_k from probes/probe_weights.glsl (trilinear × backface × Chebyshev visibility), the same
// code the CPU API (engine/gi/probes/probe_volume.cpp) runs.
// The volume is read from images with texelFetch, not storage buffers: llvmpipe reads every SSBO
// scalar per lane with a bounds check, and the 8 probes' SH were ~80 % of the pass (README "What
// costs what on lavapipe"). The SH order is a specialization constant so the loops unroll.
#include "frame.glsl"
#include "sh.glsl"
#include "dnrt/dnrt.glsl"

layout(constant_id = 0) const int kCoeffs = 9;  // order²: 4 or 9
// The SH from the uniform block below instead of the image when the volume fits it (node.cpp
// kShUboBytes): L_0 as halves, L_1, L_2 as 8-bit fractions of it, fetched cheaper (probe_sh.glsl, README "What costs what
// on lavapipe").
layout(constant_id = 1) const bool kShInUbo = false;
// The visibility moments from the second uniform block below when they fit it (node.cpp
// kMomentsUboBytes): (mean, σ) halves, one word a bin (probe_sh.glsl probeMomentsAt).
layout(constant_id = 2) const bool kMomentsInUbo = false;
// E(n) from the probes' irradiance tiles (pass `probes.tiles`, probes/probe_tiles.glsl): one
// bilinear tap a probe instead of its SH words; set with kShInUbo when the tile image fits.
layout(constant_id = 3) const bool kTiles = false;
// DNRT's fused mode ("dnrt": {"mode": "fused"}, engine/gi/probes/node.hpp FusedDnrt): this pass also
// adds the dynamic objects' L_DNRT (Eq. 16) at the pixel it already reads — no second raster,
// G-buffer fetch or blend. 0: none. 1: one object (dnrt.glsl dnrtFusedTerm, its record in the push
// block, no loop; the same sum as the "dnrt" pass's box draw up to one fp16 blend rounding: the two
// terms are summed in fp32, blended once). 2: several (up to kDnrtClusterBatch): the clustered
// mode's visit of the pixel's 16×16 tile mask (dnrt/cluster.glsl, its records in the Objects block,
// Σ_j c_j M_j in the combined atlas), the clustered draw's sum added here instead of in a pass of its
// own. A specialization constant, not a branch: llvmpipe runs both sides of a branch (DESIGN.md).
layout(constant_id = 4) const int kDnrt = 0;
// With kDnrt 1, the level's "dnrt": {"resolution"} (engine/gi/resolution.hpp step): 1 evaluates the
// term exactly here; 2 or 4 takes its position-only factor from pass dnrt.fused.reduced's target
// (binding 12) by a bilinear blend of its 4 nearest samples from one texelFetch a pixel (dnrt.glsl
// dnrtFusedReducedTerm, dnrtReducedQuadTap below; README "DNRT's fused term at reduced resolution",
// sessions 17 and 18). kDnrt 2 runs at full resolution.
layout(constant_id = 5) const int kDnrtStep = 1;

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
// The probe images' layout: probes/probe_sh.glsl.
layout(set = 1, binding = 3) uniform sampler2D probeSh;       // RGBA32F
layout(set = 1, binding = 4) uniform sampler2D probeMoments;  // RG32F
layout(std140, set = 1, binding = 5) uniform ProbeShBlock { uvec4 probeShUbo[4096]; };  // packed SH, word j of p: [kPackedTexels·p + j / 4][j % 4]
layout(set = 1, binding = 6) uniform sampler2D aoTerm;  // "ao.term" (1 = unoccluded) when bias.w = 1
layout(std140, set = 1, binding = 7) uniform ProbeMomentsBlock { uvec4 probeMomentsUbo[4096]; };  // word 64·p + bin
layout(set = 1, binding = 8) uniform sampler2D probeTiles;  // RGBA16F, bilinear (kTiles)
// kDnrt 1: the object's Σ_j c_j M_j volume this frame (pass dnrt.combine.fused, RGBA16F, trilinear);
// kDnrt 2: the combined atlas, a padded brick per object (the same pass); a 1³ dummy otherwise.
layout(set = 1, binding = 9) uniform sampler3D dnrtCombined;
// kDnrt 2: this frame's tile masks (bit i: record i may reach a pixel of the tile; the CPU's screen
// hulls cut by the tiles' depth ranges, tile_cull.comp) and the objects' records (std140, the
// clustered draw's). Dummies otherwise.
layout(std430, set = 1, binding = 10) readonly buffer DnrtTiles { uint dnrtTileMasks[]; };
layout(std140, set = 1, binding = 11) uniform DnrtObjects { DnrtClusterObject objects[kDnrtClusterBatch]; };
// kDnrt 1, kDnrtStep > 1: (w·s Σ_j c_j M_j, w) at G-buffer pixel step·j (RGBA16F, texelFetch); unread otherwise.
layout(set = 1, binding = 12) uniform sampler2D dnrtReduced;

layout(push_constant) uniform Push {
  vec4 originSpacing;  // xyz: probe (0,0,0) position, w: spacing (m)
  ivec4 countOrder;    // xyz: probes per axis, w: SH order (2 or 3)
  vec4 bias;           // x: normal bias (m), y: view bias (m), z: Chebyshev variance floor (m²), w: 1 = multiply by aoTerm
  // kDnrt 1: the object's record (dnrt.glsl dnrtFusedTerm; node.hpp FusedDnrtPush): 128 bytes in all.
  // kDnrt 2: dnrtCentreWorld xyz 1 / the atlas's texels per axis, w the tiles per row (an integer).
  vec4 dnrtWorldToQ[3];
  vec4 dnrtCentreWorld;  // xyz o (m), w R (m)
  vec4 dnrtExtents;      // x inner, y outer (units of R), z entity id + 1 (0 = none), w grid N
} pc;

#define PROBE_SH_UBO  // probe_sh.glsl: read kShInUbo's probeShUbo
#define PROBE_TILES   // … and kTiles' probeTiles
#include "probes/probe_sh.glsl"
#include "dnrt/cluster.glsl"  // after `objects`, which it reads

// No varying: the pixel is gl_FragCoord, under the full-screen triangle and the outer cube's faces alike
// (FusedDnrt::split, probes/outer_cube.vert).
layout(location = 0) out vec4 outRadiance;

const float kInvPi = 0.31830988618379067;

// The bilinear tap of the reduced target `reduced` (sample j at texel j, standing for G-buffer pixel
// step·j; `step` 2 or 4) at G-buffer pixel `pixel`, from ONE texelFetch a pixel instead of a filtered
// tap (4 texels a pixel, each a per-lane gather on llvmpipe; session 18: the tap was most of the term's
// per-pixel cost). With an even step the 4 pixels of a 2×2 quad (pixel & 1 its place, quads aligned to
// even pixels) share their 4 nearest samples j0 + {0, 1}² (j0 = pixel / step), so each pixel fetches the
// one at its own place in the quad and takes the others' through fine derivatives. Separably, as a
// bilinear filter is: first along x in the pixel's sample row, row = v + u·dFdxFine(v) (the quad's two
// pixels of a row hold that row's two samples), then along y between the quad's two rows, row + t·dFdyFine(row)
// (the two pixels of a column share u, so the other row's value at the same u is one derivative away), with
// (u, t) the pixel's bilinear fractions (pixel − step·j0) / step relative to its own sample (−1 … 0.75).
// Two derivatives of a vec4 where the expansion v + u dx + t dy + u t dxy took three (dxy = dFdyFine(dx)):
// on llvmpipe each costs about a third of the fetch, and the third was ≈ 0.006 of SSAO (README "DNRT's
// fused quarter term: two derivatives, session 20"; doing the x half in dnrt.fused.reduced instead, one
// derivative here, cost as much in that pass's stores as it saved here). Equal to the filtered tap up to
// fp32 rounding. Samples past the target's edge clamp to it (CLAMP_TO_EDGE). Must run in uniform control
// flow (the derivatives): main calls it before its first return. Here, not in dnrt.glsl: derivatives exist
// in fragment shaders only, and compute shaders include dnrt.glsl.
vec4 dnrtReducedQuadTap(ivec2 pixel, sampler2D reduced, int step) {
  const ivec2 place = pixel & 1;
  const ivec2 j0 = pixel / step;
  const vec4 v = texelFetch(reduced, min(j0 + place, textureSize(reduced, 0) - 1), 0);
  const vec2 ut = vec2(pixel - step * j0) / float(step) - vec2(place);
  const vec4 row = v + ut.x * dFdxFine(v);
  return row + ut.y * dFdyFine(row);
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  // kDnrtStep > 1: the term's reduced factor, here in uniform control flow (dnrtReducedQuadTap takes its
  // quad neighbours' samples through derivatives).
  vec4 dnrtTap = vec4(0.0);
  if (kDnrt == 1 && kDnrtStep > 1) dnrtTap = dnrtReducedQuadTap(pixel, dnrtReduced, kDnrtStep);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) {
    outRadiance = vec4(0.0);
    return;
  }
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  vec4 normal = texelFetch(gNormal, pixel, 0);
  vec3 n = normal.xyz;
  vec3 x = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
  vec3 L[9];
  probeRadianceSh(x, n, normalize(camera.position.xyz - x), L);
  float ao = pc.bias.w > 0.5 ? texelFetch(aoTerm, pixel, 0).r : 1.0;
  vec3 e = kTiles ? L[0] : shIrradiance9(L, n);  // probeRadianceSh: with kTiles, L[0] is E(n)
  vec3 radiance = albedo * kInvPi * ao * max(e, vec3(0.0));
  if (kDnrt == 1 && kDnrtStep > 1)
    radiance += albedo * dnrtFusedReducedTerm(x, normal, dnrtTap, pc.dnrtCentreWorld, pc.dnrtExtents);
  else if (kDnrt == 1)
    radiance += albedo * dnrtFusedTerm(x, normal, pc.dnrtWorldToQ, pc.dnrtCentreWorld, pc.dnrtExtents, dnrtCombined);
  if (kDnrt == 2) {
    // The self test reads the normal's w: every fused object's entity id + 1 fits it (gi/dnrt/runtime.cpp).
    uint mask = dnrtTileMasks[uint(pixel.y >> kDnrtClusterTileShift) * uint(pc.dnrtCentreWorld.w) +
                              uint(pixel.x >> kDnrtClusterTileShift)];
    vec4 r = vec4(x, 1.0);
    uint live = dnrtClusterLive(mask, r, n, uint(normal.w));
    radiance += albedo * dnrtClusterSum(live, r, n, dnrtCombined, pc.dnrtCentreWorld.xyz);
  }
  outRadiance = vec4(radiance, 0.0);
}
