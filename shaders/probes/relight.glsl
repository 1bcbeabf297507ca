// Probes relit each frame (engine/gi/probes/relight.hpp): the light math of pass `probes.relight`,
// ONE copy: relight.comp includes it, and engine/gi/probes/relight.cpp compiles it as C++ (its CPU
// reference, used by the tests), as incident.glsl is. Keep to the GLSL/C++ common subset of sh.glsl
// (f-suffixed literals, no swizzles, LIGHTS_OUT for out parameters, in/out/inout qualifiers that the
// C++ includer defines away). The includer provides lights.glsl (Light, incidentIrradiance) and
// sh.glsl (shEval9) first.
//
// What is relit is the CHANGE the dynamic objects make to the baked probes (a delta, not the whole
// light: README "Probes relit each frame"). A surfel s (a patch of static surface: position p,
// unit normal n, albedo ρ) loses, per light,
//   ΔE_l = E_l(p) · max(n·ω_l, 0) · (min(V_now, V_static) − V_static)     (W/m², ≤ 0)
// with E_l lights.glsl's irradiance on a surface facing the light, V_now the shadow atlas's
// visibility (which holds the dynamic objects) and V_static the visibility through the static
// geometry alone (Embree, at the first frame): the part of the light that only a dynamic caster
// takes away. The room then bounces that loss: ΔE += the irradiance of the probes' own ΔSH at s
// (the previous iteration). A Lambertian surfel sends ΔL = ρ/π · ΔE (W/(m²·sr)). A probe's change
// is the baker's own Monte-Carlo projection with L replaced by ΔL of the surfel its ray hits:
//   ΔL_lm = 4π/R · Σ_dirs Y_lm(ω) ΔL(hit(ω))      (bake.hpp: L_lm = 4π/N Σ L(ω_i) Y_lm(ω_i)).
#ifndef BOUNCE_RELIGHT_GLSL
#define BOUNCE_RELIGHT_GLSL

// The irradiance one light's dynamic shadow takes from a surfel (≤ 0, W/m² per channel).
vec3 relightDirectLoss(Light light, vec3 p, vec3 n, float vNow, float vStatic) {
  vec3 toLight;
  float dist;
  vec3 e = incidentIrradiance(light, p, toLight, dist);
  float c = max(dot(n, toLight), 0.0f);
  return e * (c * (min(vNow, vStatic) - vStatic));
}

// Outgoing radiance of a Lambertian surfel of albedo ρ under irradiance E: ρ/π · E.
vec3 relightSurfelRadiance(vec3 albedo, vec3 e) { return albedo * (e * 0.31830988618379067f); }

// One ray of a probe's projection: sh += w · Y(ω) · L, w = 4π/R (the baker's sample weight).
void relightGatherAdd(vec3 dir, vec3 radiance, float w, inout vec3 sh[9]) {
  float y[9];
  shEval9(dir, y);
  for (int i = 0; i < 9; ++i) sh[i] += radiance * (w * y[i]);
}

#endif  // BOUNCE_RELIGHT_GLSL
