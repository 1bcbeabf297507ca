#pragma once
// The baseline passes' pipelines and descriptor layouts, built once per renderer from the SPIR-V
// the build compiled (shaders/passes/*). Set 0 is shared by every scene pass (frame.glsl).
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

struct Pipelines {
  explicit Pipelines(gpu::Context& ctx);

  gpu::DescriptorSetLayout frameLayout;     // 0 camera UBO, 1 instances SSBO, 2 shadow matrices SSBO
  gpu::DescriptorSetLayout materialLayout;  // 0 base colour, 1 emissive (combined image samplers)
  gpu::DescriptorSetLayout lightingLayout;  // gbuffer ×4, shadow atlas, shadow matrices, lights
  gpu::DescriptorSetLayout debugLayout;     // albedo, normal, entity, depth, atlas, matrices, lights
  gpu::DescriptorSetLayout tonemapLayout;   // 0 HDR image

  gpu::PipelineLayout gbufferLayout, shadowLayout, lightingPipelineLayout, debugPipelineLayout,
      tonemapPipelineLayout;
  gpu::Pipeline gbuffer, shadow, lighting, debug, tonemap;
};

}  // namespace bounce::render
