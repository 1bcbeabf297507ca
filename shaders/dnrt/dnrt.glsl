// DNRT evaluation (paper Eq. 16 / Listing 2), term for term the CPU mirror in
// engine/gi/dnrt/evaluate.cpp:
//   L_DNRT(r) = ρ_r (n_o·n_r)₊ · s(r) · Σ_j c_j M_j(r)      per RGB channel
// (Eq. 16's "+" after (n_o·n_r) is the clamp subscript of a product, as Eq. 9 and Listing 2 show).
// M_j: trilinear 3D-texture fetch at r's offset from o in units of R, clamped to the inner cube
// (CLAMP_TO_EDGE does it, as Listing 2 notes), decoded lo + (hi − lo)·unorm per slot (Table 2).
// s(r): §5.2.2 fall-off over the outer shell, 1 at the inner cube and 0 at the outer one.
#ifndef BOUNCE_DNRT_GLSL
#define BOUNCE_DNRT_GLSL

// engine/gi/dnrt/node.hpp: DnrtObjectGpu (std430).
struct DnrtObject {
  mat4 worldToLocal;  // world → object local frame (the baked mesh's metres)
  mat4 boxToWorld;    // unit cube [-1, 1]³ → the world-space outer cube (box raster mode)
  vec4 centreWorld;   // xyz o in world space, w R in world space
  vec4 centreLocal;   // xyz o in the local frame, w R in the local frame
  vec4 extents;       // x inner, y outer (units of R), z SH count (4 or 9), w grid N
  vec4 c[9];          // rgb: irradiance SH c_j at o, rotated into the local frame
  vec4 lo[7];         // per texture, per component: decoded value of byte 0
  vec4 hi[7];         // … of byte 255
  uvec4 ids;          // x: entity index + 1 of the object (gbuffer.entity's encoding), 0 = none;
                      // y: 1 when the intrusion map applies (§5.2.3)
};

float dnrtFalloff(vec3 q, float inner, float outer) {
  vec3 a = abs(q);
  float u = max(a.x, max(a.y, a.z));
  if (u <= inner) return 1.0;
  if (u >= outer) return 0.0;
  float floorTerm = (inner / outer) * (inner / outer);
  float inv = (inner / u) * (inner / u);
  return (inv - floorTerm) / (1.0 - floorTerm);
}

// Texture coordinate of a local offset q (units of R): texel centres on grid vertices.
vec3 dnrtUvw(vec3 q, float inner, float n) {
  vec3 g = (clamp(q / inner, -1.0, 1.0) + 1.0) * 0.5 * (n - 1.0);
  return (g + 0.5) / n;
}

#endif
