#include "engine/render/passes/lighting_pass.hpp"

#include "engine/render/passes/rendering.hpp"

namespace bounce::render {

VkDescriptorSet writeGBufferSet(const PassContext* pc, const rg::PassResources& res, const gpu::DescriptorSetLayout& layout,
                                const GBuffer& g, std::optional<rg::Handle<rg::Texture>> shadowAtlas,
                                bool entityInsteadOfEmissive) {
  VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
  VkSampler compare = pc->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                         VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 1.0f, true});
  auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
  gpu::Image& atlas = shadowAtlas ? pc->backend->image(res.texture(*shadowAtlas)) : *pc->dummyShadowAtlas;
  VkImageView atlasView = pc->frameView(atlas, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, atlas.desc().layers);

  VkDescriptorSet set = pc->frame().descriptors->allocate(layout);
  gpu::DescriptorWriter w;
  w.sampledImage(0, view(g.albedo), point)
      .sampledImage(1, view(g.normal), point)
      .sampledImage(2, view(entityInsteadOfEmissive ? g.entity : g.emissive), point)
      .sampledImage(3, view(g.depth), point)
      .sampledImage(4, atlasView, compare)
      .buffer(5, *pc->shadowMatrices, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kMaxShadowLayers * sizeof(glm::mat4))
      .buffer(6, *pc->lights, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kMaxLights * sizeof(LightGpu));
  w.update(*pc->gpu, set);
  return set;
}

const Lighting& addLightingPass(rg::RenderGraph& graph, const PassContext* pc, const GBuffer& gbuffer,
                                std::optional<rg::Handle<rg::Texture>> shadowAtlas, rg::Handle<rg::Texture> hdr) {
  struct Data {
    GBuffer g;
    std::optional<rg::Handle<rg::Texture>> atlas;
    Lighting out;
  };
  const auto& data = graph.addPass<Data>(
      "lighting",
      [&](rg::Builder& b, Data& d) {
        d.g = gbuffer;
        b.read(d.g.albedo, rg::Usage::SampledFragment);
        b.read(d.g.normal, rg::Usage::SampledFragment);
        b.read(d.g.emissive, rg::Usage::SampledFragment);
        b.read(d.g.depth, rg::Usage::SampledFragment);
        if (shadowAtlas) d.atlas = b.read(*shadowAtlas, rg::Usage::SampledFragment);
        d.out.hdr = b.write(hdr, rg::Usage::ColorAttachment);
      },
      [pc](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        gpu::Image& target = pc->backend->image(res.texture(d.out.hdr));
        VkDescriptorSet set = writeGBufferSet(pc, res, pc->pipelines->lightingLayout, d.g, d.atlas, false);
        Attachment color{target.view(), res.keepsContents(d.out.hdr)};
        VkExtent2D extent{target.desc().width, target.desc().height};
        beginRendering(*pc->gpu, cmd, extent, {&color, 1}, nullptr);
        const auto& p = pc->pipelines->lighting;
        p.bind(cmd);
        p.bindSet(cmd, 0, pc->frameSet);
        p.bindSet(cmd, 1, set);
        struct {
          glm::vec4 background;
          std::uint32_t lightCount, shadowsOn;
        } push{glm::vec4(pc->world->background, 0.0f), pc->lightCount,
               d.atlas ? 1u : 0u};
        p.push(cmd, push);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        pc->gpu->cmdEndRendering(cmd);
      });
  graph.blackboard().put("lighting.hdr", data.out.hdr);
  return data.out;
}

}  // namespace bounce::render
