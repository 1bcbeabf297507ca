#pragma once
// CPU mirrors of the two VLM passes, in double, for tests and tools: phase 1 without shadows
// (shaders/vlm/vlm_lights.frag with V = 1) and phase 2 by brute force over every light (no grid),
// with the form factor of form_factor.hpp.
#include <span>

#include "engine/gi/vlm/vlm_mesh.hpp"
#include "engine/render/gpu_types.hpp"

namespace bounce::gi::vlm {

inline constexpr int kPhase1Samples = 4;  // vlm_common.glsl VLM_PHASE1_SAMPLES

// Phase-1 sample point i (centroid, then halfway to each vertex).
glm::dvec3 samplePoint(const VirtualLight& l, int i);

// L = scale · E / π with E averaged over the sample points, unshadowed; `lift` as in the pass.
glm::dvec3 emittedRadiance(const VirtualLight& l, std::span<const render::LightGpu> lights, double lift);

// E(x, n) = Σ_k π L_k F_k over every light whose tag differs from `tag` (0: skip none).
glm::dvec3 irradiance(const glm::dvec3& x, const glm::dvec3& n, std::span<const VirtualLight> lights,
                      std::span<const glm::dvec3> radiance, std::uint32_t tag);

}  // namespace bounce::gi::vlm
