#pragma once
// SH products via the triple-product (Gaunt) tensor.
//
// For f = Σ a_i Y_i and g = Σ b_j Y_j, the projection of the pointwise product f·g onto Y_k is
//   c_k = Σ_ij C_ijk a_i b_j,   C_ijk = ∫_S² Y_i Y_j Y_k dω
// (Ng, Ramamoorthi, Hanrahan 2004, "Triple Product Wavelet Integrals"; Sloan 2008 "Stupid SH
// tricks" §products). C is symmetric in i, j, k and non-zero only when |l_i - l_j| <= l_k <=
// l_i + l_j with l_i + l_j + l_k even, so it is stored sparse. The product of two order-n
// functions has bands up to 2n-2; `order` truncates the result, and the truncated result is the
// exact projection of f·g onto that order (nothing is lost but the dropped bands).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/math/sh_eval.hpp"

namespace bounce::sh {

struct GauntEntry {
  std::uint8_t i = 0, j = 0, k = 0;  // coefficient indices, each < kMaxCoeffs
  double value = 0.0;
};

// Every non-zero C_ijk with i, j, k < 16, sorted by (k, i, j). Computed once (thread-safe) by
// quadrature exact for polynomials of degree <= 9 (three SH of degree <= 3); entries with
// |C| < 1e-12 are the structural zeros and are dropped.
const std::vector<GauntEntry>& gauntTensor();

// c = projection of f_a · f_b onto `order` (a and b may have different orders 1..4).
template <typename T>
std::vector<T> product(std::span<const T> a, std::span<const T> b, int order) {
  orderFromCount(a.size());
  orderFromCount(b.size());
  checkOrder(order);
  const std::size_t nOut = static_cast<std::size_t>(coeffCount(order));
  std::vector<T> c(nOut, T(0));
  for (const GauntEntry& e : gauntTensor()) {
    if (e.k >= nOut) break;  // sorted by k
    if (e.i < a.size() && e.j < b.size()) c[e.k] += static_cast<T>(e.value) * a[e.i] * b[e.j];
  }
  return c;
}

template <typename T>
std::vector<T> product(const std::vector<T>& a, const std::vector<T>& b, int order) {
  return product<T>(std::span<const T>(a), std::span<const T>(b), order);
}

// The order²×order² matrix M (row-major, M[k][j] = Σ_i C_ijk a_i) with product(a, b, order) =
// M·b for every b of that order: "multiply by f_a" as a linear operator (e.g. a visibility
// function applied to many radiance vectors).
template <typename T>
std::vector<T> productMatrix(std::span<const T> a, int order) {
  orderFromCount(a.size());
  checkOrder(order);
  const std::size_t n = static_cast<std::size_t>(coeffCount(order));
  std::vector<T> m(n * n, T(0));
  for (const GauntEntry& e : gauntTensor()) {
    if (e.k >= n) break;
    if (e.i < a.size() && e.j < n) m[e.k * n + e.j] += static_cast<T>(e.value) * a[e.i];
  }
  return m;
}

}  // namespace bounce::sh
