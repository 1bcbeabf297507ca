#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// The ξ pass (rtf/xi.glsl) with each slot's range reduced over the subgroup before its atomicMax (XiPass picks
// it where the device's compute stage has subgroup arithmetic; xi.comp elsewhere).
#define RTF_XI_SUBGROUP_MAX
#include "rtf/xi.glsl"
