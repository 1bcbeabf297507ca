#version 450
#extension GL_GOOGLE_include_directive : require
// RTF shading step (Pan et al. 2007 §5, Eq. 10) for one object at a diffuse receiver pixel r with
// normal n and albedo ρ, what engine/gi/rtf/evaluate.cpp shade() computes for one object:
//   ρ/π · E_n(ξ(q))  −  ρ/π · E_n((u − V(q)) ⊙ L)
// ξ(q) the trilinear lookup of the object's ξ image (its interreflected light arriving at q), V(q)
// its OOF, u the SH of V ≡ 1, L the indirect light at o (the record's product matrix), all in the
// object's frame (the normal is rotated there instead of 16 coefficients into the world), and
// E_n(L) = Σ Â_l L_lm Y_lm(n) with Â_3 = 0, so only bands 0..2 matter. Both terms are folded per
// sample by the ξ pass into X_i (i < 9, xi.comp), looked up by hardware filtering
// (rtf.glsl rtfTaps, a linear sampler; one trilinear fetch each): ρ Σ_i y_i(n) X_i(q). Added to
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
// X_i = Â_l/π ξ_i − Σ_j T'_ij (u − V)_j per sample, i < 9 (xi.comp): 3D, slice i·spheres + sphere.
layout(set = 2, binding = 1) uniform sampler3D netTex;

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

  // Both terms are linear in what Eq. 10 interpolates, so the ξ pass folded them per sample
  // (xi.comp's X): the lookup of X with Eq. 10's weights, evaluated at n.
  // One trilinear fetch per coefficient: bilinear within the face (rtfTaps' clamped coordinates),
  // linear between the spheres by the slice coordinate t = (|q| − inner)/Δr clamped to the first and
  // last sphere's slice centres (inside the innermost sphere: its value), times the fade beyond the
  // outermost — Eq. 10's weights exactly (rtfTaps gives them separately; the C++ is lookup()).
  vec2 uv;
  int s0, s1;
  float w0, w1;
  rtfTaps(g, q, uv, s0, s1, w0, w1);
  float fade = w0 + w1;
  if (fade <= 0.0) discard;
  float t = clamp((length(q) - g.innerRadius) / dr, 0.0, float(g.spheres - 1));
  float slices = float(9 * g.spheres);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < 9; ++i) sum += y[i] * texture(netTex, vec3(uv, (float(i * g.spheres) + t + 0.5) / slices)).rgb;
  sum *= fade;
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  outRadiance = vec4(albedo * sum, 0.0);
}
