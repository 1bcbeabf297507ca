// Octahedral direction maps: a res² grid of texels over the octahedral square of probes/probe_tiles.glsl
// (probeOctEncode / probeOctDecode: Cigolle et al. 2014, "A Survey of Efficient Representations for
// Independent Unit Vectors", JCGT 3(2), §3.4; z the pole), no border, each texel of roughly equal
// solid angle (within 2× of 4π/res²). The probes' 16² maps of the static radiance
// (engine/gi/probes/probe_volume.hpp dirMap) and SL pass 2's read of them at each SL
// (sl/probe_shadow.glsl, "blocked_read": "map") share this file; the C++ side compiles it against glm
// (engine/math/oct_map.cpp), so the bake, the C++ reference (engine/gi/sl/probe_shadow.cpp) and the
// shader pick one texel for one direction. Keep to the GLSL/C++ common subset (common/sh.glsl's header).
#ifndef BOUNCE_OCT_MAP_GLSL
#define BOUNCE_OCT_MAP_GLSL
#ifndef BOUNCE_PROBE_TILES_GLSL
#include "probes/probe_tiles.glsl"  // C++ includers include it first (its path from the repository root)
#endif

const int OCT_MAP_RES = 16;      // texels per side (math::kOctMapRes)
const int OCT_MAP_TEXELS = 256;  // OCT_MAP_RES²

// The texel (row-major, y · OCT_MAP_RES + x) whose square holds unit direction d: a nearest read.
int octTexel(vec3 d) {
  vec2 o = probeOctEncode(d);
  int x = clamp(int((o.x * 0.5f + 0.5f) * float(OCT_MAP_RES)), 0, OCT_MAP_RES - 1);
  int y = clamp(int((o.y * 0.5f + 0.5f) * float(OCT_MAP_RES)), 0, OCT_MAP_RES - 1);
  return y * OCT_MAP_RES + x;
}

// The unit direction through texel t's centre.
vec3 octTexelDirection(int t) {
  int x = t % OCT_MAP_RES, y = t / OCT_MAP_RES;
  return probeOctDecode(vec2((float(x) + 0.5f) / float(OCT_MAP_RES) * 2.0f - 1.0f,
                             (float(y) + 0.5f) / float(OCT_MAP_RES) * 2.0f - 1.0f));
}

#endif  // BOUNCE_OCT_MAP_GLSL
