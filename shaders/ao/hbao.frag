#version 450
#extension GL_GOOGLE_include_directive : require
// HBAO baseline (Bavoil, Sainz, Dimitrov 2008, "Image-Space Horizon-Based Ambient Occlusion"):
// along `directions` screen-space directions, march `samples` steps out to the projected
// `radius`, track the horizon elevation sin(h) = n·v̂ above the tangent plane (the G-buffer normal
// gives the tangent angle t directly, sin t = 0), and integrate
//   AO = 1 − 1/D Σ_dirs (sin h − sin t) W(r),   W(r) = 1 − r²/R²  (their attenuation, eq. 4–5).
#include "ao/ao_common.glsl"

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) { outAo = vec4(1.0); return; }
  vec2 uv = (vec2(pixel) + 0.5) * camera.resolution.zw;
  vec3 p = worldAt(uv, depth);
  vec3 n = normalize(texelFetch(gNormal, pixel, 0).xyz);
  // Screen radius of the world radius at this depth: R · proj[1][1] / z · height / 2 (pixels).
  float radiusPx = pc.radius * camera.proj[1][1] * abs(1.0 / max(viewDepth(p), 1e-6)) * 0.5 * camera.resolution.y;
  radiusPx = abs(radiusPx);
  if (radiusPx < 1.0) { outAo = vec4(1.0); return; }
  float jitter = ign(vec2(pixel));
  float occlusion = 0.0;
  // Both loops do-while, not for: llvmpipe tests "is any lane still looping" only at the end of an
  // iteration, so a top-tested loop runs one more body with every lane masked (n + 1 for n; README
  // "What costs what on lavapipe"). Each body therefore also runs once with a count of 0: the
  // step's `s > samples` exit and the direction's `liveD` keep those passes from adding.
  uint d = 0u;
  do {
    bool liveD = d < pc.directions;
    float angle = 6.2831853 * (float(d) + jitter) / float(pc.directions);
    vec2 dir = vec2(cos(angle), sin(angle));
    float sinH = pc.bias;  // the tangent plane (sin t = 0) plus the bias
    float contribution = 0.0;
    uint s = 1u;
    do {
      vec2 spx = vec2(pixel) + 0.5 + dir * radiusPx * (float(s) - 1.0 + jitter) / float(pc.samples);
      ivec2 sp = ivec2(spx);
      bool liveS = s <= pc.samples;
      ++s;  // before the `continue`s, which jump to the test
      if (!liveS || any(lessThan(sp, ivec2(0))) || any(greaterThanEqual(sp, ivec2(camera.resolution.xy)))) break;
      float sd = texelFetch(gDepth, sp, 0).r;
      if (sd >= 1.0) continue;
      vec3 v = worldAt((vec2(sp) + 0.5) * camera.resolution.zw, sd) - p;
      float r2 = dot(v, v);
      if (r2 > pc.radius * pc.radius || r2 < 1e-12) continue;
      float sinE = dot(n, v) * inversesqrt(r2);
      if (sinE > sinH) {
        contribution += (sinE - sinH) * (1.0 - r2 / (pc.radius * pc.radius));
        sinH = sinE;
      }
    } while (s <= pc.samples);
    if (liveD) occlusion += contribution;
    ++d;
  } while (d < pc.directions);
  outAo = vec4(clamp(1.0 - occlusion / float(max(pc.directions, 1u)), 0.0, 1.0));
}
