#pragma once
// Per-object data of the DNRT shader, filled on the CPU each frame (§5.2.1): the record
// (DnrtObjectGpu: placement, c_j rotated into the object's frame, the field's ranges, in the paper's
// terms) and what the shader reads (DnrtShaderObject = fold(record): the same data with the decode
// and c_j product folded into per-channel k and a, shaders/dnrt/dnrt.glsl: DnrtObject, std430).
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "engine/gi/dnrt/evaluate.hpp"
#include "engine/gi/dnrt/field.hpp"

namespace bounce::gi::dnrt {

struct DnrtObjectGpu {  // the record; the node folds it (fold()) before upload
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

// shaders/dnrt/dnrt.glsl: DnrtObject (std430). The shader computes Σ_j c_j M_j per channel as
// a + Σ_slot dot(k_slot, unorm texel_slot), exactly Σ_j c_j (lo + (hi − lo)·unorm) regrouped.
struct DnrtShaderObject {
  glm::mat4 boxToWorld{1.0f};
  glm::vec4 worldToQ[3]{};  // rows of r ↦ q = (worldToLocal·r − o_local) / R_local (units of R)
  glm::vec4 centreWorld{0.0f};  // w: R in world units
  glm::vec4 extents{0.0f};      // inner, outer, SH count, grid N
  glm::vec4 k[7]{};             // slot t, component i: (hi − lo)[t][i] · c of that slot's channel
  glm::vec4 a{0.0f};            // rgb: Σ lo·c per channel
  glm::uvec4 ids{0u};           // x: the object's entity index + 1 (0 = none)
};
static_assert(sizeof(DnrtShaderObject) == 288, "must match DnrtObject in shaders/dnrt/dnrt.glsl (std430)");

// shaders/dnrt/dnrt.glsl: DnrtClusterObject (std140, a uniform array of kClusterBatch in
// clustered.frag): what a pixel of the clustered draw reads per object it visits — DnrtShaderObject
// without the box matrix, plus where the object's brick sits in the field atlas (cluster.hpp).
struct DnrtClusterObject {
  glm::vec4 worldToQ[3]{};
  glm::vec4 centreWorld{0.0f};
  glm::vec4 extents{0.0f};
  glm::vec4 k[7]{};
  glm::vec4 a{0.0f};
  glm::vec4 atlas{0.0f};  // xyz: atlas texel coordinate of grid vertex (0, 0, 0)'s centre: (1.5, 1.5, z0 + 1.5)
  glm::uvec4 ids{0u};
};
static_assert(sizeof(DnrtClusterObject) == 240, "must match DnrtClusterObject in shaders/dnrt/dnrt.glsl (std140)");

// The folded record for the clustered draw; `z0`: the brick's first layer in the atlas.
DnrtClusterObject clusterObject(const DnrtShaderObject& folded, std::uint32_t z0);

// The record folded for the shader (Table 2's slot layout: slots 0..2 hold m_0..3 of R, G, B,
// slots 3..5 m_4..7 of R, G, B, slot 6 m_8 of R, G, B in its rgb).
DnrtShaderObject fold(const DnrtObjectGpu& record);

// `world`: the object's local → world matrix; `worldRadianceSH`: radiance SH at o (world axes), e.g.
// IrradianceSource::radianceSH(placement centre). Convolves to irradiance and rotates into the
// object's frame.
// `entityIndex`: the object's ecs::Entity::index(), so the shader skips the object's own pixels
// (the field is meaningless on and inside its surface); -1 skips nothing.
DnrtObjectGpu packObject(const Field& field, const glm::mat4& world, const std::array<glm::vec3, 9>& worldRadianceSH,
                         std::int64_t entityIndex = -1);

}  // namespace bounce::gi::dnrt
