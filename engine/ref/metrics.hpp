#pragma once
// Image error metrics, computed in LINEAR radiance (never on tonemapped 8-bit values, whose
// curve would weight errors by brightness in a way no technique is designed for).
//
// Notation: a = the image under test (a technique's capture), r = the reference (path tracer),
// N = number of selected pixels × 3 channels, sums run over selected pixels and all channels.
//
//   rmse                 = sqrt( Σ (a−r)² / N )                               [radiance units]
//   relativeRmse         = rmse / mean(r),  mean(r) = Σ r / N                 [unitless]
//   perPixelRelativeRmse = sqrt( Σ (a−r)² / (r² + ε) / N )                   [unitless]
//   mae                  = Σ |a−r| / N;   maxAbs = max |a−r|                  [radiance units]
//   psnr                 = 10·log10( peak² / mse ),  peak = max(r) unless given [dB]
//
// Which relative RMSE is the headline number, and why: `relativeRmse` (RMSE normalised by the
// reference's mean). Indirect light from an object is zero over most of the screen and small
// in the rest; the per-pixel form divides by r² and so lets near-black pixels (whose values are
// path-tracer noise) dominate, with a result that depends on the arbitrary ε. The normalised
// form weights errors by energy, is invariant under scaling both images by the same factor
// (exposure, light intensity: tested), and has no tuning constant. The per-pixel form ("relMSE",
// common in the Monte-Carlo denoising literature) is offered as well because it does show
// errors in dark regions (e.g. DNRT's darkening under an object) that the energy-weighted
// number hides; it is scale-invariant only if ε is scaled by s² too.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/core/image.hpp"

namespace bounce::ref {

// Selects the pixels a metric looks at (e.g. the screen region an object can affect).
class PixelMask {
 public:
  PixelMask() = default;
  PixelMask(int width, int height, bool initial = false);

  int width() const { return width_; }
  int height() const { return height_; }
  bool test(int x, int y) const { return bits_[index(x, y)] != 0; }
  void set(int x, int y, bool on = true) { bits_[index(x, y)] = on ? 1 : 0; }
  bool testIndex(std::size_t i) const { return bits_[i] != 0; }
  // Sets every pixel of the rectangle [x0,x1)×[y0,y1), clipped to the mask.
  void setRect(int x0, int y0, int x1, int y1, bool on = true);
  std::size_t count() const;

 private:
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> bits_;
};

// ε of the per-pixel relative form, in squared radiance units. 1e-2 keeps pixels darker than
// ~0.1 from dominating at the radiance scale our levels use (sun ≈ 1–10, indirect ≈ 0.01–1).
inline constexpr double kDefaultRelativeEpsilon = 1e-2;

// Every metric of one comparison, computed in a single pass.
struct ErrorStats {
  std::size_t pixelCount = 0;  // selected pixels (all when no mask)
  double rmse = 0.0;
  double relativeRmse = 0.0;  // see relativeDefined
  double perPixelRelativeRmse = 0.0;
  double mae = 0.0;
  double maxAbs = 0.0;
  double referenceMean = 0.0;  // mean(r) over the selection
  double referenceMax = 0.0;   // max channel value of r over the selection
  // False when mean(r) ≤ 0 (black reference) or nothing is selected: relativeRmse is then 0 if
  // rmse is 0 and +inf otherwise, so a comparison against black never passes a tolerance
  // unless it is exact.
  bool relativeDefined = false;
};

// Sizes must match (InternalError otherwise: callers that load images from files check sizes
// first so that they can name the files). `mask` may be null (all pixels) or of the same size.
// With zero selected pixels every field is 0 and relativeDefined is false.
ErrorStats computeErrorStats(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask = nullptr,
                             double relativeEpsilon = kDefaultRelativeEpsilon);

// The same numbers one at a time (each is the corresponding ErrorStats field).
double rmse(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask = nullptr);
double relativeRmse(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask = nullptr);
double perPixelRelativeRmse(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask = nullptr,
                            double epsilon = kDefaultRelativeEpsilon);
double meanAbsoluteError(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask = nullptr);
double maxAbsoluteError(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask = nullptr);
// peak ≤ 0 means "max(r) over the selection". +inf for identical images.
double psnr(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask = nullptr, double peak = 0.0);

// Below this RMS (radiance units) a reference object effect counts as zero: it is ~10× float
// rounding (2^-23 ≈ 1.2e-7) of radiances around 1, so "with − without" of two renders that
// differ only by rounding lands under it.
inline constexpr double kDefaultZeroEffectRms = 1e-6;

// How well a technique reproduces ONE object's effect on the rest of the scene (DNRT/VLM/SL/RTF
// comparisons): the technique's effect e_t = techWith − techWithout is compared with the
// reference's effect e_r = refWith − refWithout. Subtracting the "without" images cancels the
// shared direct light and the error of everything else, so the number isolates the object's
// indirect contribution (bounce light and darkening alike; e_r may be negative).
//
//   effectRmse     = sqrt( Σ (e_t − e_r)² / N )       [radiance units]
//   referenceRms   = sqrt( Σ e_r² / N )               [radiance units]
//   relativeError  = effectRmse / referenceRms        [unitless; 0 perfect, 1 = as wrong as
//                                                       leaving the effect out entirely]
//   energyRatio    = Σ e_t / Σ e_r                    [1 = right total amount of light added
//                                                       or removed; 0 if Σ e_r is 0]
// Normalising by the RMS of the effect (not by the mean of the image) makes objects with small
// and large effects comparable, and gives the reading "1.0 = no better than omitting it".
// When referenceRms ≤ zeroEffectRms the ratio is meaningless: relativeError then holds the
// ABSOLUTE effectRmse and referenceEffectIsZero is set, so the caller reports it differently.
struct ObjectEffectError {
  std::size_t pixelCount = 0;
  double effectRmse = 0.0;
  double referenceRms = 0.0;
  double techniqueRms = 0.0;
  double relativeError = 0.0;
  double energyRatio = 0.0;
  bool referenceEffectIsZero = false;
};

// All four images must have the same size (InternalError otherwise); mask as above.
ObjectEffectError objectEffectError(const ImageRGB& techWith, const ImageRGB& techWithout, const ImageRGB& refWith,
                                    const ImageRGB& refWithout, const PixelMask* mask = nullptr,
                                    double zeroEffectRms = kDefaultZeroEffectRms);

}  // namespace bounce::ref
