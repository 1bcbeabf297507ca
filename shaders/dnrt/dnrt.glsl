// DNRT evaluation (paper Eq. 16 / Listing 2), term for term the CPU mirror in
// engine/gi/dnrt/evaluate.cpp:
//   L_DNRT(r) = ρ_r (n_o·n_r)₊ · s(r) · Σ_j c_j M_j(r)      per RGB channel
// (Eq. 16's "+" after (n_o·n_r) is the clamp subscript of a product, as Eq. 9 and Listing 2 show).
// M_j: trilinear 3D-texture fetch at r's offset from o in units of R, clamped to the inner cube
// (CLAMP_TO_EDGE does it, as Listing 2 notes), decoded lo + (hi − lo)·unorm per slot (Table 2);
// the decode and the c_j product are folded into Σ_j c_j M_j = a + Σ_slot dot(k_slot, unorm_slot),
// which combine.comp evaluates per grid vertex each frame, so the draws filter the sum in one tap.
// s(r): §5.2.2 fall-off over the outer shell, 1 at the inner cube and 0 at the outer one.
#ifndef BOUNCE_DNRT_GLSL
#define BOUNCE_DNRT_GLSL

// engine/gi/dnrt/gpu_object.hpp: DnrtShaderObject (std430), folded from the per-object record on
// the CPU (fold()) so a pixel does the least arithmetic. Read once per vertex in dnrt.vert and handed
// to the fragment shader as flat varyings (k and a: once per grid vertex in combine.comp): llvmpipe reads every SSBO scalar per lane with a bounds
// check, so a per-pixel copy of the record cost ~60 % of the pass (README "What costs what").
struct DnrtObject {
  mat4 boxToWorld;    // unit cube [-1, 1]³ → the world-space outer cube (box raster mode)
  vec4 worldToQ[3];   // rows of the affine map r ↦ q = (worldToLocal·r − o_local) / R_local
  vec4 centreWorld;   // xyz o in world space, w R in world space
  vec4 extents;       // x inner, y outer (units of R), z SH count (4 or 9), w grid N
  vec4 k[7];          // per texture slot and component: (hi − lo)·c_j of that slot's channel (Table 2)
  vec4 a;             // rgb: Σ lo·c_j per channel, so Σ_j c_j M_j = a + Σ_slots dot(k, texel)
  uvec4 ids;          // x: entity index + 1 of the object (gbuffer.entity's encoding), 0 = none
};

// The clustered draw's per-object record (engine/gi/dnrt/gpu_object.hpp: DnrtClusterObject, std140):
// DnrtObject without the box matrix, plus the texel coordinate of grid vertex (0, 0, 0) in the combined
// atlas (combine.comp; k and a are applied there, clustered.frag reads neither).
struct DnrtClusterObject {
  vec4 worldToQ[3];
  vec4 centreWorld;
  vec4 extents;
  vec4 k[7];
  vec4 a;
  vec4 atlas;
  uvec4 ids;
};
const uint kDnrtClusterBatch = 32u;  // engine/gi/dnrt/cluster.hpp kClusterBatch

// Corner of the unit cube [-1, 1]³ at vertex `vertex` (0..35) of its 12 triangles (6 faces × 2, outward
// counter-clockwise), for 36-vertex draws from gl_VertexIndex: the box draw (dnrt.vert) and the probes pass
// split at the outer cube (probes/outer_cube.vert). A corner's bits are its x, y, z signs.
const int kDnrtCubeFaces[6][4] = int[6][4](int[4](1, 3, 7, 5), int[4](0, 4, 6, 2), int[4](2, 6, 7, 3),
                                           int[4](0, 1, 5, 4), int[4](4, 5, 7, 6), int[4](0, 2, 3, 1));
const int kDnrtCubeQuad[6] = int[6](0, 1, 2, 0, 2, 3);
vec3 dnrtCubeCorner(int vertex) {
  const int corner = kDnrtCubeFaces[vertex / 6][kDnrtCubeQuad[vertex % 6]];
  return vec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1) * 2.0 - 1.0;
}
const int kDnrtClusterTileShift = 4;  // 16-pixel tiles (kClusterTile)

float dnrtFalloff(vec3 q, float inner, float outer) {
  vec3 a = abs(q);
  float u = max(a.x, max(a.y, a.z));
  if (u <= inner) return 1.0;
  if (u >= outer) return 0.0;
  float floorTerm = (inner / outer) * (inner / outer);
  float inv = (inner / u) * (inner / u);
  return (inv - floorTerm) / (1.0 - floorTerm);
}

// Grid coordinate (0..N − 1 per axis, vertices at integers) of a local offset q (units of R),
// clamped to the inner cube.
vec3 dnrtGrid(vec3 q, float inner, float n) { return (clamp(q / inner, -1.0, 1.0) + 1.0) * 0.5 * (n - 1.0); }

// Texture coordinate of a local offset q (units of R): texel centres on grid vertices.
vec3 dnrtUvw(vec3 q, float inner, float n) { return (dnrtGrid(q, inner, n) + 0.5) / n; }

// The receiver r (world, w = 1) in the object's frame q (units of R): the rows of DnrtObject's worldToQ.
vec3 dnrtQ(vec4 worldToQ[3], vec4 r) { return vec3(dot(worldToQ[0], r), dot(worldToQ[1], r), dot(worldToQ[2], r)); }
// (n_o·n_r)₊ of Eq. 16 with n_o = toO / len, the direction from r to the object's centre o.
float dnrtLambert(vec3 toO, float len, vec3 nr) { return max(dot(toO / len, nr), 0.0); }
// Eq. 16's receiver conditions: s(r) > 0, r not at o (n_o undefined there; R the object's radius, m)
// and (n_o·n_r)₊ > 0. False for NaN, as every caller's discards and masks need.
bool dnrtReaches(float s, float len, float radius, float lamb) { return s > 0.0 && len > 1e-6 * radius && lamb > 0.0; }

// Eq. 16 without ρ_r for one object at receiver r (world, m) with G-buffer normal `normal` (xyz unit,
// w the entity id + 1, gbuffer.glsl): (n_o·n_r)₊ s(r) Σ_j c_j M_j(r), and 0 wherever dnrt.frag
// discards (s ≤ 0, r at o, Lambert ≤ 0, the object's own pixel; no intrusion). The fused mode's form
// (probes.frag kDnrt, "dnrt": {"mode": "fused"}), which runs at every pixel of the probes pass, so
// the tests are a mask, not discards; dnrt.frag keeps its early discards (they are its cost).
// `worldToQ`, `centreWorld`: DnrtObject's; `extents`: x inner, y outer (units of R), z the entity id
// + 1 (0 = none, ≤ kEntityInNormalMax), w grid N; `combined`: this frame's Σ_j c_j M_j volume.
vec3 dnrtFusedTerm(vec3 r, vec4 normal, vec4 worldToQ[3], vec4 centreWorld, vec4 extents, sampler3D combined) {
  vec3 q = dnrtQ(worldToQ, vec4(r, 1.0));
  float s = dnrtFalloff(q, extents.x, extents.y);
  vec3 toO = centreWorld.xyz - r;
  float len = length(toO);
  float lamb = dnrtLambert(toO, len, normal.xyz);
  bool self = extents.z != 0.0 && normal.w == extents.z;
  if (!dnrtReaches(s, len, centreWorld.w, lamb) || self) return vec3(0.0);
  // One mip level: textureLod filters as dnrt.frag's texture() does, without implicit derivatives
  // in this (non-uniform) branch.
  return (lamb * s) * textureLod(combined, dnrtUvw(q, extents.x, extents.w), 0.0).rgb;
}

// The fused term below full resolution (probes.frag kDnrtStep = step 2 or 4; README "DNRT's fused term
// at reduced resolution", sessions 17 and 18): Eq. 16 without ρ_r as dnrtFusedTerm, with its position-only
// factor f(r) = s(r) Σ_j c_j M_j(r) from pass dnrt.fused.reduced (fused_reduced.comp: (w·f, w) at G-buffer
// pixel step·j, w = 0 on sky and the object's own samples) as `tap` = dnrtReducedQuadTap's bilinear blend
// of its 4 nearest samples, normalised by its filtered w — a blend over the valid samples only, no branch
// (llvmpipe would run both sides of one) — times the exact per-pixel (n_o·n_r)₊ and tests (the normal is
// where the term is not smooth). f is smooth in world space, so the error is where the 4 samples lie on
// another surface than the pixel (depth edges inside the object's outer cube). 0 where every sample is
// invalid (tap.a = 0: tap.rgb is 0 too, premultiplied).
// One division a pixel: (n_o·n_r)₊ / w = max(toO·n_r, 0) / (|toO| w), toO = o − r (dnrtLambert's three and
// the normalisation's one were most of the term's arithmetic on llvmpipe, which divides exactly; session
// 18). dnrtReaches' tests hold without their branches: w = 0 gives tap.rgb = 0 (premultiplied), and
// (n_o·n_r)₊ = 0 gives 0; r at o (|toO| ≤ 10⁻⁶ R, n_o undefined) and the object's own pixel stay tests.
vec3 dnrtFusedReducedTerm(vec3 r, vec4 normal, vec4 tap, vec4 centreWorld, vec4 extents) {
  const vec3 toO = centreWorld.xyz - r;
  const float len = length(toO);
  const bool self = extents.z != 0.0 && normal.w == extents.z;
  const bool reaches = len > 1e-6 * centreWorld.w && !self;
  return reaches ? (max(dot(toO, normal.xyz), 0.0) / (len * max(tap.a, 1e-6))) * tap.rgb : vec3(0.0);
}

#endif
