#version 450
#extension GL_GOOGLE_include_directive : require
// The SL tiles (sl/tiles.glsl) for "sl.local": its push block starts with local_light.frag's 16
// bytes (light count, shadows on, 2 pad), then tiles.hpp TilePush.
#define SL_TILE_PUSH_OFFSET 16
#include "sl/tiles.glsl"
