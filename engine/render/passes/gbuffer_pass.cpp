#include "engine/render/passes/gbuffer_pass.hpp"

#include "engine/render/mesh_gpu.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/passes/skinning_pass.hpp"

namespace bounce::render {

const GBuffer& addGBufferPass(rg::RenderGraph& graph, const PassContext* pc, VkExtent2D extent) {
  const auto& out = graph.addPass<GBuffer>(
      "gbuffer",
      [&](rg::Builder& b, GBuffer& d) {
        auto desc = [&](rg::Format f) { return rg::TextureDesc{extent.width, extent.height, 1, 1, 1, f, false}; };
        d.albedo = b.write(b.create<rg::Texture>("gbuffer.albedo", desc(rg::Format::RGBA8_UNORM)), rg::Usage::ColorAttachment);
        d.normal = b.write(b.create<rg::Texture>("gbuffer.normal", desc(rg::Format::RGBA16F)), rg::Usage::ColorAttachment);
        d.emissive = b.write(b.create<rg::Texture>("gbuffer.emissive", desc(rg::Format::RGBA16F)), rg::Usage::ColorAttachment);
        d.entity = b.write(b.create<rg::Texture>("gbuffer.entity", desc(rg::Format::R32_UINT)), rg::Usage::ColorAttachment);
        d.depth = b.write(b.create<rg::Texture>("gbuffer.depth", desc(rg::Format::D32F)), rg::Usage::DepthAttachment);
        readSkinnedVertices(graph, b, pc->world->posedInView());
      },
      [pc, extent](const GBuffer& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        Attachment colors[4] = {{view(d.albedo)}, {view(d.normal)}, {view(d.emissive)}, {view(d.entity)}};
        Attachment depth{view(d.depth)};
        depth.clear.depthStencil = {1.0f, 0};
        beginRendering(*pc->gpu, cmd, extent, colors, &depth);
        const auto& p = pc->pipelines->gbuffer;
        p.bind(cmd);
        p.bindSet(cmd, 0, pc->frameSet);
        for (const DrawItem& draw : pc->world->draws) {
          if (draw.posed() && !draw.inView) continue;  // outside the frustum: its vertices were not posed
          const auto& prim = draw.mesh->primitives[draw.primitive];
          p.bindSet(cmd, 1, draw.material);
          pc->bindGeometry(cmd, draw);
          p.push(cmd, draw.instance);
          vkCmdDrawIndexed(cmd, prim.indexCount, 1, prim.firstIndex, prim.vertexOffset, 0);
        }
        pc->gpu->cmdEndRendering(cmd);
      });
  auto& bb = graph.blackboard();
  bb.put("gbuffer.albedo", out.albedo);
  bb.put("gbuffer.normal", out.normal);
  bb.put("gbuffer.emissive", out.emissive);
  bb.put("gbuffer.entity", out.entity);
  bb.put("gbuffer.depth", out.depth);
  return out;
}

DeferredInputs readDeferredInputs(rg::Builder& b, rg::Blackboard& bb, bool withEntity, rg::Usage depthUsage) {
  DeferredInputs in;
  in.albedo = b.read(bb.get<rg::Texture>("gbuffer.albedo"), rg::Usage::SampledFragment);
  in.normal = b.read(bb.get<rg::Texture>("gbuffer.normal"), rg::Usage::SampledFragment);
  in.depth = b.read(bb.get<rg::Texture>("gbuffer.depth"), depthUsage);
  if (withEntity) in.entity = b.read(bb.get<rg::Texture>("gbuffer.entity"), rg::Usage::SampledFragment);
  return in;
}

gpu::DescriptorWriter& writeDeferredInputs(gpu::DescriptorWriter& w, const DeferredInputs& g, const PassContext& pc,
                                           const rg::PassResources& res, VkSampler point, VkImageLayout depthLayout) {
  auto view = [&](rg::Handle<rg::Texture> h) { return pc.backend->image(res.texture(h)).view(); };
  return w.sampledImage(0, view(g.albedo), point)
      .sampledImage(1, view(g.normal), point)
      .sampledImage(2, view(g.depth), point, depthLayout);
}

}  // namespace bounce::render
