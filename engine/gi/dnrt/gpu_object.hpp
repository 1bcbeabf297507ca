#pragma once
// Per-object data of the DNRT shader (shaders/dnrt/dnrt.glsl: DnrtObject, std430), filled on the
// CPU each frame (§5.2.1): placement, c_j rotated into the object's frame, the field's ranges.
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "engine/gi/dnrt/evaluate.hpp"
#include "engine/gi/dnrt/field.hpp"

namespace bounce::gi::dnrt {

struct DnrtObjectGpu {
  glm::mat4 worldToLocal{1.0f};
  glm::mat4 boxToWorld{1.0f};  // unit cube [-1, 1]³ → world outer cube
  glm::vec4 centreWorld{0.0f};  // w: R in world units
  glm::vec4 centreLocal{0.0f};  // w: R in local units
  glm::vec4 extents{0.0f};      // inner, outer, SH count, grid N
  glm::vec4 c[9]{};
  glm::vec4 lo[7]{};
  glm::vec4 hi[7]{};
  glm::uvec4 ids{0u};  // x: the object's entity index + 1 (its own pixels are skipped; 0 = none)
};
static_assert(sizeof(DnrtObjectGpu) == 560, "must match DnrtObject in shaders/dnrt/dnrt.glsl (std430)");

// `world`: the object's local → world matrix; `worldRadianceSH`: radiance SH at o (world axes), e.g.
// IrradianceSource::radianceSH(placement centre). Convolves to irradiance and rotates into the
// object's frame.
// `entityIndex`: the object's ecs::Entity::index(), so the shader skips the object's own pixels
// (the field is meaningless on and inside its surface); -1 skips nothing.
DnrtObjectGpu packObject(const Field& field, const glm::mat4& world, const std::array<glm::vec3, 9>& worldRadianceSH,
                         std::int64_t entityIndex = -1);

}  // namespace bounce::gi::dnrt
