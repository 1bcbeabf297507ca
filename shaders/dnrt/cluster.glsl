// DNRT's per-pixel visit of a tile's objects (issue 15), shared by the clustered draw
// (dnrt/clustered.frag) and the fused mode with several objects (probes/probes.frag kDnrt 2): the
// objects of the pixel's 16×16 tile mask, each term Eq. 16 without ρ_r, term for term dnrt.frag's.
// The includer declares, before including this file, the uniform array
//   DnrtClusterObject objects[kDnrtClusterBatch]   (dnrt.glsl; engine/gi/dnrt/gpu_object.hpp, std140)
// and passes the combined atlas (combine.comp: Σ_j c_j M_j, a padded brick per object starting at
// objects[i].atlas) with 1 / its texels per axis.
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
// (a pixel whose mask or live set is 0, and — measured, two-boxes.json — some lanes of a group
// after their own last object), so max(findLSB(m), 0) keeps the record index in range and the guard
// keeps such a pass from adding object 0 (or, with findLSB's −1, bit 31).
#ifndef BOUNCE_DNRT_CLUSTER_GLSL
#define BOUNCE_DNRT_CLUSTER_GLSL

#include "dnrt/dnrt.glsl"

// Object i reaches the receiver r (world position, w = 1) with normal nr: dnrt.frag's discards
// (s(r) > 0, r not at the centre, (n_o·n_r)₊ > 0, not the object's own pixel). The one-object test.
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
vec3 dnrtClusterTerm(int i, vec4 r, vec3 nr, sampler3D atlas, vec3 invAtlasSize, out bool exact) {
  vec3 q = dnrtQ(objects[i].worldToQ, r);
  vec4 ext = objects[i].extents;
  float s = dnrtFalloff(q, ext.x, ext.y);
  vec4 centre = objects[i].centreWorld;
  vec3 toO = centre.xyz - r.xyz;
  float len = length(toO);
  float lamb = dnrtLambert(toO, len, nr);
  exact = dnrtReaches(s, len, centre.w, lamb);
  vec3 uvw = (dnrtGrid(q, ext.x, ext.w) + objects[i].atlas.xyz) * invAtlasSize;
  // One mip level: textureLod filters as texture() does, without implicit derivatives in the loop
  // (non-uniform control flow).
  return (lamb * s) * textureLod(atlas, uvw, 0.0).rgb;
}

// 1. The objects of `mask` that may reach r (dnrtClusterMayReach), as a bit each: `live`, 0 where
// none may (clustered.frag discards those pixels).
uint dnrtClusterLive(uint mask, vec4 r, vec3 nr, uint entity) {
  uint live = 0u;
  uint m = mask;
  do {
    int i = max(findLSB(m), 0);
    if (dnrtClusterMayReach(i, r, nr, entity) && m != 0u) live |= 1u << uint(i);
    m &= m - 1u;
  } while (m != 0u);
  return live;
}

// 2. Σ over the `live` objects that do reach r (dnrt.frag's discards, exact) of their terms, without
// ρ_r. A pixel whose may-reach objects all fail here adds 0 where the exact test would have
// discarded it: the same value in an additive blend.
vec3 dnrtClusterSum(uint live, vec4 r, vec3 nr, sampler3D atlas, vec3 invAtlasSize) {
  vec3 total = vec3(0.0);
  uint m = live;
  do {
    int i = max(findLSB(m), 0);
    bool exact;
    vec3 term = dnrtClusterTerm(i, r, nr, atlas, invAtlasSize, exact);
    if (m != 0u && exact) total += term;
    m &= m - 1u;
  } while (m != 0u);
  return total;
}

#endif
