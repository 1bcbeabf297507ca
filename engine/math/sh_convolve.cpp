#include "engine/math/sh_convolve.hpp"

#include <cmath>
#include <string>

#include "engine/core/error.hpp"

namespace bounce::sh {

double cosineLobeBand(int l) {
  if (l < 0) throw InternalError("sh::cosineLobeBand: band " + std::to_string(l));
  if (l == 0) return M_PI;
  if (l == 1) return 2.0 * M_PI / 3.0;
  if (l % 2 == 1) return 0.0;
  // R&H 2001 eq. 9 (even l >= 2): Â_l = 2π (-1)^{l/2-1} / ((l+2)(l-1)) · l! / (2^l ((l/2)!)²).
  double binom = 1.0;  // l! / ((l/2)!)² / 2^l, built incrementally to stay in range
  for (int k = 1; k <= l / 2; ++k) binom *= double(l / 2 + k) / k / 4.0;
  const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
  return 2.0 * M_PI * sign / ((l + 2.0) * (l - 1.0)) * binom;
}

}  // namespace bounce::sh
