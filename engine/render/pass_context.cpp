#include "engine/render/pass_context.hpp"

#include "engine/render/mesh_gpu.hpp"
#include "engine/render/pipelines.hpp"

#include <memory>

namespace bounce::render {

VkImageView PassContext::frameView(gpu::Image& image, VkImageViewType type, std::uint32_t baseLayer,
                                   std::uint32_t layers) const {
  auto view = std::make_shared<gpu::ImageView>(image.createView(type, 0, 1, baseLayer, layers, image.name() + ".view"));
  VkImageView handle = view->handle();
  frames->deferDelete([view]() mutable { view->reset(); });
  return handle;
}

void PassContext::bindGeometry(VkCommandBuffer cmd, const DrawItem& draw) const {
  VkBuffer vb = draw.posed() ? posedVertices->handle() : draw.mesh->vertices.handle();
  const VkDeviceSize offset = draw.posed() ? VkDeviceSize(draw.posedBase) * sizeof(MeshVertex) : 0;
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
  vkCmdBindIndexBuffer(cmd, draw.mesh->indices.handle(), 0, VK_INDEX_TYPE_UINT32);
}

}  // namespace bounce::render
