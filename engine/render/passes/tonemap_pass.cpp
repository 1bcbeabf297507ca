#include "engine/render/passes/tonemap_pass.hpp"

#include "engine/render/passes/lighting_pass.hpp"
#include "engine/render/passes/rendering.hpp"

namespace bounce::render {

rg::Handle<rg::Texture> addTonemapPass(rg::RenderGraph& graph, const PassContext* pc, rg::Handle<rg::Texture> hdr,
                                       rg::Handle<rg::Texture> display) {
  struct Data {
    rg::Handle<rg::Texture> hdr, display;
  };
  const auto& data = graph.addPass<Data>(
      "tonemap",
      [&](rg::Builder& b, Data& d) {
        d.hdr = b.read(hdr, rg::Usage::SampledFragment);
        d.display = b.write(display, rg::Usage::ColorAttachment);
      },
      [pc](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        gpu::Image& target = pc->backend->image(res.texture(d.display));
        VkDescriptorSet set = pc->frame().descriptors->allocate(pc->pipelines->tonemapLayout);
        gpu::DescriptorWriter()
            .sampledImage(0, pc->backend->image(res.texture(d.hdr)).view(),
                          pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST}))
            .update(*pc->gpu, set);
        Attachment color{target.view(), res.keepsContents(d.display)};
        beginRendering(*pc->gpu, cmd, {target.desc().width, target.desc().height}, {&color, 1}, nullptr);
        const auto& p = pc->pipelines->tonemap;
        p.bind(cmd);
        p.bindSet(cmd, 0, set);
        p.push(cmd, pc->exposure);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        pc->gpu->cmdEndRendering(cmd);
      });
  return data.display;
}

rg::Handle<rg::Texture> addDebugViewPass(rg::RenderGraph& graph, const PassContext* pc, const GBuffer& gbuffer,
                                         std::optional<rg::Handle<rg::Texture>> shadowAtlas,
                                         rg::Handle<rg::Texture> display) {
  struct Data {
    GBuffer g;
    std::optional<rg::Handle<rg::Texture>> atlas;
    rg::Handle<rg::Texture> display;
  };
  const auto& data = graph.addPass<Data>(
      "debug-view",
      [&](rg::Builder& b, Data& d) {
        d.g = gbuffer;
        b.read(d.g.albedo, rg::Usage::SampledFragment);
        b.read(d.g.normal, rg::Usage::SampledFragment);
        b.read(d.g.entity, rg::Usage::SampledFragment);
        b.read(d.g.depth, rg::Usage::SampledFragment);
        if (shadowAtlas) d.atlas = b.read(*shadowAtlas, rg::Usage::SampledFragment);
        d.display = b.write(display, rg::Usage::ColorAttachment);
      },
      [pc](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        gpu::Image& target = pc->backend->image(res.texture(d.display));
        VkDescriptorSet set = writeGBufferSet(pc, res, pc->pipelines->debugLayout, d.g, d.atlas, true);
        Attachment color{target.view(), res.keepsContents(d.display)};
        beginRendering(*pc->gpu, cmd, {target.desc().width, target.desc().height}, {&color, 1}, nullptr);
        const auto& p = pc->pipelines->debug;
        p.bind(cmd);
        p.bindSet(cmd, 0, pc->frameSet);
        p.bindSet(cmd, 1, set);
        const glm::vec2 range = depthViewRange(*pc->world);
        struct {
          std::uint32_t mode, lightCount;
          float depthMin, depthMax;
        } push{static_cast<std::uint32_t>(pc->debugView), pc->lightCount, range.x, range.y};
        p.push(cmd, push);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        pc->gpu->cmdEndRendering(cmd);
      });
  return data.display;
}

}  // namespace bounce::render
