#include "engine/ref/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/core/error.hpp"

namespace bounce::ref {

PixelMask::PixelMask(int width, int height, bool initial) : width_(width), height_(height) {
  if (width < 0 || height < 0)
    throw InternalError("PixelMask: negative size " + std::to_string(width) + "x" + std::to_string(height));
  bits_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), initial ? 1 : 0);
}

void PixelMask::setRect(int x0, int y0, int x1, int y1, bool on) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, width_);
  y1 = std::min(y1, height_);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) set(x, y, on);
}

std::size_t PixelMask::count() const {
  return static_cast<std::size_t>(std::count_if(bits_.begin(), bits_.end(), [](std::uint8_t b) { return b != 0; }));
}

namespace {

std::string sizeText(const ImageRGB& img) { return std::to_string(img.width) + "x" + std::to_string(img.height); }

void checkSizes(const char* fn, const ImageRGB& a, const ImageRGB& b, const PixelMask* mask) {
  if (!a.sameSize(b))
    throw InternalError(std::string(fn) + ": image sizes differ (" + sizeText(a) + " vs " + sizeText(b) + ")");
  if (mask && (mask->width() != a.width || mask->height() != a.height))
    throw InternalError(std::string(fn) + ": mask " + std::to_string(mask->width()) + "x" +
                        std::to_string(mask->height()) + " does not match image " + sizeText(a));
}

// Relative value with the convention documented in metrics.hpp for an undefined denominator.
double ratioOrInf(double num, double den) {
  if (den > 0.0) return num / den;
  return num == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
}

}  // namespace

ErrorStats computeErrorStats(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask,
                             double relativeEpsilon) {
  checkSizes("computeErrorStats", image, reference, mask);
  // Double accumulators: a 4K image has 25M channel values; float sums would lose ~3 digits.
  double sumSq = 0.0, sumRelSq = 0.0, sumAbs = 0.0, sumRef = 0.0, maxAbs = 0.0;
  double refMax = -std::numeric_limits<double>::infinity();
  std::size_t count = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (mask && !mask->testIndex(i)) continue;
    ++count;
    for (int c = 0; c < 3; ++c) {
      const double a = image.pixels[i][c];
      const double r = reference.pixels[i][c];
      const double d = a - r;
      sumSq += d * d;
      sumRelSq += d * d / (r * r + relativeEpsilon);
      sumAbs += std::abs(d);
      sumRef += r;
      maxAbs = std::max(maxAbs, std::abs(d));
      refMax = std::max(refMax, r);
    }
  }
  ErrorStats s;
  s.pixelCount = count;
  if (count == 0) return s;
  const double n = 3.0 * static_cast<double>(count);
  s.rmse = std::sqrt(sumSq / n);
  s.perPixelRelativeRmse = std::sqrt(sumRelSq / n);
  s.mae = sumAbs / n;
  s.maxAbs = maxAbs;
  s.referenceMean = sumRef / n;
  s.referenceMax = refMax;
  s.relativeDefined = s.referenceMean > 0.0;
  s.relativeRmse = ratioOrInf(s.rmse, s.referenceMean);
  return s;
}

double rmse(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask) {
  return computeErrorStats(image, reference, mask).rmse;
}

double relativeRmse(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask) {
  return computeErrorStats(image, reference, mask).relativeRmse;
}

double perPixelRelativeRmse(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask, double epsilon) {
  return computeErrorStats(image, reference, mask, epsilon).perPixelRelativeRmse;
}

double meanAbsoluteError(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask) {
  return computeErrorStats(image, reference, mask).mae;
}

double maxAbsoluteError(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask) {
  return computeErrorStats(image, reference, mask).maxAbs;
}

double psnr(const ImageRGB& image, const ImageRGB& reference, const PixelMask* mask, double peak) {
  const ErrorStats s = computeErrorStats(image, reference, mask);
  const double p = peak > 0.0 ? peak : s.referenceMax;
  const double mse = s.rmse * s.rmse;
  if (mse == 0.0) return std::numeric_limits<double>::infinity();
  if (!(p > 0.0)) return -std::numeric_limits<double>::infinity();  // black reference, some error
  return 10.0 * std::log10(p * p / mse);
}

ObjectEffectError objectEffectError(const ImageRGB& techWith, const ImageRGB& techWithout, const ImageRGB& refWith,
                                    const ImageRGB& refWithout, const PixelMask* mask, double zeroEffectRms) {
  checkSizes("objectEffectError", techWith, techWithout, mask);
  checkSizes("objectEffectError", techWith, refWith, mask);
  checkSizes("objectEffectError", techWith, refWithout, mask);
  double sumDiffSq = 0.0, sumRefSq = 0.0, sumTechSq = 0.0, sumRef = 0.0, sumTech = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < techWith.pixels.size(); ++i) {
    if (mask && !mask->testIndex(i)) continue;
    ++count;
    for (int c = 0; c < 3; ++c) {
      const double et = double(techWith.pixels[i][c]) - double(techWithout.pixels[i][c]);
      const double er = double(refWith.pixels[i][c]) - double(refWithout.pixels[i][c]);
      sumDiffSq += (et - er) * (et - er);
      sumRefSq += er * er;
      sumTechSq += et * et;
      sumRef += er;
      sumTech += et;
    }
  }
  ObjectEffectError e;
  e.pixelCount = count;
  if (count == 0) {
    e.referenceEffectIsZero = true;
    return e;
  }
  const double n = 3.0 * static_cast<double>(count);
  e.effectRmse = std::sqrt(sumDiffSq / n);
  e.referenceRms = std::sqrt(sumRefSq / n);
  e.techniqueRms = std::sqrt(sumTechSq / n);
  e.energyRatio = sumRef != 0.0 ? sumTech / sumRef : 0.0;
  e.referenceEffectIsZero = !(e.referenceRms > zeroEffectRms);
  e.relativeError = e.referenceEffectIsZero ? e.effectRmse : e.effectRmse / e.referenceRms;
  return e;
}

}  // namespace bounce::ref
