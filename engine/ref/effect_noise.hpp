#pragma once
// The reference's own noise in an object effect, and an error corrected for it (issues 13, 15:
// several indirect-only goals sit inside the path tracer's noise).
//
// Notation as in metrics.hpp objectEffectError: r = refWith − refWithout is the reference's
// effect, t = techWith − techWithout the technique's, sums over the selected pixels and channels,
// e = ||t − r|| / ||r|| the reported relative error. A reference of N samples per pixel is
// r = r* + n with r* the converged effect and n its Monte-Carlo noise (zero mean, independent of
// the technique's t).
//
// Estimating ||n||². Split the N samples into two independent halves h1, h2 (N/2 each; the
// tracer draws sample s from index s, so the N/2-sample reference IS h1, and h2 = 2·r − h1).
// r = (h1 + h2)/2 carries noise of variance σ²/2 per value when each half carries σ²; their
// difference d = r − h1 = (h2 − h1)/2 = (n2 − n1)/2 carries (σ² + σ²)/4 = σ²/2 too, and no r*.
// So E||d||² = E||n||²: d is a sample of the full reference's noise, at no extra trace beyond the
// N/2 samples already in r. with and without are traced with the same sample indices, so their
// correlated noise cancels in r and in d alike.
//
// The floor. E[||t − r||²] = ||t − r*||² + E||n||² (cross term zero mean), and
// E||r||² = ||r*||² + E||n||². A perfect technique (t = r*) scores e = ||n|| / ||r||, not 0:
//   floor f = ||d|| / ||r||                                       [unitless, 0 ≤ f]
// The corrected error, against the converged effect, keeping "1 = effect missing":
//   e* = ||t − r*|| / ||r*|| = sqrt( (e² − f²) / (1 − f²) )        (0 when e < f; undefined at f ≥ 1)
// since ||t − r*||² = e²||r||² − ||d||² and ||r*||² = ||r||² − ||d||². (The plain
// sqrt(e² − f²) would be ||t − r*|| / ||r||: a technique that leaves the effect out would score
// sqrt(1 − f²) < 1 instead of 1.) Both are estimates: per image the cross terms are not zero, so
// e* of a perfect technique scatters around 0 by ~f·sqrt(2/M) for M selected values.
// tools/effect_noise.py prints the same numbers from `bounce accuracy --effect-images` output.
#include <cstddef>

#include "engine/core/image.hpp"
#include "engine/ref/metrics.hpp"

namespace bounce::ref {

struct EffectNoise {
  std::size_t pixelCount = 0;
  double effectRms = 0.0;  // sqrt(||r||² / M), M = pixels × 3   [radiance units]
  double noiseRms = 0.0;   // sqrt(||d||² / M): the estimated rms of r's noise   [radiance units]
  double floor = 0.0;      // noiseRms / effectRms; NaN when effectIsZero
  bool effectIsZero = false;  // effectRms ≤ zeroEffectRms (metrics.hpp): no ratio
};

// fullWith/fullWithout: the N-sample references; halfWith/halfWithout: the first N/2 of the same
// samples. All the same size (InternalError otherwise); mask as in metrics.hpp (null: all pixels).
EffectNoise effectNoise(const ImageRGB& fullWith, const ImageRGB& fullWithout, const ImageRGB& halfWith,
                        const ImageRGB& halfWithout, const PixelMask* mask = nullptr,
                        double zeroEffectRms = kDefaultZeroEffectRms);

// e* above: the error against the converged effect; NaN when e or floor is NaN or floor ≥ 1 (the
// effect is all noise at this sample count).
double noiseCorrectedError(double error, double floor);

}  // namespace bounce::ref
