#pragma once
// Dynamic-rendering helper shared by the raster passes: begins rendering into colour attachments
// and an optional depth attachment, clearing or loading each as the graph says.
#include <span>

#include "engine/gpu/context.hpp"

namespace bounce::render {

struct Attachment {
  VkImageView view = VK_NULL_HANDLE;
  bool load = false;             // keep the previous content (rg::PassResources::keepsContents)
  VkClearValue clear{};
};

void beginRendering(const gpu::Context& ctx, VkCommandBuffer cmd, VkExtent2D extent,
                    std::span<const Attachment> colors, const Attachment* depth);

}  // namespace bounce::render
