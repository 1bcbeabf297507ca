#version 450
#extension GL_GOOGLE_include_directive : require
// The ξ pass (rtf/xi.glsl) with one atomicMax a lane for each slot's range: for devices whose compute stage
// lacks subgroup arithmetic (XiPass picks xi_subgroup.comp where it has it).
#include "rtf/xi.glsl"
