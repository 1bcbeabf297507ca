#include "engine/render/passes/shadow_pass.hpp"

#include "engine/render/mesh_gpu.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/passes/skinning_pass.hpp"

namespace bounce::render {

const ShadowAtlas& addShadowPass(rg::RenderGraph& graph, const PassContext* pc, std::uint32_t resolution) {
  const auto layers = static_cast<std::uint32_t>(pc->world->shadowLayers.size());
  const auto& out = graph.addPass<ShadowAtlas>(
      "shadow",
      [&](rg::Builder& b, ShadowAtlas& d) {
        rg::TextureDesc desc{resolution, resolution, 1, layers, 1, rg::Format::D32F, false};
        d.atlas = b.write(b.create<rg::Texture>("shadow.atlas", desc), rg::Usage::DepthAttachment);
        readSkinnedVertices(graph, b, pc->world->posedInShadow());
      },
      [pc, resolution, layers](const ShadowAtlas& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        gpu::Image& atlas = pc->backend->image(res.texture(d.atlas));
        const auto& p = pc->pipelines->shadow;
        for (std::uint32_t layer = 0; layer < layers; ++layer) {
          Attachment depth{pc->frameView(atlas, VK_IMAGE_VIEW_TYPE_2D, layer, 1)};
          depth.clear.depthStencil = {1.0f, 0};
          beginRendering(*pc->gpu, cmd, {resolution, resolution}, {}, &depth);
          p.bind(cmd);
          p.bindSet(cmd, 0, pc->frameSet);
          vkCmdSetDepthBias(cmd, kShadowDepthBiasConstant, 0.0f, kShadowDepthBiasSlope);
          const auto& light = pc->world->lights[pc->world->shadowLayers[layer].light];
          const bool localLayer = std::uint32_t(light.positionType.w + 0.5f) != std::uint32_t(LightType::Directional);
          for (const DrawItem& draw : pc->world->draws) {
            if (draw.posed() && !draw.inShadow) continue;  // in no shadow layer: its vertices were not posed
            if (draw.slLocal && localLayer) continue;       // its shadow on this light is "sl.local"'s
            const auto& prim = draw.mesh->primitives[draw.primitive];
            pc->bindGeometry(cmd, draw);
            struct {
              std::uint32_t instance, layer;
            } push{draw.instance, layer};
            p.push(cmd, push);
            vkCmdDrawIndexed(cmd, prim.indexCount, 1, prim.firstIndex, prim.vertexOffset, 0);
          }
          pc->gpu->cmdEndRendering(cmd);
        }
      });
  graph.blackboard().put("shadow.atlas", out.atlas);
  return out;
}

}  // namespace bounce::render
