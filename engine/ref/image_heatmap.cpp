#include "engine/ref/image_heatmap.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.hpp"

namespace bounce::ref {

namespace {

// matplotlib viridis, entries 0, 5, 10, …, 255 of the 256-entry table (see the header).
constexpr int kViridisSize = 52;
constexpr float kViridis[kViridisSize][3] = {
    {0.267004f, 0.004874f, 0.329415f}, {0.273809f, 0.031497f, 0.358853f}, {0.278791f, 0.062145f, 0.386592f},
    {0.281924f, 0.089666f, 0.412415f}, {0.283197f, 0.115680f, 0.436115f}, {0.282623f, 0.140926f, 0.457517f},
    {0.280255f, 0.165693f, 0.476498f}, {0.276194f, 0.190074f, 0.493001f}, {0.270595f, 0.214069f, 0.507052f},
    {0.263663f, 0.237631f, 0.518762f}, {0.255645f, 0.260703f, 0.528312f}, {0.246811f, 0.283237f, 0.535941f},
    {0.237441f, 0.305202f, 0.541921f}, {0.227802f, 0.326594f, 0.546532f}, {0.218130f, 0.347432f, 0.550038f},
    {0.208623f, 0.367752f, 0.552675f}, {0.199430f, 0.387607f, 0.554642f}, {0.190631f, 0.407061f, 0.556089f},
    {0.182256f, 0.426184f, 0.557120f}, {0.174274f, 0.445044f, 0.557792f}, {0.166617f, 0.463708f, 0.558119f},
    {0.159194f, 0.482237f, 0.558073f}, {0.151918f, 0.500685f, 0.557587f}, {0.144759f, 0.519093f, 0.556572f},
    {0.137770f, 0.537492f, 0.554906f}, {0.131172f, 0.555899f, 0.552459f}, {0.125394f, 0.574318f, 0.549086f},
    {0.121148f, 0.592739f, 0.544641f}, {0.119423f, 0.611141f, 0.538982f}, {0.121380f, 0.629492f, 0.531973f},
    {0.128087f, 0.647749f, 0.523491f}, {0.140210f, 0.665859f, 0.513427f}, {0.157851f, 0.683765f, 0.501686f},
    {0.180653f, 0.701402f, 0.488189f}, {0.208030f, 0.718701f, 0.472873f}, {0.239374f, 0.735588f, 0.455688f},
    {0.274149f, 0.751988f, 0.436601f}, {0.311925f, 0.767822f, 0.415586f}, {0.352360f, 0.783011f, 0.392636f},
    {0.395174f, 0.797475f, 0.367757f}, {0.440137f, 0.811138f, 0.340967f}, {0.487026f, 0.823929f, 0.312321f},
    {0.535621f, 0.835785f, 0.281908f}, {0.585678f, 0.846661f, 0.249897f}, {0.636902f, 0.856542f, 0.216620f},
    {0.688944f, 0.865448f, 0.182725f}, {0.741388f, 0.873449f, 0.149561f}, {0.793760f, 0.880678f, 0.120005f},
    {0.845561f, 0.887322f, 0.099702f}, {0.896320f, 0.893616f, 0.096335f}, {0.945636f, 0.899815f, 0.112838f},
    {0.993248f, 0.906157f, 0.143936f},
};

}  // namespace

glm::vec3 viridis(float t) {
  if (std::isnan(t)) t = 0.0f;
  const float x = std::clamp(t, 0.0f, 1.0f) * float(kViridisSize - 1);
  const int i = std::min(static_cast<int>(x), kViridisSize - 2);
  const float f = x - float(i);
  const glm::vec3 a(kViridis[i][0], kViridis[i][1], kViridis[i][2]);
  const glm::vec3 b(kViridis[i + 1][0], kViridis[i + 1][1], kViridis[i + 1][2]);
  return a + (b - a) * f;
}

glm::u8vec3 viridis8(float t) {
  const glm::vec3 c = viridis(t);
  return {static_cast<std::uint8_t>(std::lround(c.r * 255.0f)), static_cast<std::uint8_t>(std::lround(c.g * 255.0f)),
          static_cast<std::uint8_t>(std::lround(c.b * 255.0f))};
}

HeatMap errorHeatMap(const ImageRGB& image, const ImageRGB& reference, const HeatMapOptions& options,
                     const PixelMask* mask) {
  if (!image.sameSize(reference))
    throw InternalError("errorHeatMap: image sizes differ (" + std::to_string(image.width) + "x" +
                        std::to_string(image.height) + " vs " + std::to_string(reference.width) + "x" +
                        std::to_string(reference.height) + ")");
  if (mask && (mask->width() != image.width || mask->height() != image.height))
    throw InternalError("errorHeatMap: mask size does not match the images");
  std::vector<double> err(image.pixels.size(), 0.0);
  double maxError = 0.0;
  for (std::size_t i = 0; i < err.size(); ++i) {
    const glm::dvec3 d = glm::abs(glm::dvec3(image.pixels[i]) - glm::dvec3(reference.pixels[i]));
    err[i] = (d.r + d.g + d.b) / 3.0;
    if (!mask || mask->testIndex(i)) maxError = std::max(maxError, err[i]);
  }
  HeatMap h;
  h.maxError = maxError;
  h.scale = options.scale > 0.0 ? options.scale : maxError;
  h.image = ImageSrgb8(image.width, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * image.width + x;
      if (mask && !mask->testIndex(i)) {
        h.image.set(x, y, options.outsideMask);
        continue;
      }
      const double t = h.scale > 0.0 ? err[i] / h.scale : 0.0;
      h.image.set(x, y, viridis8(static_cast<float>(t)));
    }
  return h;
}

ImageSrgb8 sideBySide(std::span<const ImageSrgb8> panels, int gap, glm::u8vec3 gapColour) {
  if (panels.empty()) return {};
  gap = std::max(gap, 0);
  int width = gap * (static_cast<int>(panels.size()) - 1), height = 0;
  for (const auto& p : panels) {
    width += p.width;
    height = std::max(height, p.height);
  }
  ImageSrgb8 out(width, height, gapColour);
  int x0 = 0;
  for (const auto& p : panels) {
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) out.set(x0 + x, y, p.at(x, y));
    x0 += p.width + gap;
  }
  return out;
}

Comparison comparisonImage(const ImageRGB& reference, const ImageRGB& image, const ComparisonOptions& options,
                           const PixelMask* mask) {
  const HeatMap heat = errorHeatMap(image, reference, options.heatMap, mask);
  ImageSrgb8 heatPanel = heat.image;
  if (options.colourBarHeight > 0 && heatPanel.width > 0) {
    // Heat map, `gap` black rows, then the bar: column x shows viridis(x / (width − 1)).
    const int gap = std::max(options.gap, 0);
    ImageSrgb8 withBar(heatPanel.width, heatPanel.height + gap + options.colourBarHeight);
    for (int y = 0; y < heatPanel.height; ++y)
      for (int x = 0; x < heatPanel.width; ++x) withBar.set(x, y, heatPanel.at(x, y));
    const float denom = static_cast<float>(std::max(heatPanel.width - 1, 1));
    for (int y = heatPanel.height + gap; y < withBar.height; ++y)
      for (int x = 0; x < heatPanel.width; ++x) withBar.set(x, y, viridis8(static_cast<float>(x) / denom));
    heatPanel = std::move(withBar);
  }
  const ImageSrgb8 panels[] = {toSrgb8(reference, options.exposure), toSrgb8(image, options.exposure), heatPanel};
  return {sideBySide(panels, options.gap), heat.scale, heat.maxError};
}

}  // namespace bounce::ref
