#include "engine/render/passes/rendering.hpp"

#include <vector>

#include "engine/gpu/pipeline.hpp"

namespace bounce::render {

void beginRendering(const gpu::Context& ctx, VkCommandBuffer cmd, VkExtent2D extent,
                    std::span<const Attachment> colors, const Attachment* depth) {
  std::vector<VkRenderingAttachmentInfo> color(colors.size());
  for (std::size_t i = 0; i < colors.size(); ++i) {
    auto& c = color[i];
    c = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    c.imageView = colors[i].view;
    c.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    c.loadOp = colors[i].load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    c.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    c.clearValue = colors[i].clear;
  }
  VkRenderingAttachmentInfo d{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  if (depth) {
    d.imageView = depth->view;
    d.imageLayout = depth->readOnly ? VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    d.loadOp = depth->load || depth->readOnly ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    d.storeOp = depth->readOnly ? VK_ATTACHMENT_STORE_OP_NONE : VK_ATTACHMENT_STORE_OP_STORE;
    d.clearValue = depth->clear;
  }
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, extent};
  info.layerCount = 1;
  info.colorAttachmentCount = static_cast<std::uint32_t>(color.size());
  info.pColorAttachments = color.data();
  info.pDepthAttachment = depth ? &d : nullptr;
  ctx.cmdBeginRendering(cmd, info);
  gpu::setViewportAndScissor(cmd, extent);
}

}  // namespace bounce::render
