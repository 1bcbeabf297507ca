#pragma once
// The form factor from a point on a diffuse receiver to a one-sided triangular light: the
// Baum–Rushmeier–Winget edge integral (VLM thesis Eq. 3.1), made numerically stable.
//
//   F = 1/(2π) Σ_edges θ_ij · n·(p̂_j × p̂_i)/‖p̂_j × p̂_i‖,   θ_ij = atan2(‖p̂_i × p̂_j‖, p̂_i·p̂_j)
//
// Eq. 3.1 writes θ = arccos(p̂_i·p̂_j); arccos loses all precision for nearly parallel or nearly
// opposite vectors (tiny or distant lights, receivers next to an edge), atan2 of the cross and dot
// does not. The cross product is taken as p̂_i × ((p_j − p_i)/‖p_j‖), i.e. against the edge vector,
// so no two nearly equal unit vectors are subtracted. Eq. 3.1 holds only for a polygon wholly above
// the receiver's horizon (§3.2), so the triangle is first clipped against the tangent plane
// (Sutherland–Hodgman; a triangle cut by one plane keeps at most 4 vertices). After clipping,
// vertices at the shading point and zero-length edges are dropped: both carry no solid angle and
// would otherwise divide by zero.
//
// Irradiance from a set of lights of radiance L_k is E = Σ_k π L_k F_k (W/m² for L in W/(m²·sr));
// a Lambertian receiver of albedo ρ reflects radiance ρE/π. shaders/vlm/form_factor.glsl is the
// same code line for line in float; tests/unit/vlm checks one against the other.
//
// Templated on the scalar: double is the engine's CPU path, long double the tests' reference, float
// mirrors the GPU.
#include <cmath>
#include <limits>
#include <glm/glm.hpp>

namespace bounce::gi::vlm {

template <class T>
using Vec3 = glm::vec<3, T, glm::defaultp>;

// Clipped polygons have at most 4 vertices (a triangle against one plane).
inline constexpr int kMaxClipped = 4;

// The triangle's own (unnormalised) normal; the light emits on this side only (counter-clockwise
// winding seen from the front, as glTF).
template <class T>
Vec3<T> lightNormal(const Vec3<T>& v0, const Vec3<T>& v1, const Vec3<T>& v2) {
  return glm::cross(v1 - v0, v2 - v0);
}

// Sutherland–Hodgman clip of polygon `in` (n ≤ 3 vertices, relative to the shading point) against
// the half-space n·x ≥ 0. Writes up to kMaxClipped vertices to `out`, returns the count. Vertices on
// the plane count as inside, so a light resting on the plane keeps its horizon edge (which carries
// no solid angle: its edge term has n·ĉ·θ = 0 only when collinear, see formFactorRelative).
// onPlane[i] says that out[i] lies on the plane by construction (a clip point, or n·v exactly 0):
// edgeIntegral uses it for the horizon edge, see there.
template <class T>
int clipToHorizon(const Vec3<T>* in, int n, const Vec3<T>& normal, Vec3<T>* out, bool* onPlane) {
  int count = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3<T>& a = in[i];
    const Vec3<T>& b = in[(i + 1) % n];
    const T da = glm::dot(normal, a), db = glm::dot(normal, b);
    if (da >= T(0)) {
      onPlane[count] = da == T(0);
      out[count++] = a;
    }
    if ((da >= T(0)) != (db >= T(0))) {
      // da and db have opposite signs, so da − db is never 0 and t ∈ [0, 1].
      const T t = da / (da - db);
      onPlane[count] = true;
      out[count++] = a + (b - a) * t;
    }
  }
  return count;
}

// Form factor of a polygon given relative to the shading point (vertices p_i − x), already clipped
// to the receiver's upper hemisphere, for receiver normal n (unit). Returns the signed sum of Eq.
// 3.1; the caller fixes the sign by the light's facing. onPlane: as clipToHorizon writes it.
//
// Conditioning (what float can and cannot do here; measured in tests/unit/vlm/form_factor_test.cpp):
// each term θ·n·ĉ is O(θ‖n‖) however small F is, so float leaves an absolute error of a few ε‖n‖
// (cancellation between terms is inherent to the inputs). Two cases were far worse, and are why the
// code below is not the textbook line:
//  - the horizon edge (between two clip points) lies in the tangent plane, so its ĉ is exactly ±n̂;
//    computed from the rounded clip points, ĉ tilts by (their distance from the plane, ~ε) / (the
//    edge's distance from x), which is arbitrarily small when the chord passes near x (θ → π): up
//    to 2.6e-3 relative error in float in 4·10^5 random configurations. Such an edge takes
//    n·ĉ = ±‖n‖ (the sign from the computed ĉ, which is reliable until the chord is within ~ε of x,
//    i.e. x is within ~ε of the light's plane).
//  - p̂_a × p̂_b is taken against the edge vector (no two nearly equal unit vectors subtracted), and
//    its rounding scales with ‖b − a‖ over the length the edge vector is divided by. Dividing by the
//    nearer vertex's length makes that ratio large for a long edge pointing at x (15 in the worst of
//    4000 random cases: 1.02e-4 relative error in float), so it is divided by the longer one (ratio ≤ 2).
template <class T>
T edgeIntegral(const Vec3<T>* poly, const bool* onPlane, int n, const Vec3<T>& normal) {
  // Guard: drop vertices at the shading point and zero-length edges. "Zero" is relative to the
  // polygon's size so that triangles 1e-4 and 1e4 wide behave alike.
  T scale = T(0);
  for (int i = 0; i < n; ++i) scale = glm::max(scale, glm::max(glm::abs(poly[i].x), glm::max(glm::abs(poly[i].y), glm::abs(poly[i].z))));
  if (!(scale > T(0))) return T(0);
  const T tiny = scale * std::numeric_limits<T>::epsilon() * T(4);
  Vec3<T> v[kMaxClipped];
  bool planar[kMaxClipped];
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3<T>& p = poly[i];
    if (glm::max(glm::abs(p.x), glm::max(glm::abs(p.y), glm::abs(p.z))) <= tiny) continue;  // at the point
    if (m > 0) {
      const Vec3<T> d = p - v[m - 1];
      if (glm::max(glm::abs(d.x), glm::max(glm::abs(d.y), glm::abs(d.z))) <= tiny) continue;  // zero-length edge
    }
    planar[m] = onPlane[i];
    v[m++] = p;
  }
  while (m > 1) {  // the closing edge, too
    const Vec3<T> d = v[0] - v[m - 1];
    if (glm::max(glm::abs(d.x), glm::max(glm::abs(d.y), glm::abs(d.z))) > tiny) break;
    --m;
  }
  if (m < 3) return T(0);  // a point or a segment: no solid angle

  T sum = T(0);
  for (int i = 0; i < m; ++i) {
    const Vec3<T>& a = v[i];
    const Vec3<T>& b = v[(i + 1) % m];
    const T la = glm::length(a), lb = glm::length(b);
    const Vec3<T> ua = a / la, ub = b / lb;
    // p̂_a × p̂_b = p̂_a × (b − a)/‖b‖ = (a − b)/‖a‖ × p̂_b: the edge vector, not a difference of two
    // unit vectors, divided by the longer of ‖a‖, ‖b‖ (see Conditioning above).
    const Vec3<T> c = la <= lb ? glm::cross(ua, (b - a) / lb) : glm::cross((a - b) / la, ub);
    const T s = glm::length(c);
    if (!(s > T(0))) continue;  // collinear with the point: θ = 0 (or the point on the edge, no area)
    const T theta = std::atan2(s, glm::dot(ua, ub));
    const T nc = glm::dot(normal, c);
    // A horizon edge: ĉ = ±n̂ exactly (see Conditioning above).
    const T cosine = planar[i] && planar[(i + 1) % m] ? (nc < T(0) ? -glm::length(normal) : glm::length(normal)) : nc / s;
    sum += theta * cosine;
  }
  return sum;
}

// Form factor from the receiver (point x, unit normal n) to the one-sided triangle (v0, v1, v2):
// the fraction of a Lambertian emitter's exitance that lands on x, so E = π L F. 0 when x is
// behind the light or on its plane, or the light is below the horizon.
template <class T>
T formFactor(const Vec3<T>& x, const Vec3<T>& n, const Vec3<T>& v0, const Vec3<T>& v1, const Vec3<T>& v2) {
  const Vec3<T> rel[3] = {v0 - x, v1 - x, v2 - x};
  // One-sided emission: x must be strictly in front of the light's plane. Using the edge vectors
  // (not rel) keeps the facing test independent of x's distance.
  const Vec3<T> ln = lightNormal(v0, v1, v2);
  if (!(glm::dot(ln, -rel[0]) > T(0))) return T(0);
  Vec3<T> clipped[kMaxClipped];
  bool onPlane[kMaxClipped];
  const int count = clipToHorizon(rel, 3, n, clipped, onPlane);
  // Seen from the front, a counter-clockwise light winds clockwise about n: the sum is negative.
  const T f = -edgeIntegral(clipped, onPlane, count, n) / (T(2) * T(3.14159265358979323846264338327950288L));
  return glm::max(f, T(0));  // rounding can leave −ε when the light is at the horizon
}

// Double-precision convenience for the engine's CPU paths.
double formFactor(const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& v0, const glm::dvec3& v1,
                  const glm::dvec3& v2);

}  // namespace bounce::gi::vlm
