#version 450
#extension GL_GOOGLE_include_directive : require
// RTF shading step (Pan et al. 2007 §5, Eq. 10) for one object at a diffuse receiver pixel r with
// normal n and albedo ρ, what engine/gi/rtf/evaluate.cpp shade() computes for one object:
//   ρ/π · E_n(ξ(q))  −  ρ/π · E_n((u − V(q)) ⊙ L)
// ξ(q) the trilinear lookup of the object's ξ image (its interreflected light arriving at q), V(q)
// its OOF, u the SH of V ≡ 1, L the indirect light at o (the record's product matrix), all in the
// object's frame (the normal is rotated there instead of 16 coefficients into the world), and
// E_n(L) = Σ Â_l L_lm Y_lm(n) with Â_3 = 0, so only 9 ξ coefficients are read (2 filtered taps
// each, rtf.glsl rtfTaps; linear samplers). Added to
// "lighting.hdr" with additive blending.
#include "frame.glsl"
#include "sh.glsl"
#include "rtf/object.glsl"
#include "rtf/rtf.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(set = 1, binding = 3) uniform usampler2D gEntity;
layout(set = 2, binding = 0) uniform ObjectUbo { RtfObject ob; };
layout(set = 2, binding = 1) uniform sampler2DArray xiTex;
layout(set = 2, binding = 2) uniform sampler2DArray oofTex;

layout(location = 0) out vec4 outRadiance;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) discard;
  // The object's own surface: its transfer already holds its self-interreflection (Eq. 8).
  if (texelFetch(gEntity, pixel, 0).r == ob.ids.x) discard;
  vec4 r = vec4(worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth), 1.0);
  vec3 q = vec3(dot(ob.toQ[0], r), dot(ob.toQ[1], r), dot(ob.toQ[2], r));
  RtfGrid g = RtfGrid(int(ob.grid.x), int(ob.grid.y), ob.grid.z, ob.grid.w);
  float dr = (g.outerRadius - g.innerRadius) / float(g.spheres - 1);
  if (length(q) >= g.outerRadius + dr) discard;  // beyond the fade: the field is zero
  vec3 nw = normalize(texelFetch(gNormal, pixel, 0).xyz);
  vec3 n = vec3(dot(ob.toLocal[0].xyz, nw), dot(ob.toLocal[1].xyz, nw), dot(ob.toLocal[2].xyz, nw));
  float y[9];
  shEval9(n, y);

  // Interreflected: ξ's bands 0..2 (Eq. 10), convolved and evaluated at n.
  vec3 L[16];
  rtfInterreflection(xiTex, g, q, 9, L);
  vec3 E = vec3(0.0);
  for (int i = 0; i < 9; ++i) E += ((i == 0 ? SH_A0 : (i < 4 ? SH_A1 : SH_A2)) * y[i]) * L[i];
  E *= 1.0 / 3.14159265358979324;
  // Blocked: (u − V)_j against the record's W_j = Σ_i Â_l/π y_i T_ij.
  float V[16];
  rtfOcclusion(oofTex, g, q, V);
  V[0] -= kRtfUnitVisibility;
  vec3 blocked = vec3(0.0);
  for (int j = 0; j < 16; ++j) {
    vec3 w = vec3(0.0);
    for (int i = 0; i < 9; ++i) w += y[i] * ob.blocked[j * 9 + i].rgb;
    blocked -= V[j] * w;
  }
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  outRadiance = vec4(albedo * (E - blocked), 0.0);
}
