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
  // A depth attachment only tested, never written (rg::Usage::DepthRead): read-only layout, loaded,
  // nothing stored, so the pass may sample it too.
  bool readOnly = false;
};

void beginRendering(const gpu::Context& ctx, VkCommandBuffer cmd, VkExtent2D extent,
                    std::span<const Attachment> colors, const Attachment* depth);

}  // namespace bounce::render
