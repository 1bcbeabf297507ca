#version 450
#extension GL_GOOGLE_include_directive : require
// SL pass 2 with the two-level hierarchy (§7.3 Eq. 26, sl/hierarchy.glsl): sl.frag's body plus each
// listed parent's term, the tile's t from the vertex shader (hierarchy_tiles.vert).
#define SL_HIERARCHY
#include "sl/sl_frag.glsl"
