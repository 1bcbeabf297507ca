#include "engine/render/pipelines.hpp"
#include "engine/render/hdr_format.hpp"

#include <cstddef>

namespace bounce::render {
namespace {

using gpu::Binding;
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkDescriptorType kUniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;

VkPushConstantRange push(std::uint32_t bytes) { return {VK_SHADER_STAGE_ALL, 0, bytes}; }

}  // namespace

Pipelines::Pipelines(gpu::Context& ctx)
    : frameLayout(ctx, {{0, kUniform}, {1, kStorage}, {2, kStorage}}, "frame"),
      materialLayout(ctx, {{0, kSampled}, {1, kSampled}}, "material"),
      lightingLayout(ctx,
                     {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kSampled}, {5, kUniform},
                      {6, kUniform}},
                     "lighting"),
      debugLayout(ctx,
                  {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kSampled}, {5, kUniform},
                   {6, kUniform}},
                  "debug-view"),
      tonemapLayout(ctx, {{0, kSampled}}, "tonemap"),
      skinningLayout(ctx, {{0, kStorage}, {1, kStorage}, {2, kStorage}, {3, kStorage}, {4, kStorage}}, "skinning"),
      subdivisionLayout(ctx, {{0, kStorage}, {1, kStorage}, {2, kStorage}}, "subdivision") {
  gbufferLayout = gpu::PipelineLayout(ctx, {frameLayout, materialLayout}, {push(4)}, "gbuffer");
  shadowLayout = gpu::PipelineLayout(ctx, {frameLayout}, {push(8)}, "shadow");
  lightingPipelineLayout =
      gpu::PipelineLayout(ctx, {frameLayout, lightingLayout}, {push(24)}, "lighting");
  debugPipelineLayout = gpu::PipelineLayout(ctx, {frameLayout, debugLayout}, {push(16)}, "debug");
  tonemapPipelineLayout = gpu::PipelineLayout(ctx, {tonemapLayout}, {push(4)}, "tonemap");

  gpu::ShaderModule meshVert(ctx, "passes/mesh.vert.spv");
  gpu::ShaderModule gbufferFrag(ctx, "passes/gbuffer.frag.spv");
  gpu::ShaderModule shadowVert(ctx, "passes/shadow.vert.spv");
  gpu::ShaderModule fullscreen(ctx, "passes/fullscreen.vert.spv");
  gpu::ShaderModule lightingFrag(ctx, "passes/lighting.frag.spv");
  gpu::ShaderModule debugFrag(ctx, "passes/debug_view.frag.spv");
  gpu::ShaderModule tonemapFrag(ctx, "passes/tonemap.frag.spv");

  const std::vector<gpu::VertexBinding> meshBinding = {{0, sizeof(MeshVertex), false}};
  const std::vector<gpu::VertexAttribute> meshAttributes = {
      {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, position)},
      {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, normal)},
      {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(MeshVertex, uv)},
  };

  gpu::GraphicsPipelineDesc g;
  g.vertex = &meshVert;
  g.fragment = &gbufferFrag;
  g.bindings = meshBinding;
  g.attributes = meshAttributes;
  g.colorFormats = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT,
                    VK_FORMAT_R32_UINT};
  g.depthFormat = VK_FORMAT_D32_SFLOAT;
  g.depthTest = g.depthWrite = true;
  g.depthCompare = VK_COMPARE_OP_LESS;
  g.cull = VK_CULL_MODE_NONE;  // glTF double-sided materials and the closed Cornell box seen from inside
  g.name = "gbuffer";
  gbuffer = gpu::createGraphicsPipeline(ctx, gbufferLayout, g);

  gpu::GraphicsPipelineDesc s;
  s.vertex = &shadowVert;
  s.bindings = meshBinding;
  s.attributes = {meshAttributes[0]};
  s.depthFormat = VK_FORMAT_D32_SFLOAT;
  s.depthTest = s.depthWrite = true;
  s.depthCompare = VK_COMPARE_OP_LESS;
  s.depthBias = true;  // slope-scaled bias against acne, set per pass (shadow_pass.cpp)
  s.name = "shadow";
  shadow = gpu::createGraphicsPipeline(ctx, shadowLayout, s);

  gpu::GraphicsPipelineDesc f;
  f.vertex = &fullscreen;
  f.fragment = &lightingFrag;
  f.colorFormats = {render::kLightingHdrFormat};  // "lighting.hdr"
  f.name = "lighting";
  lighting = gpu::createGraphicsPipeline(ctx, lightingPipelineLayout, f);

  f.fragment = &debugFrag;
  f.colorFormats = {VK_FORMAT_R8G8B8A8_UNORM};
  f.name = "debug-view";
  debug = gpu::createGraphicsPipeline(ctx, debugPipelineLayout, f);

  f.fragment = &tonemapFrag;
  f.name = "tonemap";
  tonemap = gpu::createGraphicsPipeline(ctx, tonemapPipelineLayout, f);

  skinningPipelineLayout = gpu::PipelineLayout(ctx, {skinningLayout}, {push(24)}, "skinning");
  gpu::ShaderModule skinningComp(ctx, "skinning/skinning.comp.spv");
  skinning = gpu::createComputePipeline(ctx, skinningPipelineLayout, skinningComp, "skinning");

  subdivisionPipelineLayout = gpu::PipelineLayout(ctx, {subdivisionLayout}, {push(12)}, "subdivision");
  gpu::ShaderModule subdivisionComp(ctx, "subdivision/subdivision.comp.spv");
  subdivision = gpu::createComputePipeline(ctx, subdivisionPipelineLayout, subdivisionComp, "subdivision");
}

}  // namespace bounce::render
