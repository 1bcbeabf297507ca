// Punctual lights and their shadow lookups (set 1 of the lighting and debug passes).
// Conventions (README "Level format"): lights point down local -Z; point/spot `intensity` is radiant
// intensity I (irradiance I·cosθ/d²), directional `intensity` is irradiance E on a surface facing it.
#ifndef BOUNCE_LIGHTS_GLSL
#define BOUNCE_LIGHTS_GLSL

// Capacity of the lighting pass's uniform blocks (engine/render/gpu_types.hpp kMaxLights,
// kMaxShadowLayers): lights and shadow matrices are read from UBOs there, which llvmpipe reads
// without the per-lane bounds-checked loads of storage buffers.
const uint kMaxLights = 128u;
const uint kMaxShadowLayers = 192u;

const uint kLightDirectional = 0u;
const uint kLightPoint = 1u;
const uint kLightSpot = 2u;

struct Light {
  vec4 positionType;    // xyz world position (point, spot), w type
  vec4 directionRange;  // xyz unit direction the light travels (directional, spot), w range (0 = none)
  vec4 radiance;        // rgb colour × intensity, w unused
  vec4 cone;            // x cos(outer cone), y cos(inner cone) (spot)
  vec4 shadow;          // x first atlas layer (< 0: no shadow), y texel size per metre of distance,
                        // z texel size constant (metres; directional), w depth bias (NDC units)
};

// glTF KHR_lights_punctual range window: smooth to zero at `range`, no effect when range == 0.
float rangeWindow(float d, float range) {
  if (range <= 0.0) return 1.0;
  float r = d / range;
  float w = clamp(1.0 - r * r * r * r, 0.0, 1.0);
  return w * w;
}

// Cube face of direction v, in the order the C++ side builds the face matrices: +X -X +Y -Y +Z -Z.
uint cubeFace(vec3 v) {
  vec3 a = abs(v);
  if (a.x >= a.y && a.x >= a.z) return v.x > 0.0 ? 0u : 1u;
  if (a.y >= a.z) return v.y > 0.0 ? 2u : 3u;
  return v.z > 0.0 ? 4u : 5u;
}

// Irradiance direction and magnitude at p (before the cosine and shadow): returns E·colour for a
// surface facing the light and writes the unit direction towards the light and the distance.
vec3 incidentIrradiance(Light light, vec3 p, out vec3 toLight, out float dist) {
  uint type = uint(light.positionType.w + 0.5);
  if (type == kLightDirectional) {
    toLight = -light.directionRange.xyz;
    dist = 1e30;
    return light.radiance.rgb;
  }
  vec3 v = light.positionType.xyz - p;
  float d2 = max(dot(v, v), 1e-12);  // receivers on the light itself stay finite
  dist = sqrt(d2);
  toLight = v / dist;
  vec3 e = light.radiance.rgb / d2 * rangeWindow(dist, light.directionRange.w);
  if (type == kLightSpot) {
    float cd = dot(-toLight, light.directionRange.xyz);
    float t = clamp((cd - light.cone.x) / max(light.cone.y - light.cone.x, 1e-4), 0.0, 1.0);
    e *= t * t;
  }
  return e;
}

#endif
