#pragma once
// The baseline passes' pipelines and descriptor layouts, built once per renderer from the SPIR-V
// the build compiled (shaders/passes/*). Set 0 is shared by every scene pass (frame.glsl).
#include <cstdint>

#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"

namespace bounce::render {

// Vertex layout of every cooked mesh on the GPU: position, normal, uv0, interleaved.
struct MeshVertex {
  float position[3];
  float normal[3];
  float uv[2];
};
static_assert(sizeof(MeshVertex) == 32);

// A skinned mesh's vertex as the skinning compute pass reads it (shaders/skinning/skinning.comp):
// position + u, normal + v, 8 joint indices as u16 pairs, 8 weights.
struct SkinVertex {
  float positionU[4];
  float normalV[4];
  std::uint32_t joints[4];  // x = j0 | j1 << 16, y = j2 | j3 << 16, z = j4 | j5 << 16, w = j6 | j7 << 16
  float weights0[4];
  float weights1[4];
};
static_assert(sizeof(SkinVertex) == 80);
// The skinning pass's workgroup size (local_size_x in skinning.comp).
inline constexpr std::uint32_t kSkinningGroupSize = 64;

// A subdivided deformed mesh's limit stencils as the subdivision pass reads them
// (shaders/subdivision/subdivision.comp): one row per refined vertex, one weight per entry.
struct StencilRow {
  std::uint32_t first, count;  // into the mesh's StencilWeight array
  float u, v;                  // the refined vertex's uv0
};
struct StencilWeight {
  std::uint32_t cageVertex;  // mesh-wide index into the cage mesh's vertices
  float w, wu, wv;           // position, ∂/∂u, ∂/∂v weights
};
static_assert(sizeof(StencilRow) == 16 && sizeof(StencilWeight) == 16);
// The subdivision pass's workgroup size (local_size_x in subdivision.comp).
inline constexpr std::uint32_t kSubdivisionGroupSize = 64;

struct Pipelines {
  explicit Pipelines(gpu::Context& ctx);

  gpu::DescriptorSetLayout frameLayout;     // 0 camera UBO, 1 instances SSBO, 2 shadow matrices SSBO
  gpu::DescriptorSetLayout materialLayout;  // 0 base colour, 1 emissive (combined image samplers)
  gpu::DescriptorSetLayout lightingLayout;  // gbuffer ×4, shadow atlas, shadow matrices, lights
  gpu::DescriptorSetLayout debugLayout;     // albedo, normal, entity, depth, atlas, matrices, lights
  gpu::DescriptorSetLayout tonemapLayout;   // 0 HDR image
  gpu::DescriptorSetLayout skinningLayout;  // 0 skin vertices, 1 joint matrices, 2 posed vertices, 3 morph deltas, 4 morph weights (SSBOs)
  gpu::DescriptorSetLayout subdivisionLayout;  // 0 posed vertices, 1 stencil rows, 2 stencil weights (SSBOs)

  gpu::PipelineLayout gbufferLayout, shadowLayout, lightingPipelineLayout, debugPipelineLayout,
      tonemapPipelineLayout;
  gpu::Pipeline gbuffer, shadow, lighting, debug, tonemap;
  gpu::PipelineLayout skinningPipelineLayout;
  gpu::Pipeline skinning;  // shaders/skinning/skinning.comp
  gpu::PipelineLayout subdivisionPipelineLayout;
  gpu::Pipeline subdivision;  // shaders/subdivision/subdivision.comp
};

}  // namespace bounce::render
