#pragma once
// Real orthonormal spherical harmonics (SH): indexing, evaluation.
//
// Convention (shared with shaders/common/sh.glsl, tested against it):
//  - order n holds bands l < n, n*n coefficients; orders 1..4 (1, 4, 9, 16 coefficients);
//  - coefficient index i = l*(l+1) + m, -l <= m <= l;
//  - real SH WITHOUT the Condon–Shortley phase (-1)^m, so every polynomial below has a positive
//    constant: Y_1,-1 = c1*y, Y_1,0 = c1*z, Y_1,1 = c1*x (c1 = sqrt(3/(4π))), i.e. the basis of
//    Ramamoorthi & Hanrahan 2001 and Ivanic & Ruedenberg 1996. Sloan's "Stupid SH tricks" and
//    google/spherical-harmonics include the phase: their Y_l,m equals ours times (-1)^m;
//  - m > 0 ~ cos(mφ), m < 0 ~ sin(|m|φ), φ measured from +X towards +Y, θ from +Z;
//  - orthonormal: ∫_S² Y_i Y_j dω = δ_ij (dω in steradians).
// A function is reconstructed as f(d) = Σ_i c_i Y_i(d); c_i = ∫ f Y_i dω (sh_project.hpp).
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::sh {

inline constexpr int kMaxOrder = 4;
inline constexpr int kMaxCoeffs = kMaxOrder * kMaxOrder;

constexpr int coeffCount(int order) { return order * order; }
constexpr int index(int l, int m) { return l * (l + 1) + m; }

// Throws InternalError unless 1 <= order <= kMaxOrder (a caller bug, not user input).
void checkOrder(int order);
// The order whose coefficient count is `count`; throws InternalError unless count is 1, 4, 9 or 16.
int orderFromCount(std::size_t count);

// Normalisation constants of the hard-coded polynomials (same digits as sh.glsl).
namespace constants {
inline constexpr double kY00 = 0.28209479177387814;   // 1/(2√π)
inline constexpr double kY1 = 0.48860251190291992;    // √(3/(4π))
inline constexpr double kY2a = 1.0925484305920792;    // √(15/π)/2     (xy, yz, xz)
inline constexpr double kY20 = 0.31539156525252005;   // √(5/π)/4      (3z²-1)
inline constexpr double kY22 = 0.54627421529603959;   // √(15/π)/4     (x²-y²)
inline constexpr double kY33 = 0.59004358992664352;   // √(35/(2π))/4  (y(3x²-y²), x(x²-3y²))
inline constexpr double kY32a = 2.8906114426405538;   // √(105/π)/2    (xyz)
inline constexpr double kY31 = 0.45704579946446572;   // √(21/(2π))/4  (y(5z²-1), x(5z²-1))
inline constexpr double kY30 = 0.37317633259011546;   // √(7/π)/4      (z(5z²-3))
inline constexpr double kY32b = 1.4453057213202769;   // √(105/π)/4    (z(x²-y²))
}  // namespace constants

// Fast path: Y_l,m(d) for l <= 3 as a polynomial of the unit direction d (d is not normalised
// here; pass a unit vector). Throws InternalError outside l <= 3, |m| <= l.
template <typename T>
T evalFast(int l, int m, const glm::vec<3, T>& d);

// Fills out[0 .. order²) with Y_i(d) by the fast path. out.size() must be >= order².
template <typename T>
void evalBasis(int order, const glm::vec<3, T>& d, std::span<T> out);

template <typename T>
std::array<T, kMaxCoeffs> evalBasis(int order, const glm::vec<3, T>& d) {
  std::array<T, kMaxCoeffs> y{};
  evalBasis<T>(order, d, std::span<T>(y));
  return y;
}

// General path for any l >= 0: associated Legendre P_l^|m|(cos θ) by the standard three-term
// recurrence (no Condon–Shortley phase), times K_lm = √((2l+1)/(4π) (l-|m|)!/(l+|m|)!) and √2
// cos(mφ) or √2 sin(|m|φ). Slower; used to cross-check the fast path and for l > 3 in tests.
template <typename T>
T evalRecurrence(int l, int m, const glm::vec<3, T>& d);

// f(d) = Σ c_i Y_i(d), the order taken from coeffs.size(). V is T (scalar) or glm::vec<3,T> (RGB).
template <typename V, typename T>
V evalSum(std::span<const V> coeffs, const glm::vec<3, T>& d) {
  const int order = orderFromCount(coeffs.size());
  const auto y = evalBasis<T>(order, d);
  V sum(0);
  for (std::size_t i = 0; i < coeffs.size(); ++i) sum += coeffs[i] * y[i];
  return sum;
}

template <typename V, typename T>
V evalSum(const std::vector<V>& coeffs, const glm::vec<3, T>& d) {
  return evalSum<V, T>(std::span<const V>(coeffs), d);
}

}  // namespace bounce::sh
