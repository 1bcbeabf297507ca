#pragma once
// Small geometric helpers: orthonormal frames around a normal, spherical triangles.
#include <cmath>

#include <glm/glm.hpp>

namespace bounce::math {

// Tangent t and bitangent b such that (t, b, n) is a right-handed orthonormal basis
// (t × b = n) for a unit normal n.
template <typename T>
struct Frame {
  glm::vec<3, T> t, b, n;

  // Local (x, y, z) → world: x along t, y along b, z along n.
  glm::vec<3, T> toWorld(const glm::vec<3, T>& v) const { return v.x * t + v.y * b + v.z * n; }
  glm::vec<3, T> toLocal(const glm::vec<3, T>& v) const {
    return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)};
  }
};

// Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin 2017, "Building an Orthonormal
// Basis, Revisited" (JCGT 6(1)), Listing 3: branchless and continuous everywhere except across
// z = 0's sign flip, accurate for n near ±Z (the Frisvad 2012 version loses orthogonality at
// n ≈ -Z). n must be unit length.
template <typename T>
Frame<T> orthonormalBasis(const glm::vec<3, T>& n) {
  const T sign = std::copysign(T(1), n.z);
  const T a = T(-1) / (sign + n.z);
  const T b = n.x * n.y * a;
  Frame<T> f;
  f.t = {T(1) + sign * n.x * n.x * a, sign * b, -sign * n.x};
  f.b = {b, sign + n.y * n.y * a, -n.y};
  f.n = n;
  return f;
}

// Solid angle (sr) of the spherical triangle with unit-vector corners a, b, c
// (Van Oosterom & Strackee 1983): tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a).
template <typename T>
T sphericalTriangleSolidAngle(const glm::vec<3, T>& a, const glm::vec<3, T>& b, const glm::vec<3, T>& c) {
  const T num = std::abs(glm::dot(a, glm::cross(b, c)));
  const T den = T(1) + glm::dot(a, b) + glm::dot(b, c) + glm::dot(c, a);
  return T(2) * std::atan2(num, den);
}

}  // namespace bounce::math
