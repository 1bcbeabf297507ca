// RTF field lookup (Pan et al. 2007, Eq. 10), what engine/gi/rtf/evaluate.cpp lookup() /
// interreflection() / occlusion() compute (tests/unit/rtf/lookup_gpu_test.cpp checks it): the 8
// samples around q (local offset from the bounding-sphere centre in units of η) — bilinear between
// the texel centres of the cube face q's direction falls on (clamped to that face), linear between
// the two spheres bracketing |q|, the innermost sphere inside it, beyond the outermost (r_N/|q|)² to
// a linear ramp to zero over the last quarter of one sphere spacing (evaluate.hpp kFadeRamp). Fields are read from 2D-array textures with a LINEAR sampler
// (the bilinear part; two taps per coefficient, rtfTaps):
//   ξ:   rgba32f, layer sphere·16 + i, texel (face·n_r + x, y)   (xi.comp)
//   OOF: rgba32f, layer sphere·4 + i/4, texel (face·n_r + x, y), component i%4 (xi_pass.cpp)

struct RtfGrid {
  int spheres;
  int faceSize;
  float innerRadius;  // units of η
  float outerRadius;
};

const float kRtfUnitVisibility = 3.5449077;  // 4π·Y_00 = 2√π: the SH of V ≡ 1
const float kRtfFadeRamp = 0.25;             // evaluate.hpp kFadeRamp: the end's ramp, share of a spacing

// evaluate.cpp tailFade: the radial factor beyond the outermost sphere r_N (1 inside it),
// (r_N/r)² (the object's solid angle) · clamp((end − r)/(kRtfFadeRamp·Δr), 0, 1), end = `reach` when
// it is > 0 (a record's reach is 0 unless the tail passes r_N + Δr: update.cpp packObject), else
// r_N + Δr. Radii in η; invDr = 1/Δr (rtf.frag's record holds it).
float rtfTailFade(float rN, float invDr, float r, float reach) {
  if (r <= rN) return 1.0;
  float end = reach > 0.0 ? reach : rN + 1.0 / invDr;
  return (rN * rN) / (r * r) * clamp((end - r) * invDr / kRtfFadeRamp, 0.0, 1.0);
}

float rtfSphereRadius(RtfGrid g, int s) { return g.innerRadius + (g.outerRadius - g.innerRadius) * float(s) / float(g.spheres - 1); }

// Between spheres ra < rb, the weight of rb at |q| = r: linear in 1/r² (evaluate.cpp radialWeight,
// where the departure from Eq. 10's linear weight is explained).
float rtfRadialWeight(float ra, float rb, float r) {
  float r2 = max(r * r, ra * ra), a2 = ra * ra, b2 = rb * rb;
  return clamp((r2 - a2) * b2 / (r2 * (b2 - a2)), 0.0, 1.0);
}

// Cube face and clamped continuous texel coordinates of direction d (sh::cubeTexelDirection's inverse).
void rtfFace(vec3 d, int size, out int face, out vec2 f) {
  vec3 a = abs(d);
  float u = 0.0, v = 0.0;
  face = 0;
  if (a.x >= a.y && a.x >= a.z && a.x > 0.0) {
    face = d.x > 0.0 ? 0 : 1;
    u = d.x > 0.0 ? -d.z / a.x : d.z / a.x;
    v = -d.y / a.x;
  } else if (a.y >= a.z && (a.y > 0.0 || a.z > 0.0)) {
    face = d.y > 0.0 ? 2 : 3;
    u = d.x / a.y;
    v = d.y > 0.0 ? d.z / a.y : -d.z / a.y;
  } else if (a.z > 0.0) {
    face = d.z > 0.0 ? 4 : 5;
    u = d.z > 0.0 ? d.x / a.z : -d.x / a.z;
    v = -d.y / a.z;
  }
  f = clamp((vec2(u, v) + 1.0) * 0.5 * float(size) - 0.5, vec2(0.0), vec2(float(size - 1)));
}

// Eq. 10's trilinear weights as two filtered taps: the bilinear part between the texel centres of
// the face is the sampler's (linear filter, coordinates clamped to that face's outer texel centres,
// so a tap never reaches into the neighbouring face), the radial part is done here: sphere s0 with
// weight w0, s1 with w1 (both × the fade beyond the outermost sphere). Four texelFetch per tap
// cost llvmpipe about 4× one filtered fetch (DESIGN.md "What costs what in a fragment shader").
// The sampler's sub-texel precision (Vulkan: ≥ 4 bits; lavapipe: 8) bounds the difference from the
// C++ weights (lookup_gpu_test.cpp).
void rtfTaps(RtfGrid g, vec3 q, out vec2 uv, out int s0, out int s1, out float w0, out float w1) {
  float r = length(q);
  float r0 = rtfSphereRadius(g, 0), rN = rtfSphereRadius(g, g.spheres - 1);
  float dr = (g.outerRadius - g.innerRadius) / float(g.spheres - 1);
  float t1 = 0.0, fade = 1.0;
  if (r <= r0) {
    s0 = 0; s1 = 0;
  } else if (r >= rN) {
    s0 = g.spheres - 1; s1 = s0;
    fade = rtfTailFade(rN, 1.0 / dr, r, 0.0);  // no tail: the end at r_N + Δr
  } else {
    float t = (r - g.innerRadius) / dr;
    s0 = min(int(floor(t)), g.spheres - 2);
    s1 = s0 + 1;
    t1 = rtfRadialWeight(rtfSphereRadius(g, s0), rtfSphereRadius(g, s1), r);
  }
  w0 = (1.0 - t1) * fade;
  w1 = t1 * fade;
  int face;
  vec2 f;
  rtfFace(r > 0.0 ? q / r : vec3(0.0), g.faceSize, face, f);
  uv = vec2((float(face * g.faceSize) + f.x + 0.5) / float(6 * g.faceSize), (f.y + 0.5) / float(g.faceSize));
}

// ξ at q: the object's interreflected radiance SH (the first `count` of 16 RGB coefficients, the
// object's frame; the shading pass needs 9: the clamped cosine has Â_3 = 0). `xi` needs a linear sampler.
void rtfInterreflection(sampler2DArray xi, RtfGrid g, vec3 q, int count, out vec3 L[16]) {
  vec2 uv;
  int s0, s1;
  float w0, w1;
  rtfTaps(g, q, uv, s0, s1, w0, w1);
  for (int i = 0; i < 16; ++i) L[i] = vec3(0.0);
  for (int i = 0; i < count; ++i) {
    if (w0 != 0.0) L[i] += w0 * texture(xi, vec3(uv, float(s0 * 16 + i))).rgb;
    if (w1 != 0.0) L[i] += w1 * texture(xi, vec3(uv, float(s1 * 16 + i))).rgb;
  }
}

// The OOF at q, faded to unoccluded beyond the field (16 floats, the object's frame). Linear sampler.
void rtfOcclusion(sampler2DArray oof, RtfGrid g, vec3 q, out float V[16]) {
  vec2 uv;
  int s0, s1;
  float w0, w1;
  rtfTaps(g, q, uv, s0, s1, w0, w1);
  for (int k = 0; k < 4; ++k) {
    vec4 v = w0 * texture(oof, vec3(uv, float(s0 * 4 + k)));
    if (w1 != 0.0) v += w1 * texture(oof, vec3(uv, float(s1 * 4 + k)));
    V[4 * k] = v.x;
    V[4 * k + 1] = v.y;
    V[4 * k + 2] = v.z;
    V[4 * k + 3] = v.w;
  }
  V[0] += (1.0 - w0 - w1) * kRtfUnitVisibility;
}
