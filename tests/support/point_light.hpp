#pragma once
// A point light as the GPU and the CPU light code read it (render::LightGpu): at `position`, radiant
// intensity `intensity` (W/sr per channel), no range limit, no shadow map (shadow.x < 0). The tests'
// hand-built lamp.
#include <glm/glm.hpp>

#include "engine/render/gpu_types.hpp"

namespace bounce::testing {

inline render::LightGpu pointLight(glm::vec3 position, glm::vec3 intensity) {
  render::LightGpu l{};
  l.positionType = glm::vec4(position, float(render::LightType::Point));
  l.directionRange = glm::vec4(0.0f, 0.0f, -1.0f, 0.0f);
  l.radiance = glm::vec4(intensity, 0.0f);
  l.cone = glm::vec4(0.0f, 1.0f, 0.0f, 0.0f);
  l.shadow = glm::vec4(-1.0f);
  return l;
}

}  // namespace bounce::testing
