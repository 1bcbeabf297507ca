#version 450
#extension GL_GOOGLE_include_directive : require
// A deferred GI term at half or quarter resolution, second step (engine/gi/upsample_pass.hpp: DNRT's
// "dnrt.upsample", RTF's "rtf.upsample"): the reduced target ("dnrt.half", "rtf.quarter", …) holds at
// sample j the sum over objects of the technique's term without ρ_r at G-buffer pixel kStep·j — DNRT's
// Eq. 16, (n_o·n_r)₊ s(r) Σ_j c_j M_j(r) (dnrt.frag / clustered.frag with kStep); RTF's Eq. 10 shading,
// Σ_i y_i(n) X_i(q) (rtf.frag with kStep). Every full-resolution pixel blends its 4 nearest samples
// with the depth- and normal-aware weights SL's upsample uses (common/upsample.glsl, one copy) and ADDS
// ρ_r times the blend to "lighting.hdr", as the full-resolution draw does. One full-screen triangle.
layout(constant_id = 0) const uint kStep = 2u;  // G-buffer pixels per sample per axis: 2 or 4
#include "frame.glsl"
#include "upsample.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(set = 1, binding = 3) uniform sampler2D reduced;  // e.g. "dnrt.half", "rtf.quarter"

layout(location = 0) out vec4 outRadiance;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ivec2 j[4], q[4];
  vec2 f;
  upsampleTaps(pixel, int(kStep), textureSize(reduced, 0), ivec2(camera.resolution.xy), j, q, f);
  vec3 e[4];
  for (int k = 0; k < 4; ++k) e[k] = texelFetch(reduced, j[k], 0).rgb;
  // No object reached any of the 4 samples (the target is cleared to 0): the blend is 0 whatever its
  // weights, exactly, so the pixel adds nothing and skips the receivers' fetches. (Per sample, not the
  // sum: the anti-radiance makes terms negative.)
  if (e[0] == vec3(0.0) && e[1] == vec3(0.0) && e[2] == vec3(0.0) && e[3] == vec3(0.0)) discard;
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) discard;
  vec3 n = texelFetch(gNormal, pixel, 0).xyz;
  vec3 p = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
  float eye = max(length(p - camera.position.xyz), 1e-6);
  vec3 pq[4], nq[4];
  bool valid[4];
  upsampleReceivers(gDepth, gNormal, camera.invViewProj, camera.resolution.zw, q, pq, nq, valid);
  outRadiance = vec4(texelFetch(gAlbedo, pixel, 0).rgb * upsampleBlend(p, n, eye, f, pq, nq, valid, e), 0.0);
}
