// Probe interpolation weights, shared by the GPU node (probes.frag) and the CPU API
// (engine/gi/probes/probe_volume.cpp compiles this file as C++ against glm), so both give the
// same weights by construction. Keep to the GLSL/C++ common subset (see common/sh.glsl).
//
// The includer defines how probe data is read:
//   PROBE_DATA_PARAM      extra leading parameter (C++: the volume; GLSL: empty)
//   PROBE_DATA_ARG        the same passed on (C++: `volume,`; GLSL: empty)
//   PROBE_VALID(i)        bool: probe i is usable (not inside geometry)
//   PROBE_MOMENTS(i, b)   vec2: mean and mean-square hit distance of probe i in bin b (metres, m²)
//
// Weight of probe k for a receiver x with normal n (after Majercik et al. 2019, "Dynamic Diffuse
// Global Illumination with Ray-Traced Irradiance Fields", JCGT 8(2), §4):
//   w_k = trilinear_k(q) · backface_k · chebyshev_k,  normalised to Σ w_k = 1 over valid probes,
// where q = x + normalBias·n + viewBias·v is the biased receiver (v: unit vector to the eye),
// backface_k = ((dir_to_probe·n + 1)/2)² + 0.2 and chebyshev_k = (σ²/(σ² + (d − μ)²))³ when the
// probe-to-q distance d exceeds the mean hit distance μ of that direction's bin (1 otherwise).
#ifndef BOUNCE_PROBE_WEIGHTS_GLSL
#define BOUNCE_PROBE_WEIGHTS_GLSL

// Visibility bins: an R×R grid over the equal-area cylindrical map u = (1 − z)/2, v = φ/2π, the
// same map the bake samples uniformly (math::uniformSphere), so with R | √rays every bin receives
// exactly rays/R² stratified rays.
const int PROBE_VIS_RES = 8;
const int PROBE_VIS_BINS = 64;  // PROBE_VIS_RES²

int probeVisBin(vec3 d) {
  float u = clamp((1.0f - d.z) * 0.5f, 0.0f, 1.0f);
  int i = min(int(u * float(PROBE_VIS_RES)), PROBE_VIS_RES - 1);
  // j = ⌊8·φ/2π⌋ for φ = atan2(y, x) in [0, 2π): with 8 columns a column is an octant of the
  // xy-plane, found from signs and |x| vs |y| without the atan (about a sixth of the probes pass
  // on llvmpipe, README "What costs what on lavapipe"). Same column as ⌊8·atan2/2π⌋ except where
  // float rounding sits on an octant edge (y = 0, y = ±x, x = 0; measure zero); x = y = 0 (φ := 0)
  // is column 0 as atan2(0, 0) = 0 gave. The lower half-plane (φ ≥ π: y < 0, or y = 0 and x < 0) is
  // turned by π onto the upper one, octants 4–7 onto 0–3.
  bool lower = d.y < 0.0f || (d.y == 0.0f && d.x < 0.0f);
  float x = lower ? -d.x : d.x;
  float y = lower ? -d.y : d.y;
  int q = x > 0.0f ? (y < x ? 0 : 1) : (y > -x ? 2 : 3);
  if (x == 0.0f && y == 0.0f) q = 0;
  return i * PROBE_VIS_RES + (lower ? q + 4 : q);
}

// Chebyshev's one-sided bound P(D ≥ d) ≤ σ²/(σ² + (d − μ)²) (variance shadow maps, Donnelly &
// Lauritzen 2006), cubed as DDGI does to sharpen the falloff.
float probeChebyshev(vec2 moments, float dist, float minVariance) {
  if (dist <= moments.x) return 1.0f;
  float variance = max(moments.y - moments.x * moments.x, minVariance);
  float d = dist - moments.x;
  float w = variance / (variance + d * d);
  return w * w * w;
}

// DDGI's smooth backface term: probes behind the surface count less, never zero (so a receiver
// always finds some probe).
float probeBackface(vec3 dirToProbe, vec3 n) {
  float t = (dot(dirToProbe, n) + 1.0f) * 0.5f;
  return t * t + 0.2f;
}

// The biased receiver q in grid units (grid: probe (i,j,k) at origin + spacing·(i,j,k), count probes
// per axis), clamped to the grid, and its cell's corner probe (0,0,0): q's fraction in the cell is
// g − base. Corner k of the cell is base + (k & 1, (k >> 1) & 1, (k >> 2) & 1).
vec3 probeGridCoord(ivec3 count, vec3 origin, float spacing, vec3 q) {
  return clamp((q - origin) / spacing, vec3(0.0f), vec3(count - ivec3(1)));
}

ivec3 probeCellBase(ivec3 count, vec3 g) { return min(ivec3(floor(g)), max(count - ivec3(2), ivec3(0))); }

ivec3 probeCorner(ivec3 count, ivec3 base, int k) {
  return min(base + ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1), count - ivec3(1));
}

int probeIndex(ivec3 count, ivec3 c) { return (c.z * count.y + c.y) * count.x + c.x; }

// Corner k's trilinear weight (0 on the far side of a face q is clamped onto).
float probeTrilinear(vec3 f, int k) {
  vec3 tri = mix(vec3(1.0f) - f, f, vec3(ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1)));
  return tri.x * tri.y * tri.z;
}

// The unnormalised weight of probe idx at grid corner c for q with normal n, given its trilinear
// weight tri > 0: tri · backface · Chebyshev, 0 when the probe is not valid.
float probeCornerWeight(PROBE_DATA_PARAM vec3 origin, float spacing, float minVariance, vec3 q, vec3 n, ivec3 c,
                        int idx, float tri) {
  float w = tri;
  if (PROBE_VALID(idx)) {
    vec3 toPoint = q - (origin + vec3(c) * spacing);
    float dist = length(toPoint);
    if (dist > 1e-6f) {
      vec3 dir = toPoint / dist;
      w *= probeBackface(-dir, n) * probeChebyshev(PROBE_MOMENTS(idx, probeVisBin(dir)), dist, minVariance);
    }
  } else {
    w = 0.0f;
  }
  return w;
}

// The 8 probes around the biased receiver q and their normalised weights; all weights 0 when no
// valid probe is near. (probes.frag sums the same unnormalised weights over the non-zero corners
// only and divides once: probe_sh.glsl probeRadianceSh.)
void probeWeights(PROBE_DATA_PARAM ivec3 count, vec3 origin, float spacing, float minVariance, vec3 q, vec3 n,
                  out int probe[8], out float weight[8]) {
  vec3 g = probeGridCoord(count, origin, spacing, q);
  ivec3 base = probeCellBase(count, g);
  vec3 f = g - vec3(base);
  float sum = 0.0f;
  for (int k = 0; k < 8; ++k) {
    ivec3 c = probeCorner(count, base, k);
    int idx = probeIndex(count, c);
    float w = probeTrilinear(f, k);
    probe[k] = idx;
    w = w > 0.0f ? probeCornerWeight(PROBE_DATA_ARG origin, spacing, minVariance, q, n, c, idx, w) : 0.0f;
    weight[k] = w;
    sum += w;
  }
  for (int k = 0; k < 8; ++k) weight[k] = sum > 0.0f ? weight[k] / sum : 0.0f;
}

#endif  // BOUNCE_PROBE_WEIGHTS_GLSL
