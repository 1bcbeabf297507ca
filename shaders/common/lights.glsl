// Punctual lights and their shadow lookups (set 1 of the lighting and debug passes).
// Conventions (README "Level format"): lights point down local -Z; point/spot `intensity` is radiant
// intensity I (irradiance I·cosθ/d²), directional `intensity` is irradiance E on a surface facing it.
//
// The light math below (rangeWindow, cubeFace, incidentIrradiance) is the ONE copy: it is compiled
// as C++ against glm too — by engine/gi/incident/incident.cpp (the techniques' CPU face, with
// incident.glsl) and engine/ref/scene_bvh.cpp (the path tracer) — so keep it to the GLSL/C++
// common subset of sh.glsl: f-suffixed literals, no swizzles (vec3(v4) instead of v4.xyz), and
// LIGHTS_OUT(T) for an out parameter. A C++ includer defines BOUNCE_LIGHTS_HOST, a Light type with
// these members and LIGHTS_OUT(T) as T&; the kLight* constants and functions come from here.
#ifndef BOUNCE_LIGHTS_GLSL
#define BOUNCE_LIGHTS_GLSL

const uint kLightDirectional = 0u;  // render::LightType (gpu_types.hpp; incident.cpp checks)
const uint kLightPoint = 1u;
const uint kLightSpot = 2u;

#ifndef BOUNCE_LIGHTS_HOST
#define LIGHTS_OUT(T) out T

// Capacity of the lighting pass's uniform blocks (engine/render/gpu_types.hpp kMaxLights,
// kMaxShadowLayers): lights and shadow matrices are read from UBOs there, which llvmpipe reads
// without the per-lane bounds-checked loads of storage buffers.
const uint kMaxLights = 128u;
const uint kMaxShadowLayers = 192u;

struct Light {
  vec4 positionType;    // xyz world position (point, spot), w type
  vec4 directionRange;  // xyz unit direction the light travels (directional, spot), w range (0 = none)
  vec4 radiance;        // rgb colour × intensity, w radius (metres; scene::Light::radius, SL local lights)
  vec4 cone;            // x cos(outer cone), y cos(inner cone) (spot)
  vec4 shadow;          // x first atlas layer (< 0: no shadow), y texel size per metre of distance,
                        // z texel size constant (metres; directional), w depth bias (NDC units)
};
#endif  // BOUNCE_LIGHTS_HOST

// glTF KHR_lights_punctual range window: smooth to zero at `range`, no effect when range == 0.
float rangeWindow(float d, float range) {
  if (range <= 0.0f) return 1.0f;
  float r = d / range;
  float w = clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
  return w * w;
}

// Cube face of direction v, in the order the C++ side builds the face matrices: +X -X +Y -Y +Z -Z.
uint cubeFace(vec3 v) {
  vec3 a = abs(v);
  if (a.x >= a.y && a.x >= a.z) return v.x > 0.0f ? 0u : 1u;
  if (a.y >= a.z) return v.y > 0.0f ? 2u : 3u;
  return v.z > 0.0f ? 4u : 5u;
}

// Irradiance direction and magnitude at p (before the cosine and shadow): returns E·colour for a
// surface facing the light and writes the unit direction towards the light and the distance.
vec3 incidentIrradiance(Light light, vec3 p, LIGHTS_OUT(vec3) toLight, LIGHTS_OUT(float) dist) {
  uint type = uint(light.positionType.w + 0.5f);
  if (type == kLightDirectional) {
    toLight = -vec3(light.directionRange);
    dist = 1e30f;
    return vec3(light.radiance);
  }
  vec3 v = vec3(light.positionType) - p;
  float d2 = max(dot(v, v), 1e-12f);  // receivers on the light itself stay finite
  dist = sqrt(d2);
  toLight = v / dist;
  vec3 e = vec3(light.radiance) / d2 * rangeWindow(dist, light.directionRange.w);
  if (type == kLightSpot) {
    float cd = dot(-toLight, vec3(light.directionRange));
    float t = clamp((cd - light.cone.x) / max(light.cone.y - light.cone.x, 1e-4f), 0.0f, 1.0f);
    e *= t * t;
  }
  return e;
}

#endif
