#version 450
#extension GL_GOOGLE_include_directive : require
// DNRT, clustered mode (issue 15; engine/gi/dnrt/cluster.hpp): one full-screen triangle for a
// batch of up to 32 objects. Each pixel reads the G-buffer once, then visits only the objects in its
// 16×16 tile's mask and adds Σ_objects L_DNRT (Eq. 16, term for term dnrt.frag's) in one blend.
//
// Why two loops: llvmpipe runs both sides of a branch under a mask but leaves a loop as soon as no
// lane of the 8 is still in it. The first loop is cheap (the affine map, s(r), (n_o·n_r)₊ and the
// own-pixel test) and keeps only the objects that reach r; the second, with the one tap of the
// combined atlas, then runs as often as the most-reached pixel of the 8 needs, not once per object
// whose screen rectangle merely covers the tile.
// Why do-while: llvmpipe tests "is any lane still in the loop" only at the end of an iteration; a
// `break` just masks lanes off. A `for (m = mask; m != 0u; …)` loop tests m at the top, so after
// its last real object it runs the whole body once more with every lane masked (n + 1 bodies for
// n objects: twice the work for one). With the test at the bottom it runs n (one object,
// cornell-1 at 1280×720: dnrt / SSAO 0.41–0.43 → 0.29–0.32; ten objects 0.96–1.0 → 0.79). Every
// iteration's result is still guarded by m != 0: a lane can pass through the body with m == 0
// (a pixel whose mask or live set is 0, discarded above, and — measured, two-boxes.json — some
// lanes of a group after their own last object), so max(findLSB(m), 0) keeps the record index in
// range and the guard keeps such a pass from adding object 0 (or, with findLSB's −1, bit 31).
// Per-object records are a uniform array indexed per pixel (no flat varyings here: one draw serves
// every object); Σ_j c_j M_j comes from one combined RGBA16F atlas, a brick per object written this
// frame by combine.comp (no descriptor indexing on lavapipe; one trilinear tap for 4 or 9 SH).
#include "frame.glsl"
#include "dnrt/dnrt.glsl"
#include "gbuffer.glsl"
#include "upsample.glsl"

// A batch of exactly one object (node.cpp): record 0, no loops. The loops' per-pixel index makes
// every record field a per-lane load, and a loop body costs about twice the same code straight
// (README "DNRT": "one object in straight-line code, no loop"); with the index a constant the
// record is read as uniforms, as the box draw's flat varyings are. Same sums, same image.
layout(constant_id = 0) const bool kSingle = false;
// kSelfInNormal: every object of the batch has an entity id + 1 ≤ kEntityInNormalMax, so the self
// test reads the normal's w (gbuffer.glsl: exact there, and no larger id rounds onto it) instead of
// fetching gbuffer.entity (dnrt.frag does the same; node.cpp clusteredPipeline()).
layout(constant_id = 1) const bool kSelfInNormal = false;
// kStep: 1 (full), 2 (half), 4 (quarter) G-buffer pixels per shaded sample along each axis, as
// dnrt.frag's: below full, sample j of the reduced target shades G-buffer pixel kStep·j (its tile's
// mask is that pixel's) and writes the sum without ρ_r for dnrt/upsample.frag.
layout(constant_id = 2) const uint kStep = 1u;

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(std430, set = 1, binding = 3) readonly buffer Tiles { uint tileMasks[]; };
layout(set = 1, binding = 4) uniform usampler2D gEntity;
layout(std140, set = 2, binding = 0) uniform Objects { DnrtClusterObject objects[kDnrtClusterBatch]; };
// rgb: Σ_j c_j M_j per channel; object i's padded brick starts at objects[i].atlas (combine.comp).
layout(set = 2, binding = 1) uniform sampler3D combined;
layout(push_constant) uniform Push {
  vec4 invAtlasSize;  // xyz: 1 / the combined atlas's texels per axis
  uint tileBase;      // this batch's first mask in Tiles
  uint tilesX;
} pc;

layout(location = 0) out vec4 outRadiance;

// Object i reaches the receiver r (world position, w = 1) with normal nr: dnrt.frag's discards
// (s(r) > 0, r not at the centre, (n_o·n_r)₊ > 0, not the object's own pixel). kSingle's test.
bool dnrtClusterReaches(int i, vec4 r, vec3 nr, uint entity) {
  vec3 q = dnrtQ(objects[i].worldToQ, r);
  float s = dnrtFalloff(q, objects[i].extents.x, objects[i].extents.y);
  vec3 toO = objects[i].centreWorld.xyz - r.xyz;
  float len = length(toO);
  uint self = objects[i].ids.x;
  return dnrtReaches(s, len, objects[i].centreWorld.w, dnrtLambert(toO, len, nr)) && !(self != 0u && entity == self);
}

// The loops' first test: a superset of dnrtClusterReaches without its divisions, square root and
// two of its loads (inner, R), since in the loop each record field is a per-lane load (session 9,
// README "DNRT and probes cost, session 9"). s(r) > 0 needs u = max|q| < outer (dnrtFalloff is 0
// from there on). (n_o·n_r)₊ > 0 needs dot(toO/len, nr) > 0; dot(toO, nr) differs from len times
// that by a few float roundings of Σ|toO_c||n_c| ≤ Σ|toO_c| (|n| = 1), far under the 10⁻⁵·Σ|toO_c|
// allowed here, so no object the exact test keeps is dropped. The exact conditions are then the
// guard of the second loop's sum (dnrtClusterTerm, the same arithmetic as dnrtClusterReaches), so
// the objects summed, their order and the image are those of the exact test.
bool dnrtClusterMayReach(int i, vec4 r, vec3 nr, uint entity) {
  vec3 q = dnrtQ(objects[i].worldToQ, r);
  vec3 a = abs(q);
  vec3 toO = objects[i].centreWorld.xyz - r.xyz;
  uint self = objects[i].ids.x;
  return max(a.x, max(a.y, a.z)) < objects[i].extents.y &&
         dot(toO, nr) > -1e-5 * (abs(toO.x) + abs(toO.y) + abs(toO.z)) && !(self != 0u && entity == self);
}

// Object i's term without ρ_r: (n_o·n_r)₊ s(r) Σ_j c_j M_j(r) (Eq. 16), the sum one trilinear tap;
// `exact` is dnrtClusterReaches' s(r), centre and (n_o·n_r)₊ conditions on the same values (the
// loops' own-pixel test is already exact).
vec3 dnrtClusterTerm(int i, vec4 r, vec3 nr, out bool exact) {
  vec3 q = dnrtQ(objects[i].worldToQ, r);
  vec4 ext = objects[i].extents;
  float s = dnrtFalloff(q, ext.x, ext.y);
  vec4 centre = objects[i].centreWorld;
  vec3 toO = centre.xyz - r.xyz;
  float len = length(toO);
  float lamb = dnrtLambert(toO, len, nr);
  exact = dnrtReaches(s, len, centre.w, lamb);
  vec3 uvw = (dnrtGrid(q, ext.x, ext.w) + objects[i].atlas.xyz) * pc.invAtlasSize.xyz;
  return (lamb * s) * texture(combined, uvw).rgb;
}

void main() {
  ivec2 pixel = kStep == 1u ? ivec2(gl_FragCoord.xy)
                            : reducedSamplePixel(ivec2(gl_FragCoord.xy), int(kStep), ivec2(camera.resolution.xy));
  uint mask = tileMasks[pc.tileBase + uint(pixel.y >> kDnrtClusterTileShift) * pc.tilesX +
                        uint(pixel.x >> kDnrtClusterTileShift)];
  if (mask == 0u) discard;
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) discard;
  vec4 r = vec4(worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth), 1.0);
  vec4 normal = texelFetch(gNormal, pixel, 0);
  vec3 nr = normal.xyz;
  uint entity = kSelfInNormal ? uint(normal.w) : texelFetch(gEntity, pixel, 0).r;

  if (kSingle) {  // a specialization constant: the loops below are compiled out, and vice versa
    if (!dnrtClusterReaches(0, r, nr, entity)) discard;
    vec3 albedo = kStep == 1u ? texelFetch(gAlbedo, pixel, 0).rgb : vec3(1.0);  // reduced: ρ_r at the upsample
    bool exact;
    outRadiance = vec4(albedo * dnrtClusterTerm(0, r, nr, exact), 0.0);
    return;
  }

  // 1. The tile's objects that may reach r (dnrtClusterMayReach), as a bit each.
  uint live = 0u;
  uint m = mask;
  do {
    int i = max(findLSB(m), 0);
    if (dnrtClusterMayReach(i, r, nr, entity) && m != 0u) live |= 1u << uint(i);
    m &= m - 1u;
  } while (m != 0u);
  if (live == 0u) discard;

  // 2. The terms of those that do reach r (dnrt.frag's discards, exact), summed, times ρ_r once. A
  // pixel whose may-reach objects all fail here adds 0 where the exact first test discarded it:
  // the same value in the additive blend.
  vec3 total = vec3(0.0);
  m = live;
  do {
    int i = max(findLSB(m), 0);
    bool exact;
    vec3 term = dnrtClusterTerm(i, r, nr, exact);
    if (m != 0u && exact) total += term;
    m &= m - 1u;
  } while (m != 0u);
  vec3 albedo = kStep == 1u ? texelFetch(gAlbedo, pixel, 0).rgb : vec3(1.0);  // reduced: ρ_r at the upsample
  outRadiance = vec4(albedo * total, 0.0);
}
