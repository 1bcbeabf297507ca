#version 450
#extension GL_GOOGLE_include_directive : require
// RTF shading step (Pan et al. 2007 §5, Eq. 10) for one object at a diffuse receiver pixel r with
// normal n and albedo ρ, what engine/gi/rtf/evaluate.cpp shade() computes for one object:
//   ρ/π · E_n(ξ(q))  −  ρ/π · E_n((u − V(q)) ⊙ L)
// ξ(q) the trilinear lookup of the object's ξ image (its interreflected light arriving at q), V(q)
// its OOF, u the SH of V ≡ 1, L the indirect light (the record's product matrix: the light at o,
// scaled per sample by the ξ pass where objects share occlusion, overlap.hpp), all in the
// object's frame (the normal is rotated there instead of 16 coefficients into the world), and
// E_n(L) = Σ Â_l L_lm Y_lm(n) with Â_3 = 0, so only bands 0..2 matter. Both terms are folded per
// sample by the ξ pass into X_i (i < 9, xi.comp), stored in 8 bits (as r_s² X_i) as 7 RGBA texels (DNRT's
// Table 2 order) and looked up by hardware filtering (rtf.glsl rtfTaps, a linear sampler; one
// trilinear fetch per texel, 7 against 9 float fetches before): ρ Σ_i y_i(n) X_i(q). Added to
// "lighting.hdr" with additive blending — or, below full resolution, without ρ into a reduced target that
// "rtf.upsample" spreads over every pixel (kStep).
#include "frame.glsl"
#include "sh.glsl"
#include "upsample.glsl"  // reducedSamplePixel
#include "rtf/object.glsl"
#include "rtf/rtf.glsl"

// 9 SH (bands 0–2) or 4 (bands 0–1: texels 0..2 only), the object's "sh" (node.cpp: one pipeline each).
layout(constant_id = 0) const bool kSh9 = true;
// kSelfInNormal: the object's entity id + 1 is ≤ kEntityInNormalMax (gbuffer.glsl), so the self test
// compares it with the normal's w, fetched anyway, instead of fetching gbuffer.entity (as dnrt.frag).
layout(constant_id = 1) const bool kSelfInNormal = true;
// kStep: G-buffer pixels per shaded sample along each axis — 1 (full), 2 (half), 4 (quarter); the level's
// "rtf": {"resolution"} (node.cpp). Below full the octagon covers the reduced target "rtf.half" /
// "rtf.quarter" (⌈size/step⌉; rtf.vert maps it so that each sample is covered where its G-buffer pixel
// is), sample j shades G-buffer pixel step·j (reducedSamplePixel) and writes Σ_i y_i(n) X_i(q) without ρ; the pass
// "rtf.upsample" (gi/upsample_pass.hpp) blends it depth- and normal-aware at every pixel and multiplies
// by ρ there. The sum is the term's smooth part in q; its normal dependence is what the upsample's
// normal weights keep (README "RTF at half and quarter resolution, session 25").
layout(constant_id = 2) const uint kStep = 1u;

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(set = 1, binding = 3) uniform usampler2D gEntity;
// X_i = w Â_l/π ξ_i − Σ_j T'_ij (u − V)_j per sample, i < 9 (xi.comp): RGBA8 3D, slice (v·7 + k)·spheres + sphere
// for texel k < 7 of variant v — 0: w_off, for receivers off the rtf objects; 1: w_on, for receivers on one
// (overlap.hpp: Algorithm 1 leaves the receiver's own entity out of the nearer objects' occlusion); a slot's
// t decodes to Y = m(2t − 1) with m its range (inRange, from xi.comp, one for both variants), and
// X = Y/r_s² (r_s the sample's sphere radius in η).
layout(set = 2, binding = 1) uniform sampler3D netTex;

// The object's record, folded by rtf.vert.
layout(location = 0) flat in vec4 toQ[3];
layout(location = 3) flat in vec4 toLocal[3];
layout(location = 6) flat in vec4 radial;  // inner (η), 1/Δr, spheres − 1, outer (η)
layout(location = 7) flat in vec4 face;    // n_r, 1/(6 n_r), 1/n_r, 1/(14 · spheres)
layout(location = 8) flat in vec4 inRange[7];
layout(location = 15) flat in uint self;
layout(location = 16) flat in float reach;  // the tail's end (η), 0: none (evaluate.cpp tailFade)
layout(location = 17) flat in uvec4 onObject[2];  // the other rtf objects' entity + 1 (0xFFFFFFFF: none)

layout(location = 0) out vec4 outRadiance;

void main() {
  ivec2 pixel = kStep == 1u ? ivec2(gl_FragCoord.xy)
                            : reducedSamplePixel(ivec2(gl_FragCoord.xy), int(kStep), ivec2(camera.resolution.xy));
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) discard;
  vec4 r = vec4(worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth), 1.0);
  vec3 q = vec3(dot(toQ[0], r), dot(toQ[1], r), dot(toQ[2], r));
  // Eq. 10's radial weights (rtf.glsl rtfTaps, evaluate.cpp lookup()): the slice coordinate
  // clamped to the first and last sphere's slice centres (inside the innermost sphere: its value),
  // times the fade beyond the outermost sphere r_N (rtfTailFade = evaluate.cpp tailFade): (r_N/|q|)²
  // (the object's solid angle), ramped to zero over the last quarter spacing before r_N + Δr, or before `reach`.
  float len = length(q);
  float fade = rtfTailFade(radial.w, radial.y, len, reach);
  if (fade <= 0.0) discard;  // beyond the fade: the field is zero
  // The object's own surface: its transfer already holds its self-interreflection (Eq. 8).
  vec4 normal = texelFetch(gNormal, pixel, 0);
  uint receiver = kSelfInNormal ? uint(normal.w) : texelFetch(gEntity, pixel, 0).r;  // entity + 1
  if (kSelfInNormal) {
    if (self != 0u && normal.w == float(self)) discard;
  } else if (receiver == self) {
    discard;
  }
  // On another rtf object's surface: X's on-object variant (2 vector compares, no branch: a slice offset below).
  bool on = any(equal(uvec4(receiver), onObject[0])) || any(equal(uvec4(receiver), onObject[1]));
  float variant = on ? 7.0 * (radial.z + 1.0) : 0.0;
  // Between spheres s0 and s0 + 1 the weight w is linear in 1/|q|² (rtfRadialWeight; evaluate.cpp
  // radialWeight says why). The texels hold Y = r_s² X (xi.comp; xi_pass.hpp netScale says why), and
  // (1 − w) Y_a/r_a² + w Y_b/r_b² = ((1 − w') Y_a + w' Y_b)/|q|² with w' = (|q|² − r_a²)/(r_b² − r_a²):
  // w' is handed to the sampler as the slice coordinate's fraction and 1/|q|² multiplies the sum
  // (|q| clamped to [r_0, r_N]: inside the innermost sphere Y_0/r_0², beyond the outermost Y_N/|q|² is
  // `fade`'s (r_N/|q|)² on X_N = Y_N/r_N²).
  float t = clamp((len - radial.x) * radial.y, 0.0, radial.z);
  float s0 = min(floor(t), radial.z - 1.0), ra = radial.x + s0 / radial.y, rb = ra + 1.0 / radial.y;
  t = s0 + clamp((len * len - ra * ra) / (rb * rb - ra * ra), 0.0, 1.0);
  float rc = clamp(len, radial.x, radial.w);
  fade /= rc * rc;
  // Bilinear within the face by clamped coordinates (rtfFace): the sampler's.
  int f;
  vec2 st;
  rtfFace(len > 0.0 ? q / len : vec3(0.0), int(face.x), f, st);
  vec2 uv = vec2((float(f) * face.x + st.x + 0.5) * face.y, (st.y + 0.5) * face.z);
  vec3 nw = normalize(normal.xyz);
  vec3 n = vec3(dot(toLocal[0].xyz, nw), dot(toLocal[1].xyz, nw), dot(toLocal[2].xyz, nw));
  float y[9];
  shEval9(n, y);  // bands 0–1 only when !kSh9: the compiler drops the rest

  // Σ_i y_i Y_i with Y = m(2t − 1) per slot and t trilinear (one fetch per texel: bilinear in the
  // face, linear between the spheres by the slice coordinate; the weights sum to 1 before the fade):
  // Σ (y m)(2t − 1) = 2 (y m)·t − Σ (y m); × fade/|q|² below makes it Σ_i y_i X_i.
  float spheres = radial.z + 1.0;
  vec4 y0 = vec4(y[0], y[1], y[2], y[3]), y1 = vec4(y[4], y[5], y[6], y[7]);
  vec3 sum;
  for (int c = 0; c < 3; ++c) {
    vec4 a = y0 * inRange[c];
    vec4 ta = texture(netTex, vec3(uv, (variant + float(c) * spheres + t + 0.5) * face.w));
    sum[c] = dot(a, 2.0 * ta - 1.0);
    if (kSh9) {
      vec4 b = y1 * inRange[3 + c];
      vec4 tb = texture(netTex, vec3(uv, (variant + float(3 + c) * spheres + t + 0.5) * face.w));
      sum[c] += dot(b, 2.0 * tb - 1.0);
    }
  }
  if (kSh9) {
    vec3 e = y[8] * inRange[6].rgb;
    sum += e * (2.0 * texture(netTex, vec3(uv, (variant + 6.0 * spheres + t + 0.5) * face.w)).rgb - 1.0);
  }
  vec3 albedo = kStep == 1u ? texelFetch(gAlbedo, pixel, 0).rgb : vec3(1.0);  // reduced: ρ at the upsample
  outRadiance = vec4(albedo * (fade * sum), 0.0);
}
