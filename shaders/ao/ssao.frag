#version 450
#extension GL_GOOGLE_include_directive : require
// SSAO baseline (paper §6.4): normal-oriented hemisphere kernel (Crytek's SSAO as refined by
// Chapman's normal-oriented version): `samples` points in the hemisphere around n within
// `radius`, each occluded when the depth buffer holds a surface in front of it, weighted by a
// range check so distant occluders do not count. Visibility = 1 − occluded fraction.
#include "ao/ao_common.glsl"

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(gDepth, pixel, 0).r;
  if (depth >= 1.0) { outAo = vec4(1.0); return; }
  vec2 uv = (vec2(pixel) + 0.5) * camera.resolution.zw;
  vec3 p = worldAt(uv, depth);
  vec3 n = normalize(texelFetch(gNormal, pixel, 0).xyz);
  // Tangent frame rotated per pixel.
  float a = 6.2831853 * ign(vec2(pixel));
  vec3 helper = abs(n.y) < 0.99 ? vec3(0, 1, 0) : vec3(1, 0, 0);
  vec3 t = normalize(cross(helper, n));
  vec3 b = cross(n, t);
  vec3 tr = cos(a) * t + sin(a) * b, br = cross(n, tr);
  float occluded = 0.0;
  // do-while, not for: llvmpipe tests "is any lane still looping" only at the end of an iteration,
  // so a top-tested loop runs one more body with every lane masked (17 bodies for 16 samples; README
  // "What costs what on lavapipe"). The body therefore also runs once with no sample, and `live`
  // keeps that pass from adding (no early exit: llvmpipe runs both sides of a branch anyway).
  uint i = 0u;
  do {
    bool live = i < pc.samples;
    // Fibonacci points on the hemisphere, scaled towards the centre (more weight close by).
    float fi = float(i) + 0.5;
    ++i;  // before the `continue`s, which jump to the test
    float z = 1.0 - fi / float(pc.samples);
    float r = sqrt(max(0.0, 1.0 - z * z));
    float phi = 2.39996323 * fi;
    float scale = mix(0.1, 1.0, (fi / float(pc.samples)) * (fi / float(pc.samples)));
    vec3 s = p + pc.radius * scale * (r * cos(phi) * tr + r * sin(phi) * br + z * n);
    vec4 clip = camera.viewProj * vec4(s, 1.0);
    if (!live || clip.w <= 0.0) continue;
    vec2 suv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(suv, vec2(0.0))) || any(greaterThan(suv, vec2(1.0)))) continue;
    float sceneDepth = texelFetch(gDepth, ivec2(suv * camera.resolution.xy), 0).r;
    if (sceneDepth >= 1.0) continue;
    float zScene = viewDepth(worldAt(suv, sceneDepth)), zSample = viewDepth(s);
    float range = smoothstep(0.0, 1.0, pc.radius / max(abs(viewDepth(p) - zScene), 1e-6));
    occluded += (zScene <= zSample - pc.bias ? 1.0 : 0.0) * range;
  } while (i < pc.samples);
  outAo = vec4(1.0 - occluded / float(max(pc.samples, 1u)));
}
