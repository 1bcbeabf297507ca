#pragma once
// Exact quadrature on the sphere for polynomials (hence for products of SH).
//
// Gauss–Legendre in z = cosθ times the uniform rule in φ: n Gauss points integrate polynomials
// in z of degree <= 2n-1 exactly, and P equally spaced φ integrate trigonometric polynomials of
// degree <= P-1 exactly. A polynomial in (x, y, z) of total degree D restricted to the sphere is a
// sum of z-polynomials of degree <= D times cos/sin(kφ) with k <= D, so n = ceil((D+1)/2) and
// P = D+1 integrate it exactly (up to rounding).
#include <vector>

#include <glm/glm.hpp>

namespace bounce::math {

struct QuadratureNode {
  double x = 0.0;       // node in [-1, 1]
  double weight = 0.0;  // weights sum to 2
};

// The n-point Gauss–Legendre rule on [-1, 1] (Newton iteration on P_n from Chebyshev guesses,
// converged to ~1e-15).
std::vector<QuadratureNode> gaussLegendre(int n);

struct SphereNode {
  glm::dvec3 dir{0.0};
  double weight = 0.0;  // steradians; weights sum to 4π
};

// Nodes integrating every polynomial of total degree <= `degree` over the unit sphere exactly.
std::vector<SphereNode> sphereQuadrature(int degree);

}  // namespace bounce::math
