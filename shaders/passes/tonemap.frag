#version 450
#extension GL_GOOGLE_include_directive : require
// HDR radiance → display: exposure (a linear scale, 2^EV), Khronos PBR Neutral tone mapping, then
// the sRGB transfer function by hand into an RGBA8 UNORM target (see color.glsl for why).
#include "color.glsl"

layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(push_constant) uniform Push { float exposure; } pc;
layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 c = texelFetch(hdr, ivec2(gl_FragCoord.xy), 0).rgb * pc.exposure;
  outColor = vec4(linearToSrgb(pbrNeutralTonemap(max(c, vec3(0.0)))), 1.0);
}
