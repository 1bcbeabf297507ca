#version 450
#extension GL_GOOGLE_include_directive : require
// The SL tiles (sl/tiles.glsl) for "sl" and "sl.upsample": tiles.hpp TilePush at offset 0.
#define SL_TILE_PUSH_OFFSET 0
#include "sl/tiles.glsl"
