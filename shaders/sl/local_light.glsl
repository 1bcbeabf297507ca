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
// radius R (metres). Two loops, as sl.glsl's: llvmpipe runs both sides of a branch but leaves a loop
// once none of its 8 lanes is in it (DESIGN.md), so the first, cheap loop keeps only the blockers
// whose cap meets the light's (c < a + b ⇔ cos c > cos(a + b), a, b ≤ π/2: dot products), and the
// trig runs in the second over those alone — most candidates are not between a pixel and the light.
float slLocalVisibility(vec3 p, vec3 n, vec3 x, float R, uvec4 candidates) {
  vec3 toLight = x - p;
  float dx = length(toLight);
  if (!(dx > 0.0)) return 1.0;
  float sinA = min(1.0, max(R, 0.0) / dx);
  float cosA = sqrt(max(0.0, 1.0 - sinA * sinA));
  // Per kept blocker: (1 − cos b')/2 of its shrunk cap, cos c, sin c, its log's weight u·w.
  vec4 live[kSpheres];
  uint count = 0u;
  uint total = min(slCount(), kSpheres);
  uvec4 rest = candidates;
  do {
    uint i = maskPop(rest);
    if (i < total) {
      vec4 cr;
      float d;
      bool seen = slSeenFrom(i, p, n, cr, d);
      vec3 c = cr.xyz;
      float r = cr.w;
      vec3 toC = c - p;
      if (seen && r > 0.0) {
        // local_light.cpp localBlockerWeight.
        float w = clamp((dx - d) / r, 0.0, 1.0) * clamp((length(c - x) - r - max(R, 0.0)) / r, 0.0, 1.0);
        float sinB = min(1.0, r / d);
        float cosB = sqrt(max(0.0, 1.0 - sinB * sinB));
        float cosC = dot(toC, toLight) / (d * dx);
        if (w > 0.0 && cosC > cosA * cosB - sinA * sinB) {
          // The cap shrunk to the set's shadow scale of its solid angle (1 − cos b' = s (1 − cos b),
          // with 1 − cos b = sin²b/(1 + cos b) for small caps), the log weighted by the object's
          // union share (local_light.hpp "Fat and overlapping spheres").
          live[count] = vec4(0.5 * slSilhouette(i) * sinB * sinB / (1.0 + cosB), cosC,
                             length(cross(toC, toLight)) / (d * dx), slShare(i) * w);
          ++count;
        }
      }
    }
  } while (rest != uvec4(0u));
  float a = asin(sinA);
  float logV = 0.0;
  uint k = 0u;
  do {
    if (k < count) {
      vec4 e = live[k];
      float b = 2.0 * asin(sqrt(e.x));
      float angle = atan(e.z, e.y);  // accurate near 0, unlike acos
      logV += e.w * log(max(1.0 - slCapOverlap(a, b, angle), kSlLocalMinVisible));
    }
    ++k;
  } while (k < count);
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
