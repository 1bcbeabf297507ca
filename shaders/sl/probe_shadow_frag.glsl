// The body of "sl.shadow"'s fragment shader: probe_shadow.frag includes it, probe_shadow_hierarchy.frag with SL_HIERARCHY defined (§7.3).
// Pass "sl.shadow" (issue 13 pass 2: the dynamic objects' soft shadows on the probes' indirect
// light), deferred: every G-buffer pixel adds ρ(p)/π · ao · ΔE(p) to "lighting.hdr" (additive
// blending into RGBA16F, which keeps the negative sum: ΔE ≤ 0 takes light away), ΔE from
// sl/probe_shadow.glsl with the probes' radiance SH read as the probes pass reads it
// (probes/probe_sh.glsl), so the probes' ρ/π · ao · E_u plus this is ρ/π · ao · E_shadowed when the
// probes pass reads the SH too. With its irradiance tiles (session 11, probes.frag kTiles) it adds
// the tiles' E_u instead, which differs from the SH's by at most the tiles' interpolation error E_t
// (gi::probes::tileIrradianceError, + fp16), so the sum is E_shadowed within ρ/π · ao · E_t; and
// since ΔE is clamped at −E_u of the SH, not of the tiles, a fully shadowed pixel's indirect sum can
// go below 0 by up to that much (E_tiles < E_sh there). Not clamped here: this pass never sees the
// tile value; the frame's negative channels end at tonemap.frag's max(c, 0), after the direct light.
// Background pixels (depth 1) receive nothing. Drawn as the SL pass's tiles (sl/shadow_cut_tiles.vert):
// a pixel visits only its tile's SLs; tiles no SL's influence reaches are not drawn (ΔE = 0 there).
// Specialization constants: sl.glsl's (ids 0–3, engine/gi/sl/shade.hpp), the probes' SH count
// (id 4) and kStep (id 5, G-buffer pixels per sample per axis: 1, 2, 4): pixel j of the reduced
// "sl.half" / "sl.quarter" takes G-buffer pixel kStep·j and adds ao · ΔE there (no albedo;
// "sl.upsample" applies each full pixel's ρ/π, as for the SLs' own E; ao is then taken at kStep·j,
// not per full pixel — ours, for the reduced cost).
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;
layout(constant_id = 4) const int kCoeffs = 9;  // the probes' order²: 4 or 9
layout(constant_id = 5) const uint kStep = 1u;
// "blocked_light": "sphere" (scene::Sl::blockedAtSphere): the blocked light read at each SL's centre
// (sl/probe_shadow.glsl); false ("receiver", the default): the receiver's SH. Not with the hierarchy.
layout(constant_id = 6) const bool kBlockedAtSphere = false;
// "blocked_read": "map" (scene::Sl::blockedMap, with kBlockedAtSphere): the SLs' blended direction maps
// in SlIndirect instead of their SH (sl/probe_shadow.glsl).
layout(constant_id = 7) const bool kBlockedMap = false;

#include "frame.glsl"
#include "sh.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(set = 1, binding = 3) uniform sampler2D probeSh;       // RGBA32F (probes/probe_sh.glsl)
layout(set = 1, binding = 4) uniform sampler2D probeMoments;  // RG32F
layout(set = 1, binding = 5) uniform sampler2D aoTerm;  // "ao.term" (1 = unoccluded) when pc.bias.w = 1
layout(push_constant) uniform Push {
  vec4 originSpacing;
  ivec4 countOrder;
  vec4 bias;  // w: 1 = multiply by aoTerm, as the probes pass does
} pc;
#include "probes/probe_sh.glsl"
#define SL_SET 1
#define SL_BINDING 7  // binding 6: the tiles (sl/tiles.glsl)
#define SL_INDIRECT_BINDING 11  // binding 10: the hierarchy's τ (shadow_hierarchy_tiles.vert)
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/probe_shadow.glsl"
#include "sl/receiver.glsl"
#ifdef SL_HIERARCHY
#include "sl/hierarchy.glsl"
#include "sl/hierarchy_shadow.glsl"
#endif

layout(location = 0) flat in uvec4 inCandidates;
#ifdef SL_HIERARCHY
layout(location = 1) flat in vec4 inRatios[kSlHierObjects];  // the tile's τ per object (probe_shadow_ratio.comp)
#endif
layout(location = 0) out vec4 outRadiance;

const float kInvPi = 0.31830988618379067;

void main() {
  ivec2 pixel;
  vec3 x, n;
  if (!slReceiver(pixel, x, n)) {
    outRadiance = vec4(0.0);
    return;
  }
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  vec3 L[9];
  probeRadianceSh(x, n, normalize(camera.position.xyz - x), L);
  float ao = pc.bias.w > 0.5 ? texelFetch(aoTerm, pixel, 0).r : 1.0;
#ifdef SL_HIERARCHY
  // §7.3 for the shadow (sl/hierarchy_shadow.glsl): the cut SLs' ΔE plus each listed parent's share.
  vec3 delta = ao * slShadowHierarchyAt(x, n, L, inCandidates, inRatios, slProbeShadow(x, n, L, inCandidates));
#else
  vec3 delta = ao * slProbeShadow(x, n, L, inCandidates, kBlockedAtSphere, kBlockedMap);
#endif
  outRadiance = vec4(kStep > 1u ? delta : albedo * kInvPi * delta, 0.0);
}
