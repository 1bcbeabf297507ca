#version 450
#extension GL_GOOGLE_include_directive : require
// DNRT, box and full-screen draws: Σ_j c_j M_j (Eq. 16's sum, per RGB channel) at every grid vertex
// of one object's field, once per frame, into an RGBA16F volume the draw then reads with ONE
// trilinear tap (dnrt.frag) instead of one tap per Table 2 slot (3 for 4 SH, 7 for 9 SH).
// Exact by linearity: trilinear filtering is a weighted sum of the 8 vertices and Σ_j c_j M_j is
// affine in the texels, so filtering the per-vertex sums equals summing the filtered slots (up to
// fp16 rounding of the sums, 2⁻¹¹ relative, and now float filter weights where llvmpipe filters
// UNORM8 with 8-bit ones). Why: on llvmpipe the three RGBA8 trilinear taps were ~0.09 of SSAO out
// of the pass's ~0.21, the largest item (README "DNRT and probes cost, session 8"); this pass
// touches N³ = 32 768 vertices, the draw ~900 000 pixels.
// Per vertex as dnrt.frag did per pixel: a + Σ_slot dot(k_slot, unorm texel_slot) (dnrt.glsl).
// The clustered draw (clustered.frag) reads one brick per object of a combined atlas the same way:
// a dispatch per object over its field's padded atlas brick (cluster.hpp), written to the object's
// own brick (objects share a field's brick in the RGBA8 atlas, not their c_j).
#include "dnrt/dnrt.glsl"

// 8 × 4 × 4: llvmpipe runs a workgroup as loops over y and z of x-rows of 8 lanes (its 256-bit
// vectors hold 8 fp32), so a 4-wide x left half of every vector idle; 8-wide rows fill them. Measured
// (README "DNRT cost, session 13"): the dispatch costs ~0.7× the 4³ one. engine/gi/dnrt/node.cpp
// dispatches ceil(size / kCombineLocal) groups per axis.
layout(local_size_x = 8, local_size_y = 4, local_size_z = 4) in;

layout(constant_id = 0) const bool kSh9 = false;
// A second term of the same object, read in the same dispatch: its occlusion-only field (−k_j) with
// the lights' c_j negated ("lights_in_anti_radiance": false, runtime.hpp), record pc.occlusion,
// slots at bindings 9..15. Summed in fp32 before the one fp16 store (no barrier, no fp16 round trip
// of the first term).
layout(constant_id = 1) const bool kOcclusion = false;

// This dispatch's k and a (DnrtObject's) and its occlusion term's, in a uniform block bound at the
// dispatch's own record (node.cpp CombineRecord): every read has a constant offset, so llvmpipe loads it
// once for all lanes. Read from the storage buffer of records instead (objects[pc.object].k), each scalar
// was a per-lane loop with a bounds check: ~30 a vertex, 13 ms of a 15 ms dispatch at load 7 against 1.7 ms
// with constants in their place (README "DNRT's fused term only inside its outer cube, session 19").
layout(std140, set = 0, binding = 0) uniform Record {
  vec4 k[7];
  vec4 a;
  vec4 occlusionK[7];  // kOcclusion: the occlusion-only field's (−c_j^lights folded in); unread otherwise
  vec4 occlusionA;
} rec;
// Table 2's slots (dnrt.frag's order); a 4-SH field binds slot 0 in 3..6 (never read).
layout(set = 0, binding = 1) uniform sampler3D field0;
layout(set = 0, binding = 2) uniform sampler3D field1;
layout(set = 0, binding = 3) uniform sampler3D field2;
layout(set = 0, binding = 4) uniform sampler3D field3;
layout(set = 0, binding = 5) uniform sampler3D field4;
layout(set = 0, binding = 6) uniform sampler3D field5;
layout(set = 0, binding = 7) uniform sampler3D field6;
layout(set = 0, binding = 8, rgba16f) uniform writeonly image3D combined;
// The occlusion-only field's slots, the same layout (kOcclusion; else bound to the first field's).
layout(set = 0, binding = 9) uniform sampler3D occlusion0;
layout(set = 0, binding = 10) uniform sampler3D occlusion1;
layout(set = 0, binding = 11) uniform sampler3D occlusion2;
layout(set = 0, binding = 12) uniform sampler3D occlusion3;
layout(set = 0, binding = 13) uniform sampler3D occlusion4;
layout(set = 0, binding = 14) uniform sampler3D occlusion5;
layout(set = 0, binding = 15) uniform sampler3D occlusion6;
layout(push_constant) uniform Push {
  int srcZ;        // first z layer of the vertices in the slot textures (an atlas brick's z0, else 0)
  int dstZ;        // first z layer written in `combined`
  int size;        // vertices per axis: N (a field's own textures) or N + 2 (a padded atlas brick)
  int occlusionZ;  // kOcclusion: first z layer of its vertices in occlusion0..6
} pc;

void main() {
  ivec3 v = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(v, ivec3(pc.size)))) return;
  ivec3 src = ivec3(v.xy, v.z + pc.srcZ);
  const vec4 k[7] = rec.k;
  vec3 sum = rec.a.rgb + vec3(dot(k[0], texelFetch(field0, src, 0)),
                                            dot(k[1], texelFetch(field1, src, 0)), dot(k[2], texelFetch(field2, src, 0)));
  if (kSh9) {
    sum += vec3(dot(k[3], texelFetch(field3, src, 0)), dot(k[4], texelFetch(field4, src, 0)),
                dot(k[5], texelFetch(field5, src, 0)));
    sum += k[6].rgb * texelFetch(field6, src, 0).rgb;
  }
  if (kOcclusion) {
    ivec3 o = ivec3(v.xy, v.z + pc.occlusionZ);
    const vec4 q[7] = rec.occlusionK;
    sum += rec.occlusionA.rgb + vec3(dot(q[0], texelFetch(occlusion0, o, 0)),
                                             dot(q[1], texelFetch(occlusion1, o, 0)), dot(q[2], texelFetch(occlusion2, o, 0)));
    if (kSh9) {
      sum += vec3(dot(q[3], texelFetch(occlusion3, o, 0)), dot(q[4], texelFetch(occlusion4, o, 0)),
                  dot(q[5], texelFetch(occlusion5, o, 0)));
      sum += q[6].rgb * texelFetch(occlusion6, o, 0).rgb;
    }
  }
  imageStore(combined, ivec3(v.xy, v.z + pc.dstZ), vec4(sum, 0.0));
}
