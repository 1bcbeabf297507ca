// SL pass 2's resources (engine/gi/sl/shade.hpp ShadeData fills them) and the accessors sl.glsl
// needs. All uniform blocks and a texture, no SSBOs: DESIGN.md's llvmpipe facts for fragment shaders.
// The includer defines SL_SET (descriptor set) and SL_BINDING (first of three bindings) first.
//   SL_BINDING + 0: slTables, rgba32f 256×3 (sl.glsl's header);
//   SL_BINDING + 1: SlSpheres (std140): header.x = SL count; per SL i, spheres[4i] = (world centre,
//                   radius), spheres[4i + 1 … 4i + 3] = the SL-local → world rotation's columns in
//                   xyz, spheres[4i + 1].w = its object index, spheres[4i + 2].w = its object's
//                   union share (sl/probe_shadow.glsl), spheres[4i + 3].w = its set's shadow
//                   scale (SlSphere::shadowScale); header.y = object ids in use (max + 1),
//                   objects[o] = (mean of object o's sphere centres, its sphere count): per-object
//                   blocking's order, the same for every pixel, so computed once on the CPU;
//                   header.z = §7.3 parents (sl/hierarchy.glsl), object o's at SL index header.x + o;
//                   intersects[i]: bit j % 32 of word j / 32 set when SLs i and j belong to one
//                   object and overlap (evaluate.cpp's intersects(), in double on the CPU: they
//                   ignore each other as blockers, §6.2);
//   SL_BINDING + 2: SlIntensity (std140): pass 1's output buffer, L^c of SL i as fp16 pairs in
//                   words 24i … 24i + 23 (engine/gi/sl/intensity_words.hpp: word 8c + m holds
//                   channel c of coefficients 2m, 2m + 1) — half the per-lane gathers of rgb floats;
#ifndef BOUNCE_SL_DATA_GLSL
#define BOUNCE_SL_DATA_GLSL

const uint kSlMaxLights = 128u;  // shade.hpp kMaxShadedSpheres: 128 · 6 uvec4 = 12 KiB of intensity

layout(set = SL_SET, binding = SL_BINDING) uniform sampler2D slTables;
layout(std140, set = SL_SET, binding = SL_BINDING + 1) uniform SlSpheres { uvec4 slHeader; vec4 slSpheres[kSlMaxLights * 4u]; vec4 slObjects[kSlMaxLights]; uvec4 slIntersectMasks[kSlMaxLights]; };
layout(std140, set = SL_SET, binding = SL_BINDING + 2) uniform SlIntensity { uvec4 slIntensityWords[kSlMaxLights * 6u]; };

uint slCount() { return slHeader.x; }
vec4 slSphere(uint i) { return slSpheres[4u * i]; }
mat3 slRotation(uint i) { return mat3(slSpheres[4u * i + 1u].xyz, slSpheres[4u * i + 2u].xyz, slSpheres[4u * i + 3u].xyz); }
uint slObject(uint i) { return uint(slSpheres[4u * i + 1u].w + 0.5); }
uint slObjectCount() { return slHeader.y; }
float slShare(uint i) { return slSpheres[4u * i + 2u].w; }
float slSilhouette(uint i) { return slSpheres[4u * i + 3u].w; }
vec4 slObjectCentre(uint o) { return slObjects[o]; }
uvec4 slIntersecting(uint i) { return slIntersectMasks[i]; }
// Channel c of L^c_2m and L^c_2m+1 of SL i (m a loop counter: the component index folds to a constant).
vec2 slIntensityPair(uint i, uint c, uint m) { return unpackHalf2x16(slIntensityWords[6u * i + 2u * c + m / 4u][m % 4u]); }

// "blocked_light": "sphere" (sl/probe_shadow.glsl, engine/gi/sl/probe_shadow.hpp): the light the SLs
// block, read at each SL's posed centre, in its own uniform block at binding SL_INDIRECT_BINDING when
// the includer defines it (sl.shadow and the fused pass; not pass 1 nor sl.local), in one of two
// layouts (engine/gi/sl/shade.hpp ShadeData::setSpheres):
//   "blocked_read": "sh": the probes' radiance SH (pass 1's `indirect`). fp16, 16 words per SL (4 uvec4):
//   half h = 3k + c (coefficient k < 9, channel c) in word h / 2, low half first (packHalf2x16); half
//   27 is 0. 128 · 64 B = 8 KiB, the block's size (kBlockedMap false).
//   "blocked_read": "map": the probes' direction maps blended at the SL (common/oct_map.glsl texels).
//   RGB9E5 (glm::packF3x9_E1x5: bits 0–8, 9–17, 18–26 the channels' mantissas, 27–31 the shared
//   exponent, bias 15), texel t of SL i in word 256 i + t: kSpheres · 1 KiB, the block's size
//   (kBlockedMap true; kSpheres ≤ kSlMaxMappedLights = 64, so ≤ 64 KiB).
// The includer declares the specialization constants kSpheres (sl.glsl's) and kBlockedMap first; the
// block's size follows them, as shade.hpp indirectBlockBytes sizes the buffer and its descriptor range.
#ifdef SL_INDIRECT_BINDING
#include "oct_map.glsl"
const uint kSlMaxMappedLights = 64u;   // shade.hpp kMaxMappedSpheres
const uint kSlMapWordsPerLight = 256u;  // shade.hpp kMapWordsPerSl
const uint kSlIndirectVec4s = kBlockedMap ? kSpheres * (kSlMapWordsPerLight / 4u) : kSlMaxLights * 4u;
layout(std140, set = SL_SET, binding = SL_INDIRECT_BINDING) uniform SlIndirect { uvec4 slIndirectWords[kSlIndirectVec4s]; };
float slIndirectHalf(uint i, uint h) {
  vec2 pair = unpackHalf2x16(slIndirectWords[4u * i + h / 8u][(h / 2u) % 4u]);
  return (h % 2u) == 0u ? pair.x : pair.y;
}
// Coefficient k (W/(m²·sr) per channel) of the radiance SH at SL i's posed centre (k a loop counter).
vec3 slIndirect(uint i, uint k) { return vec3(slIndirectHalf(i, 3u * k), slIndirectHalf(i, 3u * k + 1u), slIndirectHalf(i, 3u * k + 2u)); }
// SL i's blended map read in unit direction d (W/(m²·sr) per channel): the texel holding d (nearest),
// one word, RGB9E5 as glm::unpackF3x9_E1x5 decodes it: mantissas × 2^(e − 15 − 9).
vec3 slIndirectMap(uint i, vec3 d) {
  uint w = kSlMapWordsPerLight * i + uint(octTexel(d));
  uint v = slIndirectWords[w / 4u][w % 4u];
  return vec3(float(v & 511u), float((v >> 9u) & 511u), float((v >> 18u) & 511u)) * exp2(float(v >> 27u) - 24.0);
}
#endif

#endif  // BOUNCE_SL_DATA_GLSL
