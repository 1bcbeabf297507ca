#version 450
#extension GL_GOOGLE_include_directive : require
// The SL tiles (sl/tiles.glsl) for "sl" with the §7.3 hierarchy: tiles.hpp TilePush at offset 0, and
// each tile's Eq. 25 ratios from binding 8 (engine/gi/sl/node.cpp kRatiosBinding).
#define SL_TILE_PUSH_OFFSET 0
#define SL_TILE_RATIOS 8
#include "sl/tiles.glsl"
