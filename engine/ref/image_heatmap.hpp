#pragma once
// Error heat maps and side-by-side panels for captures and failed golden tests.
//
// Colour map: matplotlib's "viridis" (Stéfan van der Walt and Nathaniel Smith, 2015, "mpl
// colormaps", released CC0; https://bids.github.io/colormap/). It is perceptually uniform
// (equal steps in error look like equal steps in colour), monotonic in lightness (readable in
// greyscale) and colour-blind safe — a rainbow map has none of these. We keep every 5th entry of
// the 256-entry table (52 entries, indices 0, 5, …, 255) and interpolate linearly; that
// deviates from the full table by at most 0.62/255 per channel, below one 8-bit step.
#include <span>

#include <glm/glm.hpp>

#include "engine/core/image.hpp"
#include "engine/ref/metrics.hpp"

namespace bounce::ref {

// viridis(t) for t in [0,1] (clamped; NaN → 0), as sRGB-encoded values in [0,1] — the table
// is defined in sRGB, so these are written to 8-bit images without another transfer function.
glm::vec3 viridis(float t);
// viridis(t) rounded to 8-bit codes.
glm::u8vec3 viridis8(float t);

struct HeatMapOptions {
  // Error value drawn with the top colour of the map (radiance units); larger errors saturate.
  // ≤ 0: use the largest per-pixel error in the image (stated back in HeatMap::scale). Give a
  // fixed scale when several heat maps must be compared by eye.
  double scale = 0.0;
  // Colour of pixels outside the mask (when a mask is given): mid grey, not in viridis.
  glm::u8vec3 outsideMask{128, 128, 128};
};

struct HeatMap {
  ImageSrgb8 image;
  double scale = 0.0;     // the error that maps to viridis(1)
  double maxError = 0.0;  // largest per-pixel error found (over the mask)
};

// Per-pixel error e = (|a.r−r.r| + |a.g−r.g| + |a.b−r.b|) / 3 (the per-pixel MAE, linear
// radiance), drawn as viridis(e / scale). When every error is 0 and no scale is given the
// scale is reported as 0 and every pixel is viridis(0). Sizes must match (InternalError).
HeatMap errorHeatMap(const ImageRGB& image, const ImageRGB& reference, const HeatMapOptions& options = {},
                     const PixelMask* mask = nullptr);

// Panels placed left to right with `gap` columns of `gapColour` between them, top-aligned;
// the height is the tallest panel's, shorter panels are padded below with gapColour.
ImageSrgb8 sideBySide(std::span<const ImageSrgb8> panels, int gap = 4, glm::u8vec3 gapColour = {0, 0, 0});

struct ComparisonOptions {
  HeatMapOptions heatMap;
  float exposure = 1.0f;  // applied to reference and image alike before sRGB encoding
  int gap = 4;
  // Height in pixels of a colour bar under the heat-map panel (0 = none). It runs from error 0
  // at the left to HeatMap::scale at the right, so the picture carries its own key.
  int colourBarHeight = 8;
};

struct Comparison {
  ImageSrgb8 image;  // reference | image | heat map  (+ colour bar under the heat map)
  double scale = 0.0;
  double maxError = 0.0;
};

// The standard capture panel: "reference | image | heat map".
Comparison comparisonImage(const ImageRGB& reference, const ImageRGB& image, const ComparisonOptions& options = {},
                           const PixelMask* mask = nullptr);

}  // namespace bounce::ref
