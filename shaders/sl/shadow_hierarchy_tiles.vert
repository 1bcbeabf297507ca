#version 450
#extension GL_GOOGLE_include_directive : require
// The SL tiles (sl/tiles.glsl) for "sl.shadow" with the §7.3 hierarchy: shadow_tiles.vert's push
// layout, and each tile's τ from binding 10 (engine/gi/sl/probe_shadow_pass.cpp kRatiosBinding).
#define SL_TILE_PUSH_OFFSET 48
#define SL_TILE_RATIOS 10
#include "sl/tiles.glsl"
