#version 450
#extension GL_GOOGLE_include_directive : require
// The SL tiles (sl/tiles.glsl) for "sl.shadow" uncut (scene::Sl::tileCut false; shadow_cut_tiles.vert
// draws the shipped passes): its push block starts with probe_sh.glsl's 48 bytes
// (probes::ProbePush, read by the fragment shader), then tiles.hpp TilePush.
#define SL_TILE_PUSH_OFFSET 48
#include "sl/tiles.glsl"
