// The body of SL pass 2's fragment shader: sl.frag includes it, sl_hierarchy.frag with SL_HIERARCHY defined (§7.3).
// SL pass 2 (Guerrero, Jeschke, Wimmer 2008, §5.2), deferred: every G-buffer pixel is a receiver;
// the diffuse reflection of the light arriving from every SL, ρ(p)/π · E(p) with E(p) = Σ L̃ Ṽ
// (Eq. 13–14, sl.glsl), is ADDED to "lighting.hdr" (additive blending; W/(m²·sr), linear HDR).
// Background pixels (depth 1) receive nothing. Drawn as tiles (shaders/sl/tiles.vert): a pixel
// visits only its tile's SLs, those whose influence bound covers the tile. Order, blocking, the
// per-receiver array size and the resolution are specialization constants
// (engine/gi/sl/shade.hpp ShadeData::specialization, kStep: engine/gi/sl/node.cpp).
// Half or quarter resolution (kStep 2 or 4, engine/gi/resolution.hpp): pixel j of the reduced
// target shades the G-buffer's pixel kStep·j and writes E itself (W/m², no albedo) into "sl.half" /
// "sl.quarter"; shaders/sl/upsample.frag spreads it over the full resolution with depth and normal
// weights and applies each full pixel's own albedo.
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;
layout(constant_id = 4) const uint kStep = 1u;  // G-buffer pixels per sample per axis: 1, 2, 4
layout(constant_id = 5) const bool kSingleObject = false;  // per-object: tiles whose SLs are one object's
#define SL_SINGLE_OBJECT kSingleObject

#include "frame.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
#define SL_SET 1
#define SL_BINDING 3
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/receiver.glsl"
#ifdef SL_HIERARCHY
#include "sl/hierarchy.glsl"
#endif

layout(location = 0) flat in uvec4 inCandidates;
#ifdef SL_HIERARCHY
layout(location = 1) flat in vec4 inRatios[kSlHierObjects];  // the tile's Eq. 25 t per object (hierarchy_ratio.comp)
#endif
layout(location = 0) out vec4 outRadiance;

const float kInvPi = 0.31830988618379067;

void main() {
  ivec2 pixel;
  vec3 p, n;
  if (!slReceiver(pixel, p, n)) {
    outRadiance = vec4(0.0);
    return;
  }
#ifdef SL_HIERARCHY
  // §7.3 (sl/hierarchy.glsl): the children cut by rule 0, plus each listed parent for the share cut.
  vec3 e = max(slIrradianceAt(p, n, inCandidates) + slHierarchyAt(p, n, inCandidates, inRatios), vec3(0.0));
#else
  vec3 e = max(slIrradianceAt(p, n, inCandidates), vec3(0.0));
#endif
  outRadiance = kStep > 1u ? vec4(e, 0.0) : vec4(texelFetch(gAlbedo, pixel, 0).rgb * kInvPi * e, 0.0);
}
