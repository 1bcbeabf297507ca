#version 450
#extension GL_GOOGLE_include_directive : require
// The SL tiles (sl/tiles.glsl) for "sl.shadow" and for "sl" and "sl.shadow" in one walk
// (sl_shadow.frag), without the hierarchy: each tile's list cut by its receivers' world box
// (tiles.glsl slCutTile), as cut_tiles.vert does for "sl". Exact for both terms: ΔE
// (probe_shadow.glsl slProbeShadowLive) and E (sl.glsl slIrradianceLive) sum over the live SLs that
// sl.glsl slWalk keeps, and rule 0 drops from that walk every SL the cut drops (tile_cut.glsl); the
// Ratio form's sums (X_j, u_o X_j, the blocked light at the spheres) run over the same live list.
// Push block: probe_sh.glsl's 48 bytes (probes::ProbePush), then tiles.hpp TilePush. Set 1 and the
// specialization constants are probe_shadow.frag's / sl_shadow.frag's (engine/gi/sl/probe_shadow_pass.cpp).
layout(constant_id = 3) const float kInfluence = 0.0;
layout(constant_id = 5) const uint kStep = 1u;

#include "frame.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 2) uniform sampler2D gDepth;
#define SL_SET 1
#define SL_BINDING 7
#include "sl/sl_data.glsl"

#define SL_TILE_PUSH_OFFSET 48
#define SL_TILE_CUT
#include "sl/tiles.glsl"
