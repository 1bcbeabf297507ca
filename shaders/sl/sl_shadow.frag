#version 450
#extension GL_GOOGLE_include_directive : require
// Passes "sl" and "sl.shadow" in one (issue 13 pass 2, README "SL: one walk for sl and sl.shadow"),
// drawn when both run and the §7.3 hierarchy is off: the two walk the same tiles and the same
// candidates, so each pixel walks its tile's candidates once (sl.glsl slWalk: the receiver rules)
// and both terms read that live list — E(p) (sl.glsl slIrradianceLive, sl_frag.glsl's term) and the
// shadow on the probes' light ΔE(p) (probe_shadow.glsl slProbeShadowLive, probe_shadow_frag.glsl's
// term). Each term is the same floats as its own pass computes; the output is their sum, blended
// once (additive) where the two passes blend twice: the images differ by RGBA16F rounding only.
// Full resolution: ρ/π · E + ρ/π · ao · ΔE added to "lighting.hdr"; half or quarter (kStep 2, 4):
// pixel j of "sl.half" / "sl.quarter" takes G-buffer pixel kStep·j and writes E + ao · ΔE
// ("sl.upsample" applies ρ/π).
// Bindings and push block are sl.shadow's (probe_shadow_frag.glsl, sl/shadow_tiles.vert);
// specialization: sl.glsl's ids 0–3, kCoeffs (4), kStep (5), kTerms (6), kSingleObject (7, sl_frag.glsl's),
// kBlockedAtSphere (8), kBlockedMap (9).
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;
layout(constant_id = 4) const int kCoeffs = 9;  // the probes' order²: 4 or 9
layout(constant_id = 5) const uint kStep = 1u;  // G-buffer pixels per sample per axis: 1, 2, 4
// Which terms are added (bit 0 E, bit 1 ΔE): 3 always but in `bounce accuracy`'s decomposition rows
// (scene::Sl::terms); a constant, so the shipped pipeline is the same code.
layout(constant_id = 6) const uint kTerms = 3u;
layout(constant_id = 7) const bool kSingleObject = false;  // per-object: tiles whose SLs are one object's
#define SL_SINGLE_OBJECT kSingleObject
layout(constant_id = 8) const bool kBlockedAtSphere = false;  // probe_shadow_frag.glsl's (constant_id 6 there)
layout(constant_id = 9) const bool kBlockedMap = false;       // probe_shadow_frag.glsl's (constant_id 7 there)

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
#define SL_INDIRECT_BINDING 11  // probe_shadow_frag.glsl's
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/probe_shadow.glsl"
#include "sl/receiver.glsl"

layout(location = 0) flat in uvec4 inCandidates;
layout(location = 0) out vec4 outRadiance;

const float kInvPi = 0.31830988618379067;

void main() {
  ivec2 pixel;
  vec3 p, n;
  if (!slReceiver(pixel, p, n)) {
    outRadiance = vec4(0.0);
    return;
  }
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  // One walk; slIrradianceLive leaves slLive / slDist / slAdjusted as it found them.
  uint alive = slWalk(p, n, inCandidates, min(slCount(), kSpheres));
  vec3 e = (kTerms & 1u) != 0u ? max(slIrradianceLive(p, n, alive), vec3(0.0)) : vec3(0.0);
  vec3 L[9];
  probeRadianceSh(p, n, normalize(camera.position.xyz - p), L);
  float ao = pc.bias.w > 0.5 ? texelFetch(aoTerm, pixel, 0).r : 1.0;
  vec3 delta = (kTerms & 2u) != 0u ? ao * slProbeShadowLive(p, n, L, alive, kBlockedAtSphere, kBlockedMap) : vec3(0.0);
  // Each pass's own output, then summed (fp32): the terms as the two passes write them.
  outRadiance = vec4(kStep > 1u ? e + delta : albedo * kInvPi * e + albedo * kInvPi * delta, 0.0);
}
