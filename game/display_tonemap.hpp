#pragma once
// The display transform of shaders/passes/tonemap.frag on the CPU — exposure, Khronos PBR Neutral,
// sRGB — for previews of linear images the GPU did not draw (`bounce reference` writes one beside
// its PFM). Tested against the GPU's own PNG of a capture (tests/unit/viewer).
#include <cstdint>
#include <vector>

#include "engine/gpu/image_io.hpp"

namespace bounce::game {

// RGBA8 (alpha 255), rows top to bottom, as the tonemap pass writes them.
std::vector<std::uint8_t> tonemapToSrgb8(const gpu::FloatImage& image, float exposure = 1.0f);

}  // namespace bounce::game
