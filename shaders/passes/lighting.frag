#version 450
#extension GL_GOOGLE_include_directive : require
// Deferred direct lighting: Lambertian reflection of every punctual light plus emission.
//   L_o(x) = ρ(x)/π · Σ_i E_i(x) (n·l_i)₊ V_i(x) + L_e(x)          [radiance, linear HDR]
// where E_i is the light's irradiance at normal incidence (lights.glsl) and V_i its shadow term.
#include "frame.glsl"
#include "gbuffer.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gEmissive;
layout(set = 1, binding = 3) uniform sampler2D gDepth;
layout(set = 1, binding = 4) uniform sampler2DArrayShadow shadowAtlas;
#include "lights.glsl"
// Uniform blocks, not storage buffers (lights.glsl kMaxLights says why).
layout(std140, set = 1, binding = 5) uniform ShadowMatrices { mat4 shadowMatrices[kMaxShadowLayers]; };
#include "shadow.glsl"
layout(std140, set = 1, binding = 6) uniform Lights { Light lights[kMaxLights]; };

layout(push_constant) uniform Push {
  vec4 background;  // rgb radiance where nothing was drawn
  uint lightCount;
  uint shadowsOn;   // 0 when the level's effects do not name `shadows`
} pc;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outRadiance;

const float kInvPi = 0.31830988618379067;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) {
    outRadiance = vec4(pc.background.rgb, 1.0);
    return;
  }
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  vec3 n = texelFetch(gNormal, pixel, 0).xyz;
  vec3 p = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
  vec3 irradiance = vec3(0.0);
  // do-while, not for: llvmpipe tests "is any lane still looping" only at the end of an iteration,
  // so a loop whose test is at the top runs its body once more after the last light with every
  // lane masked — n + 1 bodies, shadow taps included, for n lights (one light: twice the work;
  // cornell-1, 1280×720: lighting / SSAO 0.38 → 0.26–0.28). The body therefore also runs once
  // when there is no light (lights[0] is bound: the block is kMaxLights long), and the guard keeps
  // it from adding anything, as it keeps a light behind the surface out (no `continue`: llvmpipe
  // runs both sides of a branch anyway).
  uint i = 0u;
  do {
    vec3 l;
    float dist;
    vec3 e = incidentIrradiance(lights[i], p, l, dist);
    float cosTheta = max(dot(n, l), 0.0);
    float v = pc.shadowsOn != 0u ? shadowVisibility(lights[i], p, n, dist) : 1.0;
    if (cosTheta > 0.0 && i < pc.lightCount) irradiance += e * cosTheta * v;
    ++i;
  } while (i < pc.lightCount);
  vec3 radiance = albedo * kInvPi * irradiance + texelFetch(gEmissive, pixel, 0).rgb;
  outRadiance = vec4(radiance, 1.0);
}
