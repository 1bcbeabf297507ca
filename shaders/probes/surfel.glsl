// One relit surfel as the GPU reads it (engine/gi/probes/relight.hpp Surfel, std430, 48 bytes): the
// layout relight.comp and SL's sl.relight_bounce.comp both bind.
#ifndef BOUNCE_PROBES_SURFEL_GLSL
#define BOUNCE_PROBES_SURFEL_GLSL
struct Surfel {
  vec4 position;  // xyz world (m)
  vec4 normal;    // xyz unit
  vec4 albedo;    // rgb
};
#endif
