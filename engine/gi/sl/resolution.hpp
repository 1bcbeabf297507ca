#pragma once
// SL pass 2's reduced target names; the steps themselves are engine/gi/resolution.hpp's (shared with
// DNRT).
#include "engine/core/error.hpp"
#include "engine/gi/resolution.hpp"

namespace bounce::gi::sl {

// The transient target pass 2 writes at a reduced resolution: "sl.half" (step 2) or "sl.quarter" (4).
inline const char* reducedTargetName(std::uint32_t step) {
  if (checkedStep(step) == 1u) throw InternalError("sl: no reduced target at step 1 (full resolution)");
  return step == 4u ? "sl.quarter" : "sl.half";
}

}  // namespace bounce::gi::sl
