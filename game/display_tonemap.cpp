#include "game/display_tonemap.hpp"

#include <algorithm>
#include <cmath>

namespace bounce::game {
namespace {

// shaders/common/color.glsl pbrNeutralTonemap, line for line.
void pbrNeutral(float c[3]) {
  constexpr float kStartCompression = 0.8f - 0.04f;
  constexpr float kDesaturation = 0.15f;
  const float x = std::min(c[0], std::min(c[1], c[2]));
  const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
  for (int k = 0; k < 3; ++k) c[k] -= offset;
  const float peak = std::max(c[0], std::max(c[1], c[2]));
  if (peak < kStartCompression) return;
  constexpr float d = 1.0f - kStartCompression;
  const float newPeak = 1.0f - d * d / (peak + d - kStartCompression);
  const float g = 1.0f - 1.0f / (kDesaturation * (peak - newPeak) + 1.0f);
  for (int k = 0; k < 3; ++k) c[k] = c[k] * (newPeak / peak) * (1.0f - g) + newPeak * g;
}

float linearToSrgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c < 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

std::vector<std::uint8_t> tonemapToSrgb8(const gpu::FloatImage& image, float exposure) {
  std::vector<std::uint8_t> out(std::size_t(image.width) * image.height * 4, 255);
  for (std::size_t i = 0; i < std::size_t(image.width) * image.height; ++i) {
    float c[3];
    for (int k = 0; k < 3; ++k) c[k] = std::max(image.rgb[i * 3 + k] * exposure, 0.0f);
    pbrNeutral(c);
    for (int k = 0; k < 3; ++k) out[i * 4 + k] = std::uint8_t(std::lround(linearToSrgb(c[k]) * 255.0f));
  }
  return out;
}

}  // namespace bounce::game
