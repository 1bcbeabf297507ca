#include "engine/math/sh_window.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/core/error.hpp"

namespace bounce::sh {

double windowWeight(Window kind, int l, double width) {
  if (l < 0 || !(width > 0.0)) throw InternalError("sh::windowWeight: band " + std::to_string(l) + " width " + std::to_string(width));
  if (l == 0 || std::isinf(width)) return 1.0;
  if (l >= width) return 0.0;
  const double x = M_PI * l / width;  // finite width here
  switch (kind) {
    case Window::Hann: return 0.5 * (1.0 + std::cos(x));
    case Window::Sloan: {
      const double s = std::sin(x) / x;
      return s * s * s * s;
    }
  }
  throw InternalError("sh::windowWeight: unknown window");
}

double minValue(std::span<const double> coeffs, std::span<const glm::dvec3> directions) {
  double lo = std::numeric_limits<double>::infinity();
  for (const auto& d : directions) lo = std::min(lo, evalSum<double, double>(coeffs, d));
  return lo;
}

std::optional<double> minimalWindow(std::span<const double> coeffs, Window kind,
                                    std::span<const glm::dvec3> directions, double tolerance) {
  orderFromCount(coeffs.size());
  const auto ok = [&](double width) {
    const auto w = applyWindow<double>(coeffs, kind, width);
    return minValue(w, directions) >= -tolerance;
  };
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (ok(kInf)) return kInf;
  double lo = 1.0, hi = 64.0;  // at W = 1 only band 0 is left
  if (!ok(lo)) return std::nullopt;
  if (ok(hi)) return hi;
  while (hi - lo > 1e-4 * lo) {
    const double mid = 0.5 * (lo + hi);
    (ok(mid) ? lo : hi) = mid;
  }
  return lo;  // ok(lo) holds by construction
}

std::optional<double> minimalWindow(std::span<const glm::dvec3> coeffs, Window kind,
                                    std::span<const glm::dvec3> directions, double tolerance) {
  double width = std::numeric_limits<double>::infinity();
  std::vector<double> channel(coeffs.size());
  for (int c = 0; c < 3; ++c) {
    for (std::size_t i = 0; i < coeffs.size(); ++i) channel[i] = coeffs[i][c];
    const auto w = minimalWindow(channel, kind, directions, tolerance);
    if (!w) return std::nullopt;
    width = std::min(width, *w);
  }
  return width;
}

}  // namespace bounce::sh
