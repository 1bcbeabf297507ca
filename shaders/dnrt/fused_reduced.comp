#version 450
#extension GL_GOOGLE_include_directive : require
// DNRT's fused mode below full resolution ("dnrt": {"mode": "fused", "resolution": "half"|"quarter"};
// pass "dnrt.fused.reduced", README "DNRT's fused term at reduced resolution, session 17"): the part of
// Eq. 16 that depends on the receiver's position alone,
//   f(r) = s(r) · Σ_j c_j M_j(r)          (fall-off × the combined volume's trilinear tap, RGB),
// at reduced sample j = the G-buffer pixel step·j (upsample.glsl reducedSamplePixel, as the reduced
// dnrt draws), written premultiplied by the sample's validity w (1 = a receiver other than the object,
// 0 = sky or the object's own pixel): (w·f, w). probes.frag (kDnrtStep > 1, dnrtReducedQuadTap and dnrt.glsl
// dnrtFusedReducedTerm) blends its 4 nearest samples bilinearly and divides by the blended w, so sky and the
// object's own samples never bleed into their neighbours, and multiplies the per-pixel factors
// (n_o·n_r)₊ and the receiver tests itself: those hold the normal, which is where the term is not
// smooth; f is smooth in world space (a trilinear field times the §5.2.2 fall-off).
#include "dnrt/dnrt.glsl"
#include "upsample.glsl"  // reducedSamplePixel; frame.glsl worldFromDepth

layout(constant_id = 0) const int kStep = 2;  // G-buffer pixels per sample along each axis: 2 or 4

// 32×8: llvmpipe runs a workgroup as 8-lane rows, each group a task of its own; 8×8 made 900 small tasks
// at quarter resolution (1280×720), 32×8 makes 230 (node.cpp kFusedReducedLocal; session 18).
layout(local_size_x = 32, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D gDepth;
layout(set = 0, binding = 1) uniform sampler2D gNormal;
layout(set = 0, binding = 2) uniform sampler3D combined;  // this frame's Σ_j c_j M_j (dnrt.combine.fused)
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D reducedOut;

layout(push_constant) uniform Push {
  mat4 invViewProj;    // the frame's camera (frame.glsl Camera.invViewProj)
  vec4 worldToQ[3];    // rows of r ↦ q (units of R), DnrtShaderObject's
  vec4 extents;        // x inner, y outer (units of R), z entity id + 1 (0 = none), w grid N
} pc;

void main() {
  const ivec2 j = ivec2(gl_GlobalInvocationID.xy);
  const ivec2 size = imageSize(reducedOut);
  if (j.x >= size.x || j.y >= size.y) return;
  const ivec2 full = textureSize(gDepth, 0);
  const ivec2 p = reducedSamplePixel(j, kStep, full);
  const float depth = texelFetch(gDepth, p, 0).r;
  const vec4 normal = texelFetch(gNormal, p, 0);
  vec4 outValue = vec4(0.0);
  const bool self = pc.extents.z != 0.0 && normal.w == pc.extents.z;
  if (depth < 1.0 && !self) {
    const vec3 r = worldFromDepth(pc.invViewProj, (vec2(p) + 0.5) / vec2(full), depth);
    const vec3 q = dnrtQ(pc.worldToQ, vec4(r, 1.0));
    const float s = dnrtFalloff(q, pc.extents.x, pc.extents.y);
    const vec3 sum = s > 0.0 ? textureLod(combined, dnrtUvw(q, pc.extents.x, pc.extents.w), 0.0).rgb : vec3(0.0);
    outValue = vec4(s * sum, 1.0);
  }
  imageStore(reducedOut, j, outValue);
}
