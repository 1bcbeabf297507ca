#include "engine/math/quadrature.hpp"

#include <cmath>
#include <string>

#include "engine/core/error.hpp"
#include "engine/math/sampling.hpp"

namespace bounce::math {

std::vector<QuadratureNode> gaussLegendre(int n) {
  if (n < 1 || n > 1000) throw InternalError("gaussLegendre: " + std::to_string(n) + " points outside 1..1000");
  std::vector<QuadratureNode> nodes(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    // Root i of P_n, starting from the Chebyshev approximation (Abramowitz & Stegun 22.16.6).
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      // P_n(x) by Bonnet's recurrence (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1}.
      double p0 = 1.0, p1 = x;
      for (int k = 1; k < n; ++k) {
        const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
        p0 = p1;
        p1 = p2;
      }
      // P_n'(x) = n (x P_n - P_{n-1}) / (x² - 1)
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    nodes[i].x = x;
    nodes[i].weight = 2.0 / ((1.0 - x * x) * dp * dp);  // A&S 25.4.29
  }
  return nodes;
}

std::vector<SphereNode> sphereQuadrature(int degree) {
  if (degree < 0 || degree > 200) throw InternalError("sphereQuadrature: degree " + std::to_string(degree));
  const int nz = (degree + 2) / 2;  // ceil((degree+1)/2)
  const int nphi = degree + 1;
  const auto gl = gaussLegendre(nz);
  std::vector<SphereNode> nodes;
  nodes.reserve(static_cast<std::size_t>(nz) * nphi);
  for (const auto& g : gl) {
    const double r = std::sqrt(std::max(0.0, 1.0 - g.x * g.x));
    for (int k = 0; k < nphi; ++k) {
      // Offset by half a step so no node sits on the ±X seam (harmless either way; symmetric).
      const double phi = 2.0 * kPi * (k + 0.5) / nphi;
      nodes.push_back({{r * std::cos(phi), r * std::sin(phi), g.x}, g.weight * 2.0 * kPi / nphi});
    }
  }
  return nodes;
}

}  // namespace bounce::math
