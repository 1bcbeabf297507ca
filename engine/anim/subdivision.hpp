#pragma once
// The CPU face of the per-frame subdivision of a deformed cage (the GPU face is
// shaders/subdivision/subdivision.comp; tests hold them equal, and both equal OpenSubdiv's own
// refinement of the same posed cage): a refined primitive's LimitStencils (engine/asset, built
// once at cook time) evaluated on the posed cage vertices.
//
//   S(v)   = Σ_k w_k·P[i_k]      ∂S/∂u(v) = Σ_k wu_k·P[i_k]      ∂S/∂v(v) = Σ_k wv_k·P[i_k]
//   N(v)   = normalize(∂S/∂u × ∂S/∂v), or normalize(Σ_k w_k·N[i_k]) where the tangents are
//            (nearly) parallel: |∂S/∂u × ∂S/∂v| ≤ kParallelTangents·|∂S/∂u|·|∂S/∂v|
//
// Work: one multiply-add of a 3-vector per weight and per sum (4 sums) — the "vertex·weights"
// `bounce bench skinning` reports.
#include <cstddef>
#include <span>

#include <glm/glm.hpp>

#include "engine/asset/cooked_asset.hpp"

namespace bounce::anim {

// sin of the angle between the limit tangents below which the normal comes from the posed cage
// normals instead (a collapsed tangent plane at some boundary corners). Same value in the shader.
inline constexpr float kParallelTangents = 1e-6f;

struct LimitStencilJob {
  const asset::LimitStencils* stencils = nullptr;
  std::span<const glm::vec3> cagePositions;  // the posed cage primitive (asset or node space)
  std::span<const glm::vec3> cageNormals;    // its posed normals (any length)
  std::span<glm::vec3> outPositions;         // one per stencil row
  std::span<glm::vec3> outNormals;           // unit length
  bool parallel = true;  // rows spread over TBB's pool (engine/core/parallel.hpp); false: this thread

  // Spans of the row count (outputs) and of the cage's vertex count (inputs), every stencil
  // index below it.
  bool validate() const;
  bool run() const;
};

// Evaluates rows [begin, end) (what run() spreads over threads; exposed for the bench).
void evaluateLimitStencils(const asset::LimitStencils& st, std::span<const glm::vec3> cagePositions,
                           std::span<const glm::vec3> cageNormals, std::span<glm::vec3> outPositions,
                           std::span<glm::vec3> outNormals, std::size_t begin, std::size_t end);

}  // namespace bounce::anim
