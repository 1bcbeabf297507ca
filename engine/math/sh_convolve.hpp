#pragma once
// Convolution with the clamped cosine: radiance SH → irradiance SH and back.
//
// Irradiance at a surface with normal n from distant radiance L(ω) = Σ L_lm Y_lm(ω) is
//   E(n) = ∫ L(ω) max(0, n·ω) dω = Σ_lm Â_l L_lm Y_lm(n)                (DESIGN.md convention)
// by the Funk–Hecke theorem, with Â_l = 2π ∫_0^1 P_l(t) t dt the clamped cosine's zonal factors
// (Ramamoorthi & Hanrahan 2001, "An Efficient Representation for Irradiance Environment Maps",
// eq. 8–9, there written Â_l = √(4π/(2l+1)) A_l): Â_0 = π, Â_1 = 2π/3, Â_2 = π/4, Â_3 = 0.
// Â_3 = 0 means band 3 of radiance never reaches irradiance, and band 3 of radiance cannot be
// recovered from irradiance. Â_4 = -π/24 is the first term a 9-coefficient irradiance drops.
// Truncation bound (Cauchy–Schwarz plus the addition theorem Σ_m Y_lm(n)² = (2l+1)/(4π)):
//   |E(n) - E_{l<=2}(n)| <= √(Σ_{l>=4} Â_l² (2l+1)/(4π)) · ‖L - L_{l<=3}‖₂ ≈ 0.128 · ‖L - L_{l<=3}‖₂,
// checked against brute force in tests/unit/math/sh_convolve_test.cpp.
#include <span>
#include <vector>

#include "engine/math/sh_eval.hpp"

namespace bounce::sh {

// Â_l for l >= 0 (closed form for every l: 0 for odd l > 1, R&H eq. 9 for even l).
double cosineLobeBand(int l);

// E_lm = Â_l L_lm: the irradiance SH of radiance SH `radiance` (any order 1..4).
template <typename V>
std::vector<V> convolveCosine(std::span<const V> radiance) {
  const int order = orderFromCount(radiance.size());
  std::vector<V> out(radiance.begin(), radiance.end());
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m) out[index(l, m)] *= cosineLobeBand(l);
  return out;
}

// Radiance from irradiance band by band: L_lm = E_lm / Â_l where Â_l ≠ 0; bands with Â_l = 0
// (l = 3) are set to 0 since irradiance holds no information about them. Used by DNRT's improved
// anti-radiance ("divide band l by Â_l").
template <typename V>
std::vector<V> deconvolveCosine(std::span<const V> irradiance) {
  const int order = orderFromCount(irradiance.size());
  std::vector<V> out(irradiance.begin(), irradiance.end());
  for (int l = 0; l < order; ++l) {
    const double a = cosineLobeBand(l);
    for (int m = -l; m <= l; ++m) {
      if (a != 0.0) out[index(l, m)] *= 1.0 / a;
      else out[index(l, m)] = V(0);
    }
  }
  return out;
}

// E(n) = Σ Â_l L_lm Y_lm(n) for radiance coefficients L (scalar or RGB); n unit length.
template <typename V, typename T>
V evalIrradiance(std::span<const V> radiance, const glm::vec<3, T>& n) {
  const int order = orderFromCount(radiance.size());
  const auto y = evalBasis<T>(order, n);
  V sum(0);
  for (int l = 0; l < order; ++l) {
    const T a = static_cast<T>(cosineLobeBand(l));
    for (int m = -l; m <= l; ++m) sum += radiance[index(l, m)] * (a * y[index(l, m)]);
  }
  return sum;
}

template <typename V, typename T>
V evalIrradiance(const std::vector<V>& radiance, const glm::vec<3, T>& n) {
  return evalIrradiance<V, T>(std::span<const V>(radiance), n);
}

}  // namespace bounce::sh
