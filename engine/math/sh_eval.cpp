#include "engine/math/sh_eval.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.hpp"

namespace bounce::sh {

void checkOrder(int order) {
  if (order < 1 || order > kMaxOrder)
    throw InternalError("sh: order " + std::to_string(order) + " outside 1.." + std::to_string(kMaxOrder));
}

int orderFromCount(std::size_t count) {
  for (int order = 1; order <= kMaxOrder; ++order)
    if (count == static_cast<std::size_t>(coeffCount(order))) return order;
  throw InternalError("sh: " + std::to_string(count) + " coefficients is not 1, 4, 9 or 16");
}

namespace {

// The 16 polynomials, written once; evalFast and evalBasis share them.
template <typename T>
void evalAll(int order, const glm::vec<3, T>& d, T* y) {
  using namespace constants;
  const T x = d.x, yy = d.y, z = d.z;
  y[0] = T(kY00);
  if (order < 2) return;
  y[1] = T(kY1) * yy;
  y[2] = T(kY1) * z;
  y[3] = T(kY1) * x;
  if (order < 3) return;
  const T x2 = x * x, y2 = yy * yy, z2 = z * z;
  y[4] = T(kY2a) * x * yy;
  y[5] = T(kY2a) * yy * z;
  y[6] = T(kY20) * (T(3) * z2 - T(1));
  y[7] = T(kY2a) * x * z;
  y[8] = T(kY22) * (x2 - y2);
  if (order < 4) return;
  y[9] = T(kY33) * yy * (T(3) * x2 - y2);
  y[10] = T(kY32a) * x * yy * z;
  y[11] = T(kY31) * yy * (T(5) * z2 - T(1));
  y[12] = T(kY30) * z * (T(5) * z2 - T(3));
  y[13] = T(kY31) * x * (T(5) * z2 - T(1));
  y[14] = T(kY32b) * z * (x2 - y2);
  y[15] = T(kY33) * x * (x2 - T(3) * y2);
}

}  // namespace

template <typename T>
T evalFast(int l, int m, const glm::vec<3, T>& d) {
  if (l < 0 || l > 3 || m < -l || m > l)
    throw InternalError("sh::evalFast: (l, m) = (" + std::to_string(l) + ", " + std::to_string(m) +
                        ") outside l <= 3, |m| <= l");
  T y[kMaxCoeffs];
  evalAll<T>(l + 1, d, y);
  return y[index(l, m)];
}

template <typename T>
void evalBasis(int order, const glm::vec<3, T>& d, std::span<T> out) {
  checkOrder(order);
  if (out.size() < static_cast<std::size_t>(coeffCount(order)))
    throw InternalError("sh::evalBasis: output holds " + std::to_string(out.size()) + " values, needs " +
                        std::to_string(coeffCount(order)));
  evalAll<T>(order, d, out.data());
}

template <typename T>
T evalRecurrence(int l, int m, const glm::vec<3, T>& d) {
  if (l < 0 || m < -l || m > l)
    throw InternalError("sh::evalRecurrence: (l, m) = (" + std::to_string(l) + ", " + std::to_string(m) + ")");
  // Work in double: the recurrence loses digits for large l, and callers are tests/bakes.
  const double z = std::clamp(static_cast<double>(d.z), -1.0, 1.0);
  const double phi = std::atan2(static_cast<double>(d.y), static_cast<double>(d.x));
  const int am = std::abs(m);
  // P_m^m(z) = (2m-1)!! (1-z²)^{m/2}  (no (-1)^m: the convention above).
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  double pmm = 1.0;
  for (int i = 1; i <= am; ++i) pmm *= (2.0 * i - 1.0) * s;
  double p = pmm;
  if (l > am) {
    // P_{m+1}^m = z (2m+1) P_m^m, then (l-m) P_l^m = z (2l-1) P_{l-1}^m - (l+m-1) P_{l-2}^m.
    double pPrev = pmm;
    double pCur = z * (2.0 * am + 1.0) * pmm;
    for (int ll = am + 2; ll <= l; ++ll) {
      const double pNext = (z * (2.0 * ll - 1.0) * pCur - (ll + am - 1.0) * pPrev) / (ll - am);
      pPrev = pCur;
      pCur = pNext;
    }
    p = pCur;
  }
  // K_lm = √((2l+1)/(4π) · (l-|m|)!/(l+|m|)!)
  double ratio = 1.0;
  for (int k = l - am + 1; k <= l + am; ++k) ratio /= k;
  const double k = std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI) * ratio);
  if (m == 0) return static_cast<T>(k * p);
  const double trig = m > 0 ? std::cos(am * phi) : std::sin(am * phi);
  return static_cast<T>(std::sqrt(2.0) * k * trig * p);
}

template float evalFast<float>(int, int, const glm::vec3&);
template double evalFast<double>(int, int, const glm::dvec3&);
template void evalBasis<float>(int, const glm::vec3&, std::span<float>);
template void evalBasis<double>(int, const glm::dvec3&, std::span<double>);
template float evalRecurrence<float>(int, int, const glm::vec3&);
template double evalRecurrence<double>(int, int, const glm::dvec3&);

}  // namespace bounce::sh
