// Shared by the two VLM passes (engine/gi/vlm/node.hpp). One virtual light (a triangle of a Virtual
// Light Mesh, thesis §3.1) as packed by engine/gi/vlm/vlm_mesh.hpp: VlmLightGpu.
#ifndef VLM_COMMON_GLSL
#define VLM_COMMON_GLSL

struct VlmLight {
  vec4 v0;     // xyz world position (m), w the tag id (§3.4) as a float (exact below 2^24; 0 = none)
  vec4 v1;     // xyz, counter-clockwise seen from the emitting side
  vec4 v2;
  vec4 scale;  // rgb reflectance × colour × intensity (§3.3, §3.5), w unused
};

// Phase 1's sample points (several per triangle, §3.3 "intensity at each virtual light"): the
// centroid and the three points halfway from it to each vertex, equal weights.
const int VLM_PHASE1_SAMPLES = 4;
vec3 vlmSamplePoint(VlmLight l, int i) {
  vec3 c = (l.v0.xyz + l.v1.xyz + l.v2.xyz) / 3.0;
  if (i == 0) return c;
  vec3 v = i == 1 ? l.v0.xyz : (i == 2 ? l.v1.xyz : l.v2.xyz);
  return 0.5 * (c + v);
}

#endif
