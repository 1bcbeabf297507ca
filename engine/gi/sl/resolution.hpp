#pragma once
// SL pass 2's resolution (level key "sl": {"resolution": "full"|"half"|"quarter"}; README "SL at
// quarter resolution, session 10"): pass 2 shades one G-buffer pixel in step × step — pixel j of the
// reduced target stands for G-buffer pixel step·j — and "sl.upsample" (shaders/sl/upsample.frag)
// spreads it over every pixel with depth and normal weights. One code path for every factor: the
// step is a specialization constant of the pass-2 shaders (kStep) and of the upsample.
#include <cstdint>

#include <glm/vec2.hpp>

namespace bounce::gi::sl {

enum class Resolution { Full, Half, Quarter };

// G-buffer pixels per pass-2 sample along each axis: 1, 2 or 4.
inline std::uint32_t resolutionStep(Resolution r) { return r == Resolution::Quarter ? 4u : r == Resolution::Half ? 2u : 1u; }
inline Resolution resolutionFromStep(int step) {
  return step >= 4 ? Resolution::Quarter : step == 2 ? Resolution::Half : Resolution::Full;
}
// The reduced target's size: ceil(size / step), so its last sample covers the G-buffer's last pixels.
inline glm::uvec2 reducedSize(glm::uvec2 size, std::uint32_t step) { return (size + (step - 1u)) / step; }
// The transient target pass 2 writes at a reduced resolution ("sl.half" or "sl.quarter").
inline const char* reducedTargetName(std::uint32_t step) { return step >= 4 ? "sl.quarter" : "sl.half"; }

}  // namespace bounce::gi::sl
