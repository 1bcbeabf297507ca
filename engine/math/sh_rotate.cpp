#include "engine/math/sh_rotate.hpp"

#include <cmath>
#include <string>

#include "engine/core/error.hpp"

namespace bounce::sh {

namespace {

// A band matrix addressed by centred indices -l..l, as in Ivanic & Ruedenberg.
struct Band {
  int l = 0;
  std::array<double, 49> m{};
  double& at(int i, int j) { return m[(i + l) * (2 * l + 1) + (j + l)]; }
  double at(int i, int j) const { return m[(i + l) * (2 * l + 1) + (j + l)]; }
};

// I&R 1996 Table 2 helper P: built from band 1 (r1) and band l-1 (prev).
double P(int i, int a, int b, int l, const Band& r1, const Band& prev) {
  if (b == l) return r1.at(i, 1) * prev.at(a, l - 1) - r1.at(i, -1) * prev.at(a, -l + 1);
  if (b == -l) return r1.at(i, 1) * prev.at(a, -l + 1) + r1.at(i, -1) * prev.at(a, l - 1);
  return r1.at(i, 0) * prev.at(a, b);
}

double U(int m, int n, int l, const Band& r1, const Band& prev) { return P(0, m, n, l, r1, prev); }

double V(int m, int n, int l, const Band& r1, const Band& prev) {
  if (m == 0) return P(1, 1, n, l, r1, prev) + P(-1, -1, n, l, r1, prev);
  if (m > 0) {
    const double d = m == 1 ? 1.0 : 0.0;
    return P(1, m - 1, n, l, r1, prev) * std::sqrt(1.0 + d) - P(-1, -m + 1, n, l, r1, prev) * (1.0 - d);
  }
  // m < 0: the printed versions disagree on which term carries √(1+δ); it must pair with the
  // P(-1, ...) term to mirror the m > 0 case (as google/spherical-harmonics derives). The tests
  // against the projection of the rotated function confirm this form.
  const double d = m == -1 ? 1.0 : 0.0;
  return P(1, m + 1, n, l, r1, prev) * (1.0 - d) + P(-1, -m - 1, n, l, r1, prev) * std::sqrt(1.0 + d);
}

double W(int m, int n, int l, const Band& r1, const Band& prev) {
  // m = 0 never reaches here: its coefficient w is 0.
  if (m > 0) return P(1, m + 1, n, l, r1, prev) + P(-1, -m - 1, n, l, r1, prev);
  return P(1, m - 1, n, l, r1, prev) - P(-1, -m + 1, n, l, r1, prev);
}

// I&R 1996 eq. 8.1: M^l_mn = u U + v V + w W with the coefficients of Table 1.
Band nextBand(int l, const Band& r1, const Band& prev) {
  Band out;
  out.l = l;
  for (int m = -l; m <= l; ++m)
    for (int n = -l; n <= l; ++n) {
      const double d = m == 0 ? 1.0 : 0.0;
      const double denom = std::abs(n) == l ? 2.0 * l * (2.0 * l - 1.0) : double((l + n) * (l - n));
      const int am = std::abs(m);
      const double u = std::sqrt(double((l + m) * (l - m)) / denom);
      const double v = 0.5 * std::sqrt((1.0 + d) * (l + am - 1.0) * (l + am) / denom) * (1.0 - 2.0 * d);
      const double w = -0.5 * std::sqrt(double((l - am - 1) * (l - am)) / denom) * (1.0 - d);
      // A zero coefficient means the matching U/V/W would index outside band l-1: skip it.
      double sum = 0.0;
      if (u != 0.0) sum += u * U(m, n, l, r1, prev);
      if (v != 0.0) sum += v * V(m, n, l, r1, prev);
      if (w != 0.0) sum += w * W(m, n, l, r1, prev);
      out.at(m, n) = sum;
    }
  return out;
}

}  // namespace

template <typename T>
Rotation<T> Rotation<T>::fromMatrix(const glm::mat<3, 3, T>& r) {
  // glm is column-major: r[col][row]. R(i, j) = row i, column j.
  glm::dmat3 rd(r);
  const glm::dmat3 shouldBeIdentity = glm::transpose(rd) * rd;
  const double tol = sizeof(T) == sizeof(float) ? 1e-3 : 1e-6;
  double err = std::abs(glm::determinant(rd) - 1.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) err = std::max(err, std::abs(shouldBeIdentity[i][j] - (i == j ? 1.0 : 0.0)));
  if (!(err <= tol))
    throw InternalError("sh::Rotation::fromMatrix: not a proper rotation (error " + std::to_string(err) + ")");

  const auto R = [&](int row, int col) { return rd[col][row]; };
  const int p[3] = {1, 2, 0};  // band-1 index m = -1, 0, 1 ↔ axis y, z, x
  Band b1;
  b1.l = 1;
  for (int m = -1; m <= 1; ++m)
    for (int n = -1; n <= 1; ++n) b1.at(m, n) = R(p[m + 1], p[n + 1]);
  const Band b2 = nextBand(2, b1, b1);
  const Band b3 = nextBand(3, b1, b2);

  Rotation out;
  for (int i = 0; i < 9; ++i) out.band1_[i] = static_cast<T>(b1.m[i]);
  for (int i = 0; i < 25; ++i) out.band2_[i] = static_cast<T>(b2.m[i]);
  for (int i = 0; i < 49; ++i) out.band3_[i] = static_cast<T>(b3.m[i]);
  return out;
}

template <typename T>
Rotation<T> Rotation<T>::fromQuaternion(const glm::qua<T>& q) {
  const T len = glm::length(q);
  if (!(len > T(0))) throw InternalError("sh::Rotation::fromQuaternion: zero-length quaternion");
  return fromMatrix(glm::mat3_cast(q / len));
}

template <typename T>
std::span<const T> Rotation<T>::band(int l) const {
  switch (l) {
    case 1: return band1_;
    case 2: return band2_;
    case 3: return band3_;
    default: throw InternalError("sh::Rotation::band: band " + std::to_string(l) + " outside 1..3");
  }
}

template <typename T>
std::vector<T> rotateZonal(std::span<const T> zonal, const glm::vec<3, T>& d) {
  const int order = static_cast<int>(zonal.size());
  checkOrder(order);
  const auto y = evalBasis<T>(order, d);
  std::vector<T> out(static_cast<std::size_t>(coeffCount(order)));
  for (int l = 0; l < order; ++l) {
    const T scale = static_cast<T>(std::sqrt(4.0 * M_PI / (2.0 * l + 1.0))) * zonal[l];
    for (int m = -l; m <= l; ++m) out[index(l, m)] = scale * y[index(l, m)];
  }
  return out;
}

template class Rotation<float>;
template class Rotation<double>;
template std::vector<float> rotateZonal<float>(std::span<const float>, const glm::vec3&);
template std::vector<double> rotateZonal<double>(std::span<const double>, const glm::dvec3&);

}  // namespace bounce::sh
