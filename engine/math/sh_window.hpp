#pragma once
// Windowing against ringing. A truncated SH projection of a small bright light rings: the
// reconstruction has negative lobes (negative radiance, then negative irradiance on the far
// side). Scaling band l by a factor w_l that decreases with l is a convolution with a zonal
// kernel (Funk–Hecke), which trades sharpness for smaller lobes.
//
// Both windows take a width W in band units: w_0 = 1 and w_l = 0 for l >= W; a larger W filters
// less (W → ∞ gives w_l → 1), W <= 1 keeps only band 0.
//  - Hann:  w_l = (1 + cos(π l / W)) / 2 (Sloan 2008, "Stupid SH Tricks" §windowing).
//  - Sloan: w_l = sinc⁴(π l / W), the window of Sloan 2017, "Deringing Spherical Harmonics"
//    (SIGGRAPH Asia technical brief), as used by Filament's cmgen; its kernel is positive and
//    narrower than Hann's for the same width, so it keeps more contrast per unit of deringing.
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/math/sh_eval.hpp"

namespace bounce::sh {

enum class Window { Hann, Sloan };

// w_l for band l >= 0 and width W > 0 (W = +inf gives 1).
double windowWeight(Window kind, int l, double width);

template <typename V>
std::vector<V> applyWindow(std::span<const V> coeffs, Window kind, double width) {
  const int order = orderFromCount(coeffs.size());
  std::vector<V> out(coeffs.begin(), coeffs.end());
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m) out[index(l, m)] *= windowWeight(kind, l, width);
  return out;
}

// Smallest value of Σ c_i Y_i(d) over `directions` (unit vectors).
double minValue(std::span<const double> coeffs, std::span<const glm::dvec3> directions);

// A width W (as little filtering as found) for which the windowed reconstruction is
// >= -tolerance along every direction: bisection on W in [1, 64] to 1e-4 relative, as Filament's
// cmgen does. Bisection finds a W at which the minimum crosses -tolerance; if the minimum is not
// monotone in W a larger valid W may exist, so the result can be conservative but is never
// wrong (every W returned was checked):
//  - +inf when the coefficients are already non-negative along `directions` (no window needed);
//  - nullopt when even band 0 alone is below -tolerance (c_0 < 0: no window can help).
std::optional<double> minimalWindow(std::span<const double> coeffs, Window kind,
                                    std::span<const glm::dvec3> directions, double tolerance = 0.0);

// RGB: the smallest per-channel width, so every channel is non-negative with one shared window.
std::optional<double> minimalWindow(std::span<const glm::dvec3> coeffs, Window kind,
                                    std::span<const glm::dvec3> directions, double tolerance = 0.0);

}  // namespace bounce::sh
