#pragma once
// The bound on what fp16 storage of the CPCA (cpca.hpp quantize, n₈ = 0) may move one reconstructed
// entry x̂_r[d] of Eq. 9 by.
//
// Each stored value v (a basis entry E_j[d] or a coefficient α_j) becomes v̂ = v + δ with
//   |δ| ≤ u·|v| + t,   u = 2⁻¹¹ (half an ulp of the 11-bit significand, normal halves |v| ≥ 2⁻¹⁴),
//                      t = 2⁻²⁵ (half the spacing 2⁻²⁴ of subnormal halves; values below it → 0).
// With x̂ = E_0 + Σ_{j≥1} α_j E_j (α_0 ≡ 1 is not stored):
//   x̂_h − x̂_f = δE_0 + Σ_j (δα_j E_j + α_j δE_j + δα_j δE_j)
//   |x̂_h − x̂_f| ≤ u|E_0| + t + Σ_j [ (u|α_j| + t)|E_j| + |α_j|(u|E_j| + t) + (u|α_j| + t)(u|E_j| + t) ].
// Cpca::reconstruct sums in float, once for each side: (n_e + 1) roundings of at most 2⁻²⁴ of the
// running sum, bounded by 2·(n_e + 1)·2⁻²⁴·(|E_0| + Σ_j |α_j||E_j|).
// `rounded`: the Cpca passed holds v̂, not v; then |v| ≤ (|v̂| + t)/(1 − u) stands in for |v|.
#include <cmath>
#include <cstddef>

#include "engine/gi/rtf/cpca.hpp"

namespace bounce::gi::rtf::testing {

inline double halfBound(const Cpca& c, std::size_t r, std::size_t d, bool rounded) {
  constexpr double u = 1.0 / 2048.0, t = 1.0 / 33554432.0, eps = 1.0 / 16777216.0;
  const auto mag = [&](float v) { return rounded ? (std::abs(double(v)) + t) / (1.0 - u) : std::abs(double(v)); };
  const std::size_t D = std::size_t(c.dimension), ne = std::size_t(c.components);
  const float* b = c.basis.data() + std::size_t(c.cluster[r]) * (ne + 1) * D;
  const double e0 = mag(b[d]);
  double bound = u * e0 + t, sum = e0;
  for (std::size_t j = 1; j <= ne; ++j) {
    const double a = mag(c.alpha[r * ne + j - 1]), e = mag(b[j * D + d]);
    bound += (u * a + t) * e + a * (u * e + t) + (u * a + t) * (u * e + t);
    sum += a * e;
  }
  return bound + 2.0 * double(ne + 1) * eps * sum;
}

}  // namespace bounce::gi::rtf::testing
