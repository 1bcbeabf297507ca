#version 450
#extension GL_GOOGLE_include_directive : require
// VLM phase 1 (thesis §3.3, Fig. 3.4 top): the radiance every virtual light emits this frame.
// One fragment per light (texel i = light i, row-major in a `width`-wide target); one draw per
// range [first, first + count) of lights (the static VLMs, then each dynamic VLM under its own
// timestamp scope), texels outside the range keep what the clear or another draw wrote:
//   E   = 1/S Σ_s Σ_i E_i(p_s) (n_l·l_i)₊ V_i(p_s)       [W/m²; S = 4 points of the triangle]
//   L   = scale · E / π,  scale = reflectance × colour × intensity     [W/(m²·sr)]
// with E_i the real light's irradiance at normal incidence (lights.glsl, the lighting pass's own
// model) and V_i its shadow-atlas visibility (shadow.glsl) at the point lifted `lift` metres along
// the light's normal: virtual geometry sits just behind the real surface (§3.4, Fig. 3.5), which
// would otherwise shadow it.
#include "lights.glsl"
#include "vlm/vlm_common.glsl"

layout(std430, set = 0, binding = 0) readonly buffer VlmLights { VlmLight vlmLights[]; };
layout(set = 0, binding = 1) uniform sampler2DArrayShadow shadowAtlas;
layout(std430, set = 0, binding = 2) readonly buffer ShadowMatrices { mat4 shadowMatrices[]; };
#include "shadow.glsl"
layout(std430, set = 0, binding = 3) readonly buffer Lights { Light lights[]; };

layout(push_constant) uniform Push {
  uint count;       // virtual lights this draw lights
  uint width;       // texels per row of the target
  uint lightCount;  // real lights
  uint shadowsOn;   // 0: no shadow atlas this frame
  float lift;       // metres
  uint first;       // the first virtual light this draw lights
} pc;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outRadiance;

const float kInvPi = 0.31830988618379067;

void main() {
  uint index = uint(gl_FragCoord.y) * pc.width + uint(gl_FragCoord.x);
  if (index < pc.first || index - pc.first >= pc.count) discard;
  VlmLight vl = vlmLights[index];
  vec3 ln = cross(vl.v1.xyz - vl.v0.xyz, vl.v2.xyz - vl.v0.xyz);
  float len = length(ln);
  if (!(len > 0.0)) {
    outRadiance = vec4(0.0);
    return;
  }
  ln /= len;
  vec3 e = vec3(0.0);
  for (int s = 0; s < VLM_PHASE1_SAMPLES; ++s) {
    vec3 p = vlmSamplePoint(vl, s) + ln * pc.lift;
    // do-while, not for (as lighting.frag's light loop): llvmpipe would run n + 1 light bodies,
    // shadow taps included, for n lights; the guard keeps the pass with no light from adding.
    uint i = 0u;
    do {
      vec3 l;
      float dist;
      vec3 ei = incidentIrradiance(lights[i], p, l, dist);
      float c = max(dot(ln, l), 0.0);
      float v = pc.shadowsOn != 0u ? shadowVisibility(lights[i], p, ln, dist) : 1.0;
      if (c > 0.0 && i < pc.lightCount) e += ei * c * v;
      ++i;
    } while (i < pc.lightCount);
  }
  e /= float(VLM_PHASE1_SAMPLES);
  outRadiance = vec4(vl.scale.rgb * e * kInvPi, 1.0);
}
