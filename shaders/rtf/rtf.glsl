// RTF field lookup (Pan et al. 2007, Eq. 10), term for term what engine/gi/rtf/evaluate.cpp
// lookup() / interreflection() / occlusion() compute (tests/unit/rtf/lookup_gpu_test.cpp checks it):
// the 8 samples around q (local offset from the bounding-sphere centre in units of η) — bilinear
// between the texel centres of the cube face q's direction falls on (clamped to that face), linear
// between the two spheres bracketing |q|, the innermost sphere inside it, a linear fade to zero over
// one sphere spacing beyond the outermost. Fields are read with texelFetch from 2D-array textures:
//   ξ:   rgba32f, layer sphere·16 + i, texel (face·n_r + x, y)   (xi.comp)
//   OOF: rgba32f, layer sphere·4 + i/4, texel (face·n_r + x, y), component i%4 (xi_pass.cpp)

struct RtfGrid {
  int spheres;
  int faceSize;
  float innerRadius;  // units of η
  float outerRadius;
};

const float kRtfUnitVisibility = 3.5449077;  // 4π·Y_00 = 2√π: the SH of V ≡ 1

float rtfSphereRadius(RtfGrid g, int s) { return g.innerRadius + (g.outerRadius - g.innerRadius) * float(s) / float(g.spheres - 1); }

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

// The 8 (layer base, texel) pairs and weights: layerBase[c] is the sphere index.
void rtfLookup(RtfGrid g, vec3 q, out ivec2 texel[8], out int sphere[8], out float weight[8]) {
  float r = length(q);
  float r0 = rtfSphereRadius(g, 0), rN = rtfSphereRadius(g, g.spheres - 1);
  float dr = (g.outerRadius - g.innerRadius) / float(g.spheres - 1);
  int s0 = 0, s1 = 0;
  float w1 = 0.0, fade = 1.0;
  if (r <= r0) {
    s0 = 0; s1 = 0;
  } else if (r >= rN) {
    s0 = g.spheres - 1; s1 = s0;
    fade = max(0.0, 1.0 - (r - rN) / dr);
  } else {
    float t = (r - g.innerRadius) / dr;
    s0 = min(int(floor(t)), g.spheres - 2);
    s1 = s0 + 1;
    w1 = clamp(t - float(s0), 0.0, 1.0);
  }
  int face;
  vec2 f;
  rtfFace(r > 0.0 ? q / r : vec3(0.0), g.faceSize, face, f);
  int x0 = min(int(f.x), g.faceSize - 1), y0 = min(int(f.y), g.faceSize - 1);
  int x1 = min(x0 + 1, g.faceSize - 1), y1 = min(y0 + 1, g.faceSize - 1);
  float ax = f.x - float(x0), ay = f.y - float(y0);
  int c = 0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int e = 0; e < 2; ++e, ++c) {
        sphere[c] = a == 0 ? s0 : s1;
        texel[c] = ivec2(face * g.faceSize + (e == 0 ? x0 : x1), b == 0 ? y0 : y1);
        float ws = (a == 0 ? 1.0 - w1 : w1) * fade;
        weight[c] = ws * (b == 0 ? 1.0 - ay : ay) * (e == 0 ? 1.0 - ax : ax);
      }
}

// ξ at q: the object's interreflected radiance SH (16 RGB, the object's frame).
void rtfInterreflection(sampler2DArray xi, RtfGrid g, vec3 q, out vec3 L[16]) {
  ivec2 texel[8];
  int sphere[8];
  float weight[8];
  rtfLookup(g, q, texel, sphere, weight);
  for (int i = 0; i < 16; ++i) L[i] = vec3(0.0);
  for (int c = 0; c < 8; ++c) {
    if (weight[c] == 0.0) continue;
    for (int i = 0; i < 16; ++i) L[i] += weight[c] * texelFetch(xi, ivec3(texel[c], sphere[c] * 16 + i), 0).rgb;
  }
}

// The OOF at q, faded to unoccluded beyond the field (16 floats, the object's frame).
void rtfOcclusion(sampler2DArray oof, RtfGrid g, vec3 q, out float V[16]) {
  ivec2 texel[8];
  int sphere[8];
  float weight[8];
  rtfLookup(g, q, texel, sphere, weight);
  for (int i = 0; i < 16; ++i) V[i] = 0.0;
  float total = 0.0;
  for (int c = 0; c < 8; ++c) {
    total += weight[c];
    for (int k = 0; k < 4; ++k) {
      vec4 v = texelFetch(oof, ivec3(texel[c], sphere[c] * 4 + k), 0);
      V[4 * k] += weight[c] * v.x;
      V[4 * k + 1] += weight[c] * v.y;
      V[4 * k + 2] += weight[c] * v.z;
      V[4 * k + 3] += weight[c] * v.w;
    }
  }
  V[0] += (1.0 - total) * kRtfUnitVisibility;
}
