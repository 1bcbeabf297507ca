// The VLM form factor (thesis Eq. 3.1) in float: a line-for-line mirror of
// engine/gi/vlm/form_factor.hpp (read the reasoning there). tests/unit/vlm compares the two.
//   F = 1/(2π) Σ θ_ij n·ĉ_ij,  θ_ij = atan(‖p̂_i × p̂_j‖, p̂_i·p̂_j)  (never acos)
// after Sutherland–Hodgman clipping of the triangle against the receiver's tangent plane.
#ifndef VLM_FORM_FACTOR_GLSL
#define VLM_FORM_FACTOR_GLSL

const int VLM_MAX_CLIPPED = 4;
const float VLM_FLT_EPSILON = 1.1920929e-7;

float vlmMaxAbs(vec3 v) { return max(abs(v.x), max(abs(v.y), abs(v.z))); }

// Clip triangle (relative to the shading point) against n·x ≥ 0; returns the vertex count (≤ 4).
// onPlane[i]: poly[i] lies on the plane by construction (a clip point, or n·v exactly 0).
int vlmClipToHorizon(vec3 tri[3], vec3 n, out vec3 poly[VLM_MAX_CLIPPED], out bool onPlane[VLM_MAX_CLIPPED]) {
  int count = 0;
  for (int i = 0; i < 3; ++i) {
    vec3 a = tri[i];
    vec3 b = tri[(i + 1) % 3];
    float da = dot(n, a), db = dot(n, b);
    if (da >= 0.0) {
      onPlane[count] = da == 0.0;
      poly[count++] = a;
    }
    if ((da >= 0.0) != (db >= 0.0)) {
      onPlane[count] = true;
      poly[count++] = a + (b - a) * (da / (da - db));
    }
  }
  for (int i = count; i < VLM_MAX_CLIPPED; ++i) {
    poly[i] = vec3(0.0);
    onPlane[i] = false;
  }
  return count;
}

// Signed Eq. 3.1 sum over a clipped polygon; drops vertices at the point and zero-length edges.
// The horizon edge takes n·ĉ = ±‖n‖ exactly, the cross product is divided by the longer vertex
// length (why: "Conditioning" in form_factor.hpp).
float vlmEdgeIntegral(vec3 poly[VLM_MAX_CLIPPED], bool onPlane[VLM_MAX_CLIPPED], int n, vec3 normal) {
  float scale = 0.0;
  for (int i = 0; i < n; ++i) scale = max(scale, vlmMaxAbs(poly[i]));
  if (!(scale > 0.0)) return 0.0;
  float tiny = scale * VLM_FLT_EPSILON * 4.0;
  vec3 v[VLM_MAX_CLIPPED];
  bool planar[VLM_MAX_CLIPPED];
  int m = 0;
  for (int i = 0; i < n; ++i) {
    vec3 p = poly[i];
    if (vlmMaxAbs(p) <= tiny) continue;
    if (m > 0 && vlmMaxAbs(p - v[m - 1]) <= tiny) continue;
    planar[m] = onPlane[i];
    v[m++] = p;
  }
  while (m > 1 && vlmMaxAbs(v[0] - v[m - 1]) <= tiny) --m;
  if (m < 3) return 0.0;
  float sum = 0.0;
  for (int i = 0; i < m; ++i) {
    vec3 a = v[i];
    vec3 b = v[(i + 1) % m];
    float la = length(a), lb = length(b);
    vec3 ua = a / la, ub = b / lb;
    vec3 c = la <= lb ? cross(ua, (b - a) / lb) : cross((a - b) / la, ub);
    float s = length(c);
    if (!(s > 0.0)) continue;
    float theta = atan(s, dot(ua, ub));
    float nc = dot(normal, c);
    float cosine = planar[i] && planar[(i + 1) % m] ? (nc < 0.0 ? -length(normal) : length(normal)) : nc / s;
    sum += theta * cosine;
  }
  return sum;
}

// Form factor from receiver (x, unit n) to the one-sided light (v0, v1, v2); E = π L F.
float vlmFormFactor(vec3 x, vec3 n, vec3 v0, vec3 v1, vec3 v2) {
  vec3 rel[3] = vec3[3](v0 - x, v1 - x, v2 - x);
  vec3 ln = cross(v1 - v0, v2 - v0);
  if (!(dot(ln, -rel[0]) > 0.0)) return 0.0;
  vec3 poly[VLM_MAX_CLIPPED];
  bool onPlane[VLM_MAX_CLIPPED];
  int count = vlmClipToHorizon(rel, n, poly, onPlane);
  float f = -vlmEdgeIntegral(poly, onPlane, count, n) / (2.0 * 3.14159265358979);
  return max(f, 0.0);
}

#endif
