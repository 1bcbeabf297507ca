#version 450
// Pass `sl.relight_bounce` (engine/gi/sl/node.cpp; level `"probes": {"sl_bounce": true}`): the
// irradiance the posed SLs send each of relight's surfels (engine/gi/probes/relight.hpp), E_SL(s) =
// slIrradianceAt(p_s, n_s) — Eq. 14, the same sl.glsl function pass 2 evaluates per pixel, with pass
// 1's intensities, the SLs' own blocking and pass 2's cut (kInfluence: the room carries on the first
// bounce pass 2 shows; engine/gi/sl/node.cpp enableRelightBounce says why). `probes.relight` adds it to the
// surfels' ΔE (relight.comp surfelStage), so the room's bounce iterations carry the prop's bounce on:
// the probes hold its 2nd+ bounces, the 1st stays pass 2's at the receiver (README "SL's bounce in
// relight's transport, session 15").
// Bindings 0–2: sl_data.glsl; 3: relight's surfels (relight.comp's Surfel); 4: E_SL per surfel.
// One invocation per surfel; push constant: the surfel count.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;

#define SL_SET 0
#define SL_BINDING 0
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"

#include "probes/surfel.glsl"
layout(std430, binding = 3) readonly buffer Surfels { Surfel surfels[]; };
layout(std430, binding = 4) writeonly buffer SlBounce { vec4 slBounce[]; };  // E_SL rgb (W/m²)

layout(push_constant) uniform Push { uvec4 sizes; } pc;  // x: surfels

void main() {
  uint s = gl_GlobalInvocationID.x;
  if (s >= pc.sizes.x) return;
  slBounce[s] = vec4(slIrradianceAt(surfels[s].position.xyz, surfels[s].normal.xyz), 0.0);
}
