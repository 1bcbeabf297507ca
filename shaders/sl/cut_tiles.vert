#version 450
#extension GL_GOOGLE_include_directive : require
// The SL tiles (sl/tiles.glsl) for "sl" without the hierarchy: tiles.hpp TilePush at offset 0, each
// tile's list cut by its receivers' world box (tiles.glsl slCutTile). sl.frag's set 1 and the
// specialization constants it shares with sl.frag (engine/gi/sl/node.cpp).
layout(constant_id = 3) const float kInfluence = 0.0;
layout(constant_id = 4) const uint kStep = 1u;

#include "frame.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 2) uniform sampler2D gDepth;
#define SL_SET 1
#define SL_BINDING 3
#include "sl/sl_data.glsl"

#define SL_TILE_PUSH_OFFSET 0
#define SL_TILE_CUT
#include "sl/tiles.glsl"
