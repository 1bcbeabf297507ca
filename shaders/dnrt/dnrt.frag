#version 450
#extension GL_GOOGLE_include_directive : require
// DNRT: adds one object's L_DNRT (dnrt.glsl) to "lighting.hdr" with additive blending.
// Variants are specialization constants, one pipeline each (llvmpipe runs an untaken branch in
// full): kIntrusion tests the intrusion map (§5.2.3). Σ_j c_j M_j comes from this frame's combined
// volume (combine.comp), one trilinear tap for 4 SH and 9 SH alike.
#include "frame.glsl"
#include "dnrt/dnrt.glsl"
#include "dnrt/intrusion.glsl"
#include "gbuffer.glsl"
#include "upsample.glsl"

layout(constant_id = 0) const bool kIntrusion = false;
// kSelfInNormal: the object's entity id + 1 is ≤ kEntityInNormalMax, so the self test compares it with
// the normal's w (gbuffer.glsl) instead of fetching gbuffer.entity: one G-buffer fetch of four less
// per reached pixel, the same pixels rejected (node.cpp pipeline()).
layout(constant_id = 2) const bool kSelfInNormal = false;
// kStep: G-buffer pixels per shaded sample along each axis — 1 (full), 2 (half), 4 (quarter); the level's
// "dnrt": {"resolution"} (node.cpp). Below full the draw covers the reduced target "dnrt.half" /
// "dnrt.quarter": sample j shades G-buffer pixel kStep·j (reducedSamplePixel) and writes Eq. 16 without
// ρ_r, (n_o·n_r)₊ s(r) Σ_j c_j M_j(r), which passes/reduced_upsample.frag spreads over every pixel (depth- and
// normal-aware, upsample.glsl) and multiplies by ρ_r there. That target has no depth attachment, so
// the early depth test below rejects nothing then; s(r) > 0 keeps the same receivers.
layout(constant_id = 3) const uint kStep = 1u;

// The box's depth test (GREATER_OR_EQUAL against the G-buffer's depth, no depth write: node.cpp
// pipeline()) before the shader: a pixel whose surface lies behind the box's exit face never runs
// it. Without depth writes or gl_FragDepth, early and late tests keep the same fragments, so the
// image is the same (the discards below write nothing either way).
layout(early_fragment_tests) in;

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(set = 1, binding = 4) uniform usampler2D gEntity;
// rgb: Σ_j c_j M_j per channel at each grid vertex, this frame (combine.comp; the field's N³).
layout(set = 2, binding = 0) uniform sampler3D combined;
// Intrusion map (intrusion.glsl); a 1×1 "nothing near" map for objects without intrusion.
layout(set = 2, binding = 1) uniform sampler2DArray intrusion;

layout(location = 0) flat in vec4 worldToQ[3];
layout(location = 3) flat in vec4 centreWorld;
layout(location = 4) flat in vec4 extents;
layout(location = 5) flat in uint self;

layout(location = 0) out vec4 outRadiance;

void main() {
  ivec2 pixel = kStep == 1u ? ivec2(gl_FragCoord.xy)
                            : reducedSamplePixel(ivec2(gl_FragCoord.xy), int(kStep), ivec2(camera.resolution.xy));
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) discard;
  vec4 r = vec4(worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth), 1.0);
  vec3 q = dnrtQ(worldToQ, r);
  float s = dnrtFalloff(q, extents.x, extents.y);
  if (s <= 0.0) discard;
  vec3 toO = centreWorld.xyz - r.xyz;
  float len = length(toO);
  if (!(len > 1e-6 * centreWorld.w)) discard;  // at o: n_o undefined
  if (kIntrusion) {
    // Something between o and r: r does not see the object (§5.2.3). Bias: 2% of R plus 2% of the
    // distance, the size of a 128² texel at 90° and the receiver's own surface in the map.
    float nearest = texture(intrusion, intrusionCoord(-toO)).r;
    if (len > nearest + 0.02 * centreWorld.w + 0.02 * len) discard;
  }
  vec4 normal = texelFetch(gNormal, pixel, 0);
  vec3 nr = normal.xyz;
  float lamb = dnrtLambert(toO, len, nr);
  if (lamb <= 0.0) discard;
  // The object's own surface: its field holds filled (interior) values there, not a transfer.
  if (kSelfInNormal) {
    if (self != 0u && normal.w == float(self)) discard;
  } else if (self != 0u && texelFetch(gEntity, pixel, 0).r == self) {
    discard;
  }
  vec3 uvw = dnrtUvw(q, extents.x, extents.w);
  // Σ_j c_j M_j(r) (§5.1.2's dot products, done per grid vertex by combine.comp), trilinear.
  vec3 sum = texture(combined, uvw).rgb;
  vec3 albedo = kStep == 1u ? texelFetch(gAlbedo, pixel, 0).rgb : vec3(1.0);  // reduced: ρ_r at the upsample
  outRadiance = vec4(albedo * (lamb * s) * sum, 0.0);
}
