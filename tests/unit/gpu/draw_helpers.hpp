#pragma once
// Small drawing helpers shared by the GPU tests.
#include <array>
#include <optional>

#include "engine/gpu/commands.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"

namespace bounce::gpu::testkit {

using Color = std::array<float, 4>;

// Begins dynamic rendering into `target` (cleared to `clear`, or loaded when nullopt).
inline void beginColor(const Context& ctx, VkCommandBuffer cmd, Image& target, std::optional<Color> clear) {
  transition(cmd, target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = target.view();
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  if (clear)
    for (int i = 0; i < 4; ++i) color.clearValue.color.float32[i] = (*clear)[i];
  VkExtent3D e = target.extent();
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {e.width, e.height}};
  info.layerCount = 1;
  info.colorAttachmentCount = 1;
  info.pColorAttachments = &color;
  ctx.cmdBeginRendering(cmd, info);
  setViewportAndScissor(cmd, {e.width, e.height});
}

// A full-screen pipeline writing a push-constant colour into targets of `format`.
struct SolidPipeline {
  ShaderModule vs, fs;
  PipelineLayout layout;
  Pipeline pipeline;
  SolidPipeline(Context& ctx, VkFormat format, Blend blend = Blend::None)
      : vs(ctx, "test/fullscreen.vert.spv"),
        fs(ctx, "test/solid.frag.spv"),
        layout(ctx, {}, {{VK_SHADER_STAGE_ALL, 0, sizeof(Color)}}, "solid") {
    GraphicsPipelineDesc d;
    d.vertex = &vs;
    d.fragment = &fs;
    d.colorFormats = {format};
    d.blend = blend;
    d.name = "solid";
    pipeline = createGraphicsPipeline(ctx, layout, d);
  }
  void draw(VkCommandBuffer cmd, const Color& color) const {
    pipeline.bind(cmd);
    pipeline.push(cmd, color);
    vkCmdDraw(cmd, 3, 1, 0, 0);
  }
};

}  // namespace bounce::gpu::testkit
