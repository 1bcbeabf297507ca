// SL local lights (§7.3; issue 13 item 4): the visible fraction v ∈ [0, 1] of a point or spot light
// of radius R through the SLs at one receiver — the GLSL port of engine/gi/sl/local_light.cpp's Cap
// form (whose header derives it), float instead of double: the SLs after the receiver rules
// (sl.glsl slAdjust), each blocker's covered fraction o_j of the light's cap (two spherical caps'
// intersection), log v = Σ_j w_j log(1 − o_j), w_j the closer-than-the-light and not-intersecting-it
// fades, the cap shrunk by the set's shadow scale and the log weighted by the object's union share.
// Needs sl.glsl (and what it needs) included first.
#ifndef BOUNCE_SL_LOCAL_LIGHT_GLSL
#define BOUNCE_SL_LOCAL_LIGHT_GLSL
#include "mask.glsl"

const float kSlLocalMinVisible = 1e-6;  // local_light.cpp kMinVisible
// Below this angular radius (rad) of the light the caps' lens is taken in the tangent plane: the
// spherical formula's 1 − cos a cancels in float there (~1e-3 relative at 0.02 rad), while the
// planar lens differs from it by O(a²).
const float kSlLocalPlanar = 0.02;

// local_light.hpp capOverlapFraction: the fraction of the light's cap (angular radius a) that a cap
// of angular radius b covers, centres c apart.
float slCapOverlap(float a, float b, float c) {
  if (!(b > 0.0) || c >= a + b) return 0.0;
  if (c <= b - a) return 1.0;
  if (a < kSlLocalPlanar) {
    if (c <= a - b) return (b * b) / (a * a);
    // Two discs of radii a, b, centres c apart: their lens over πa².
    float k = sqrt(max(0.0, (-c + a + b) * (c + a - b) * (c - a + b) * (c + a + b)));
    float lens = a * a * acos(clamp((c * c + a * a - b * b) / (2.0 * c * a), -1.0, 1.0)) +
                 b * b * acos(clamp((c * c + b * b - a * a) / (2.0 * c * b), -1.0, 1.0)) - 0.5 * k;
    return clamp(lens / (kSlPi * a * a), 0.0, 1.0);
  }
  float ca = cos(a), cb = cos(b), cc = cos(c), sa = sin(a), sb = sin(b), sc = sin(c);
  if (c <= a - b) return (1.0 - cb) / (1.0 - ca);
  float area = 2.0 * (kSlPi - acos(clamp((cc - ca * cb) / (sa * sb), -1.0, 1.0)) -
                      ca * acos(clamp((cb - cc * ca) / (sc * sa), -1.0, 1.0)) -
                      cb * acos(clamp((ca - cc * cb) / (sc * sb), -1.0, 1.0)));
  return clamp(area / (2.0 * kSlPi * (1.0 - ca)), 0.0, 1.0);
}

// Over the SLs whose bit is set in `candidates` (sl.glsl slIrradianceAt's convention); light at x,
// radius R (metres).
float slLocalVisibility(vec3 p, vec3 n, vec3 x, float R, uvec4 candidates) {
  vec3 toLight = x - p;
  float dx = length(toLight);
  if (!(dx > 0.0)) return 1.0;
  float a = asin(min(1.0, max(R, 0.0) / dx));
  float logV = 0.0;
  uint count = min(slCount(), kSpheres);
  uvec4 rest = candidates;
  do {
    uint i = maskPop(rest);
    if (i < count) {
      vec4 sp = slSphere(i);
      vec3 c = sp.xyz;
      float r = sp.w;
      bool kept = slAdjust(c, r, p, n);
      vec3 toC = c - p;
      float d = length(toC);
      if (kept && d > 0.0 && r > 0.0) {
        // local_light.cpp localBlockerWeight.
        float w = clamp((dx - d) / r, 0.0, 1.0) * clamp((length(c - x) - r - max(R, 0.0)) / r, 0.0, 1.0);
        // The cap shrunk to the set's shadow scale of its solid angle, the log weighted by the
        // object's union share (local_light.hpp "Fat and overlapping spheres").
        float sinB = min(1.0, r / d);
        float b = 2.0 * asin(sqrt(0.5 * slSilhouette(i) * sinB * sinB / (1.0 + sqrt(max(0.0, 1.0 - sinB * sinB)))));
        w *= slShare(i);
        float angle = atan(length(cross(toC, toLight)), dot(toC, toLight));  // accurate near 0, unlike acos
        if (w > 0.0) logV += w * log(max(1.0 - slCapOverlap(a, b, angle), kSlLocalMinVisible));
      }
    }
  } while (rest != uvec4(0u));
  return exp(logV);
}

// Over every SL (pass 1's samples and the self-test's receivers, which no tile list culls).
float slLocalVisibility(vec3 p, vec3 n, vec3 x, float R) {
  uvec4 all = uvec4(0u);
  uint count = min(slCount(), kSpheres);
  for (uint w = 0u; w < 4u; ++w) {
    uint bits = uint(clamp(int(count) - int(32u * w), 0, 32));
    all[w] = bits == 32u ? 0xffffffffu : (1u << bits) - 1u;
  }
  return slLocalVisibility(p, n, x, R, all);
}

#endif  // BOUNCE_SL_LOCAL_LIGHT_GLSL
