#pragma once
// A deferred pass's reduced resolution, shared by SL pass 2 (level key "sl": {"resolution": …}; README
// "SL at quarter resolution, session 10"), DNRT ("dnrt": {"resolution": …}; README "DNRT at half
// resolution, session 15") and RTF ("rtf": {"resolution": …}; README "RTF at half and quarter
// resolution, session 25"): the pass shades one G-buffer pixel in step × step — pixel j of the
// reduced target stands for G-buffer pixel step·j — and an upsample (shaders/common/upsample.glsl,
// engine/gi/upsample.hpp) spreads it over every pixel with depth and normal weights. One code path
// for every factor: the step is a specialization constant of the shaders (kStep) and of the upsample.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>

#include "engine/core/error.hpp"

namespace bounce::gi {

enum class Resolution { Full, Half, Quarter };

// The only steps: 1, 2 and 4. Powers of two on purpose — the upsample's bilinear fraction is an exact
// ldexp by −log2(step) (shaders/common/upsample.glsl upsampleTaps) — and one name each below.
inline bool isResolutionStep(std::uint32_t step) { return step == 1u || step == 2u || step == 4u; }
// Throws InternalError unless `step` is 1, 2 or 4 (a bug: the level and `bounce bench` parse names).
inline std::uint32_t checkedStep(std::uint32_t step) {
  if (!isResolutionStep(step))
    throw InternalError("resolution step " + std::to_string(step) + " (expected 1, 2 or 4)");
  return step;
}
// A step's index among 1, 2, 4 (0, 1, 2): the passes' per-step pipeline arrays.
inline std::size_t stepIndex(std::uint32_t step) { return checkedStep(step) == 4u ? 2u : step == 2u ? 1u : 0u; }

// G-buffer pixels per pass-2 sample along each axis: 1, 2 or 4.
inline std::uint32_t resolutionStep(Resolution r) { return r == Resolution::Quarter ? 4u : r == Resolution::Half ? 2u : 1u; }
inline Resolution resolutionFromStep(std::uint32_t step) {
  return checkedStep(step) == 4u ? Resolution::Quarter : step == 2u ? Resolution::Half : Resolution::Full;
}
// The level's / `bounce bench --sl-resolution`'s name of a step: "full" (1), "half" (2), "quarter" (4).
inline const char* resolutionName(std::uint32_t step) {
  return checkedStep(step) == 4u ? "quarter" : step == 2u ? "half" : "full";
}
// The step a name stands for, nothing for an unknown name (the caller reports it with its place).
inline std::optional<std::uint32_t> parseResolution(std::string_view name) {
  for (const std::uint32_t step : {1u, 2u, 4u})
    if (name == resolutionName(step)) return step;
  return std::nullopt;
}
// What parseResolution accepts, for the "(expected …)" of an error.
inline constexpr const char* kResolutionNames = "full, half or quarter";
// A command's list of names (`bounce bench … --sl-resolution full,half`): their steps in order; an unknown
// name is one InputError at `place` of `file`.
inline std::vector<std::uint32_t> parseResolutionList(const std::vector<std::string>& names, const std::string& file,
                                                      const std::string& place) {
  std::vector<std::uint32_t> steps;
  for (const std::string& name : names) {
    const std::optional<std::uint32_t> step = parseResolution(name);
    if (!step)
      throwInputError(file, place, "'" + name + "' is not a resolution", "full, half, quarter or a list: full,half,quarter");
    steps.push_back(*step);
  }
  return steps;
}

// The reduced target's size: ceil(size / step), so its last sample covers the G-buffer's last pixels.
inline glm::uvec2 reducedSize(glm::uvec2 size, std::uint32_t step) { return (size + (step - 1u)) / step; }

}  // namespace bounce::gi
