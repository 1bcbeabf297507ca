#version 450
#extension GL_GOOGLE_include_directive : require
// DNRT, clustered mode (issue 15; engine/gi/dnrt/cluster.hpp): one full-screen triangle for a
// batch of up to 32 objects. Each pixel reads the G-buffer once, then visits only the objects in its
// 16×16 tile's mask and adds Σ_objects L_DNRT (Eq. 16, term for term dnrt.frag's) in one blend.
//
// The loops (and why two, why do-while): dnrt/cluster.glsl, shared with the fused mode's several objects.
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
// mask is that pixel's) and writes the sum without ρ_r for passes/reduced_upsample.frag.
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

#include "dnrt/cluster.glsl"  // after `objects`, which it reads

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
    outRadiance = vec4(albedo * dnrtClusterTerm(0, r, nr, combined, pc.invAtlasSize.xyz, exact), 0.0);
    return;
  }

  // 1. The tile's objects that may reach r; 2. the terms of those that do, summed, times ρ_r once.
  uint live = dnrtClusterLive(mask, r, nr, entity);
  if (live == 0u) discard;
  vec3 total = dnrtClusterSum(live, r, nr, combined, pc.invAtlasSize.xyz);
  vec3 albedo = kStep == 1u ? texelFetch(gAlbedo, pixel, 0).rgb : vec3(1.0);  // reduced: ρ_r at the upsample
  outRadiance = vec4(albedo * total, 0.0);
}
