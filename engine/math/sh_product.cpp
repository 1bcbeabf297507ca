#include "engine/math/sh_product.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/math/quadrature.hpp"

namespace bounce::sh {

namespace {

std::vector<GauntEntry> computeGaunt() {
  // Y_i Y_j Y_k with l <= 3 each is a polynomial of degree <= 9 on the sphere.
  constexpr int kDegree = 3 * (kMaxOrder - 1);
  constexpr double kStructuralZero = 1e-12;  // exact zeros come out ~1e-17 after rounding
  const auto nodes = math::sphereQuadrature(kDegree);
  std::vector<std::array<double, kMaxCoeffs>> y(nodes.size());
  for (std::size_t q = 0; q < nodes.size(); ++q) evalBasis<double>(kMaxOrder, nodes[q].dir, y[q]);
  std::vector<GauntEntry> entries;
  for (int k = 0; k < kMaxCoeffs; ++k)
    for (int i = 0; i < kMaxCoeffs; ++i)
      for (int j = 0; j < kMaxCoeffs; ++j) {
        double sum = 0.0;
        for (std::size_t q = 0; q < nodes.size(); ++q) sum += nodes[q].weight * y[q][i] * y[q][j] * y[q][k];
        if (std::abs(sum) >= kStructuralZero)
          entries.push_back({static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(j),
                             static_cast<std::uint8_t>(k), sum});
      }
  return entries;  // generated in (k, i, j) order
}

}  // namespace

const std::vector<GauntEntry>& gauntTensor() {
  static const std::vector<GauntEntry> tensor = computeGaunt();
  return tensor;
}

}  // namespace bounce::sh
