#version 450
#extension GL_GOOGLE_include_directive : require
// Pass "sl.local" (issue 13 item 4, the SL paper §7.3: the level's point and spot lights as SLs of
// their own radius), deferred: every G-buffer pixel of a tile some SL reaches adds
//   ρ(p)/π · Σ_lights −E_i(p) (n·l_i)₊ V_i(p) (1 − v_i(p))
// to "lighting.hdr" (additive blending into RGBA16F keeps the negative sum), where E_i (n·l_i)₊ V_i is
// the lighting pass's own term for light i (lights.glsl, shadow.glsl: the same functions) and v_i the
// SLs' visible fraction of the light's sphere (sl/local_light.glsl). The lighting pass drew the light
// with the shadow map alone, which no longer holds the SL objects for point and spot lights
// (DrawItem::slLocal), so after this pass the light is E·V·v: the objects' shadow counts once, soft.
// Directional lights are left alone (no position; their shadow map keeps the objects).
// Light i's radius is lights[i].radiance.w (scene::Light::radius).
layout(constant_id = 0) const uint kOrder = 4u;
layout(constant_id = 1) const bool kPerObject = false;
layout(constant_id = 2) const uint kSpheres = 64u;
layout(constant_id = 3) const float kInfluence = 0.0;

#include "frame.glsl"

layout(set = 0, binding = 0) uniform FrameUbo { Camera camera; };
layout(set = 1, binding = 0) uniform sampler2D gAlbedo;
layout(set = 1, binding = 1) uniform sampler2D gNormal;
layout(set = 1, binding = 2) uniform sampler2D gDepth;
layout(set = 1, binding = 3) uniform sampler2DArrayShadow shadowAtlas;
#include "lights.glsl"
layout(std140, set = 1, binding = 4) uniform ShadowMatrices { mat4 shadowMatrices[kMaxShadowLayers]; };
#include "shadow.glsl"
layout(std140, set = 1, binding = 5) uniform Lights { Light lights[kMaxLights]; };
layout(push_constant) uniform Push {
  uint lightCount;
  uint shadowsOn;  // as lighting.frag's
} pcLocal;
#define SL_SET 1
#define SL_BINDING 7  // binding 6: the tiles (sl/tiles.glsl)
#include "sl/sl_data.glsl"
#include "sl/sl.glsl"
#include "sl/local_light.glsl"

layout(location = 0) flat in uvec4 inCandidates;
layout(location = 0) out vec4 outRadiance;

const float kInvPi = 0.31830988618379067;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) {
    outRadiance = vec4(0.0);
    return;
  }
  vec3 albedo = texelFetch(gAlbedo, pixel, 0).rgb;
  vec3 n = texelFetch(gNormal, pixel, 0).xyz;
  vec3 p = worldFromDepth(camera.invViewProj, (vec2(pixel) + 0.5) * camera.resolution.zw, depth);
  vec3 delta = vec3(0.0);
  // do…while as lighting.frag's loop (README "Loop bodies"): guarded, lights[0] is always bound.
  uint i = 0u;
  do {
    vec3 l;
    float dist;
    vec3 e = incidentIrradiance(lights[i], p, l, dist);
    float cosTheta = max(dot(n, l), 0.0);
    bool local = uint(lights[i].positionType.w + 0.5) != kLightDirectional;
    if (cosTheta > 0.0 && local && i < pcLocal.lightCount) {
      float v = pcLocal.shadowsOn != 0u ? shadowVisibility(lights[i], p, n, dist) : 1.0;
      float seen = slLocalVisibility(p, n, lights[i].positionType.xyz, lights[i].radiance.w, inCandidates);
      delta -= e * cosTheta * v * (1.0 - seen);
    }
    ++i;
  } while (i < pcLocal.lightCount);
  outRadiance = vec4(albedo * kInvPi * delta, 0.0);
}
