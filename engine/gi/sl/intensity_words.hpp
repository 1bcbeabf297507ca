#pragma once
// The layout of pass 1's output, which pass 2 reads as a uniform block (shaders/sl/intensity.comp
// writes it, shaders/sl/sl_data.glsl slIntensityPair reads it): every SL's L^c (order² RGB
// coefficients, the SL's local frame) as fp16 pairs — ours, for cost. Pass 2 reads an SL's
// intensity per lane (the SL index differs between a tile's pixels), and llvmpipe gathers a
// non-uniform uniform-block read one 32-bit component at a time: 48 gathers per live SL as rgb
// float, 24 as half pairs (README "SL intensity as fp16 pairs").
//
// Per SL kIntensityWordsPerSl = 24 words (6 uvec4): word 8c + m = packHalf2x16(L^c_{2m}[c],
// L^c_{2m+1}[c]) for channel c ∈ {r, g, b} and pair m ∈ 0 … 7 (GLSL packHalf2x16: the first value
// in the low 16 bits). Coefficients ≥ order² are 0. Values are clamped to ±kIntensityHalfMax.
//
// Precision: round to nearest half, a relative error ≤ 2⁻¹¹ per coefficient (kIntensityHalfRelative;
// below half's normal range, 2⁻²⁵ absolute). Tests compare pass 1 against its double reference with
// this added to their bound, and pass 2 against sl::evaluate on intensities rounded the same way.
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>

namespace bounce::gi::sl {

inline constexpr std::uint32_t kIntensityWordsPerSl = 24;
inline constexpr float kIntensityHalfMax = 65504.0f;          // largest finite half
inline constexpr double kIntensityHalfRelative = 1.0 / 2048.0;  // half's rounding, 2⁻¹¹

// Up to 16 coefficients → one SL's 24 words (missing coefficients are 0).
inline std::array<std::uint32_t, kIntensityWordsPerSl> packIntensity(std::span<const glm::vec3> coeffs) {
  std::array<std::uint32_t, kIntensityWordsPerSl> words{};
  auto at = [&](std::size_t k, int c) {
    return k < coeffs.size() ? std::clamp(coeffs[k][c], -kIntensityHalfMax, kIntensityHalfMax) : 0.0f;
  };
  for (int c = 0; c < 3; ++c)
    for (std::size_t m = 0; m < 8; ++m)
      words[std::size_t(8 * c) + m] = glm::packHalf2x16(glm::vec2(at(2 * m, c), at(2 * m + 1, c)));
  return words;
}

// One SL's 24 words → its 16 coefficients (as pass 2 reads them).
inline std::array<glm::vec3, 16> unpackIntensity(std::span<const std::uint32_t> words) {
  std::array<glm::vec3, 16> out{};
  for (int c = 0; c < 3; ++c)
    for (std::size_t m = 0; m < 8; ++m) {
      const glm::vec2 v = glm::unpackHalf2x16(words[std::size_t(8 * c) + m]);
      out[2 * m][c] = v.x;
      out[2 * m + 1][c] = v.y;
    }
  return out;
}

}  // namespace bounce::gi::sl
