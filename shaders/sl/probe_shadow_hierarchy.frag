#version 450
#extension GL_GOOGLE_include_directive : require
// "sl.shadow" with the two-level hierarchy (sl/hierarchy_shadow.glsl): probe_shadow.frag's body plus
// each listed parent's ΔE share, the tile's τ from shadow_hierarchy_tiles.vert.
#define SL_HIERARCHY
#include "sl/probe_shadow_frag.glsl"
