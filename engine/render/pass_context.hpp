#pragma once
// What every pass's execute callback needs besides its graph resources: the device, the graph
// backend (to turn physical ids into images), the frame being recorded, the shared pipelines and
// the extracted RenderWorld. Execute callbacks capture a pointer to it by value; it outlives the
// graph's execution.
#include "engine/gpu/context.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/frames.hpp"
#include "engine/gpu/image.hpp"
#include "engine/render/pipelines.hpp"
#include "engine/render/render_world.hpp"
#include "engine/render/vk_backend.hpp"

namespace bounce::render {

struct PassContext {
  gpu::Context* gpu = nullptr;
  VkBackend* backend = nullptr;
  gpu::FrameRing* frames = nullptr;
  gpu::SamplerCache* samplers = nullptr;
  const Pipelines* pipelines = nullptr;
  const RenderWorld* world = nullptr;
  VkDescriptorSet frameSet = VK_NULL_HANDLE;  // set 0: camera UBO, instances, shadow matrices
  gpu::Buffer* lights = nullptr;              // LightGpu[]
  std::uint32_t lightCount = 0;               // lights the shaders loop over (0 without `direct`)
  gpu::Buffer* shadowMatrices = nullptr;      // mat4 per atlas layer
  gpu::Buffer* posedVertices = nullptr;       // RenderWorld::posedVertices (DrawItem::posedBase)
  gpu::Buffer* jointMatrices = nullptr;       // RenderWorld::jointMatrices (SkinJob::jointBase)
  gpu::Buffer* morphWeights = nullptr;        // RenderWorld::morphWeights (SkinJob::weightBase)
  gpu::Image* dummyShadowAtlas = nullptr;     // 1×1 depth array bound when there is no shadow pass
  int debugView = 0;                          // 0 = lit; see shaders/passes/debug_view.frag
  float exposure = 1.0f;

  gpu::Frame& frame() const { return frames->current(); }
  VkCommandBuffer cmd(rg::CommandContext& c) const { return static_cast<VkCommandContext&>(c).cmd; }
  // Binds a draw's vertex buffer (its posed vertices when deformed) and index buffer.
  void bindGeometry(VkCommandBuffer cmd, const DrawItem& draw) const;
  // A view that lives until this frame's slot is reused (views of one layer, array views).
  VkImageView frameView(gpu::Image& image, VkImageViewType type, std::uint32_t baseLayer, std::uint32_t layers) const;
};

}  // namespace bounce::render
