#include "engine/ref/effect_noise.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bounce::ref {

EffectNoise effectNoise(const ImageRGB& fullWith, const ImageRGB& fullWithout, const ImageRGB& halfWith,
                        const ImageRGB& halfWithout, const PixelMask* mask, double zeroEffectRms) {
  // objectEffectError with the full reference in the technique's place: its effectRmse is
  // rms(r_full − r_half) = rms(d) and its techniqueRms is rms(r_full) (one definition of the
  // effect and of the sums, metrics.cpp).
  const ObjectEffectError e = objectEffectError(fullWith, fullWithout, halfWith, halfWithout, mask, zeroEffectRms);
  EffectNoise out;
  out.pixelCount = e.pixelCount;
  out.effectRms = e.techniqueRms;
  out.noiseRms = e.effectRmse;
  out.effectIsZero = e.pixelCount == 0 || !(out.effectRms > zeroEffectRms);
  out.floor = out.effectIsZero ? std::numeric_limits<double>::quiet_NaN() : out.noiseRms / out.effectRms;
  return out;
}

double noiseCorrectedError(double error, double floor) {
  if (!std::isfinite(error) || !std::isfinite(floor) || floor >= 1.0) return std::numeric_limits<double>::quiet_NaN();
  const double f2 = floor * floor;
  return std::sqrt(std::max(0.0, error * error - f2) / (1.0 - f2));
}

}  // namespace bounce::ref
