// Incident light: the level's real lights (point, spot, directional) projected analytically into
// order-3 RADIANCE SH (9 RGB coefficients, world axes, the convention of engine/math/sh_eval.hpp and
// sh.glsl: L(ω) = Σ L_i Y_i(ω), ω pointing towards the source) at a receiver. The GPU face of the
// incident-light service (engine/gi/incident); engine/gi/incident/incident.cpp compiles THIS file as
// C++ against glm (the CPU face), so both faces run the same code. Keep to the GLSL/C++ common
// subset of sh.glsl: f-suffixed literals, no swizzles, no array constructors, qualifiers only.
//
// The includer provides, before including this file:
//   GLSL: nothing — lights.glsl (Light, incidentIrradiance, kLight*) is included here;
//   C++:  #define BOUNCE_INCIDENT_HOST, then Light, kLightDirectional/Point/Spot and
//         vec3 incidentIrradiance(Light, vec3 p, out vec3 toLight, out float dist) (lights.glsl's
//         contract: irradiance on a surface facing the light, 1/d², range window, spot cone).
//
// Model (why a cap): a punctual light seen from a point is a delta, L(ω) = E δ(ω − ω_L) with E the
// irradiance on a surface facing it (W/m² per channel), whose SH are E·Y_i(ω_L). A receiver that is
// not a point — DNRT's object, a sphere of radius R around its centre o — sees the light from every
// direction within α of ω_L, sin α = R/d (d = |light − o|). We spread the light uniformly over that
// cap and give the cap the flux the sphere intercepts, I·Ω (Ω = 2π(1 − cos α) the cap's solid angle)
// instead of the centre's I/d² · πR²: E_cap = (I/d²)·2/(1 + cos α). A uniform cap of total
// irradiance-weight E about ω_L has SH E·s_l·Y_lm(ω_L), with per-band factors (zonal harmonics of a
// cap, rotated: Sloan 2008, "Stupid Spherical Harmonics Tricks", §Zonal harmonics)
//   s_0 = 1,  s_1 = (1 + cos α)/2,  s_2 = cos α (1 + cos α)/2
// (from ∫_{cos α}^{1} P_l(t) dt / (1 − cos α) with P_1 = t, P_2 = (3t² − 1)/2). So E_cap·s_1 = I/d²:
// the cap keeps the centre's band-1 (directional) term and adds the flux the near side of a large
// receiver catches. R → 0 gives the delta exactly (cos α = 1, s_l = 1). A light inside the sphere
// (d ≤ R) is treated as on it (cos α = 0, a hemisphere, E_cap = 2I/R²): bounded for every d ≥ 0.
// Lights have no radius in this engine (KHR_lights_punctual), so R is the receiver's alone.
#ifndef BOUNCE_INCIDENT_GLSL
#define BOUNCE_INCIDENT_GLSL

#include "sh.glsl"
#ifndef BOUNCE_INCIDENT_HOST
#include "lights.glsl"
#endif

// cos α of the cap of directions from which a sphere of radius `radius` around the receiver sees
// a point at distance `dist` (1 for a point receiver; 0 when the point is inside the sphere).
float incidentCapCosine(float radius, float dist) {
  if (!(radius > 0.0f)) return 1.0f;
  float s = min(radius / max(dist, 1e-30f), 1.0f);
  return sqrt(max(1.0f - s * s, 0.0f));
}

// Adds a uniform cap of half-angle α (cosAlpha = cos α ∈ [0, 1]) about unit direction toLight,
// carrying irradiance-weight e (∫_cap L dω, W/m² per channel), to the radiance SH sh.
void incidentAddCap(vec3 toLight, float cosAlpha, vec3 e, inout vec3 sh[9]) {
  float y[9];
  shEval9(toLight, y);
  float s1 = 0.5f * (1.0f + cosAlpha);
  float s2 = cosAlpha * s1;
  sh[0] += e * y[0];
  for (int i = 1; i < 4; ++i) sh[i] += e * (s1 * y[i]);
  for (int i = 4; i < 9; ++i) sh[i] += e * (s2 * y[i]);
}

// Directional light: a delta from −direction with its irradiance, times visibility ∈ [0, 1].
void incidentAddDirectional(Light light, float visibility, inout vec3 sh[9]) {
  vec3 toLight;
  float dist;
  vec3 e = incidentIrradiance(light, vec3(0.0f), toLight, dist);
  incidentAddCap(toLight, 1.0f, e * visibility, sh);
}

// Point light at receiver p (a sphere of `radius` metres; 0: a point), times visibility ∈ [0, 1]:
// the cap of the header, its flux from lights.glsl's I/d² and range window at the centre.
void incidentAddPoint(Light light, vec3 p, float radius, float visibility, inout vec3 sh[9]) {
  vec3 toLight;
  float dist;
  vec3 e = incidentIrradiance(light, p, toLight, dist);
  float r = max(radius, 0.0f);
  if (dist < r) e *= (dist * dist) / (r * r);  // a light inside the receiver counts as on it: I/R²
  float c = incidentCapCosine(r, dist);
  incidentAddCap(toLight, c, e * (visibility * 2.0f / (1.0f + c)), sh);
}

// Spot light: the point light's cap, scaled by lights.glsl's cone falloff towards the centre
// (incidentIrradiance applies it by the light's type).
void incidentAddSpot(Light light, vec3 p, float radius, float visibility, inout vec3 sh[9]) {
  incidentAddPoint(light, p, radius, visibility, sh);
}

// Any light, by its type (Light.positionType.w).
void incidentAddLight(Light light, vec3 p, float radius, float visibility, inout vec3 sh[9]) {
  uint type = uint(light.positionType.w + 0.5f);
  if (type == kLightDirectional) {
    incidentAddDirectional(light, visibility, sh);
  } else if (type == kLightSpot) {
    incidentAddSpot(light, p, radius, visibility, sh);
  } else {
    incidentAddPoint(light, p, radius, visibility, sh);
  }
}

#endif  // BOUNCE_INCIDENT_GLSL
