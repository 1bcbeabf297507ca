#include "engine/gi/sl/probe_shadow_pass.hpp"

#include "engine/gi/probes/node.hpp"
#include "engine/gi/sl/tiles.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"

namespace bounce::gi::sl {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // "lighting.hdr" (renderer.cpp), "sl.half"
constexpr std::uint32_t kTilesBinding = 6;                     // tiles.vert: SlTiles
constexpr std::uint32_t kFirstShadeBinding = 7;                // probe_shadow.frag: SL_BINDING

std::vector<gpu::Binding> inputBindings() {
  // G-buffer albedo, normal, depth; probe SH, moments; "ao.term"; the tiles.
  std::vector<gpu::Binding> b = {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kSampled}, {5, kSampled},
                                 {kTilesBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
  for (const gpu::Binding& s : ShadeData::bindings(kFirstShadeBinding)) b.push_back(s);
  return b;
}
}  // namespace

ProbeShadowPass::ProbeShadowPass(gpu::Context& ctx, const render::Pipelines& shared, ProbeLight probes, int order,
                                 Blocking blocking, std::uint32_t spheres, float influence, bool half)
    : ctx_(ctx),
      probes_(probes),
      half_(half),
      inputLayout_(ctx, inputBindings(), "sl.shadow.inputs"),
      layout_(ctx, {shared.frameLayout.handle(), inputLayout_.handle()},
              {{VK_SHADER_STAGE_ALL, 0, sizeof(probes::ProbePush) + sizeof(TilePush)}}, "sl.shadow") {
  gpu::ShaderModule vert(ctx, "sl/shadow_tiles.vert.spv");
  gpu::ShaderModule frag(ctx, "sl/probe_shadow.frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert;
  d.fragment = &frag;
  d.colorFormats = {kHdrFormat};
  d.blend = gpu::Blend::Additive;  // RGBA16F keeps the negative sum: the shadow takes light away
  d.specialization = ShadeData::specialization(order, blocking, spheres, influence);
  d.specialization.push_back(std::uint32_t(probes.volume->coeffs()));  // probe_shadow.frag kCoeffs
  d.specialization.push_back(half ? 1u : 0u);                          // probe_shadow.frag kHalf
  d.name = half ? "sl.shadow.half" : "sl.shadow";
  pipeline_ = gpu::createGraphicsPipeline(ctx, layout_, d);
}

rg::Handle<rg::Texture> ProbeShadowPass::addTo(rg::RenderGraph& graph, const render::PassContext* pc,
                                               const ShadeData& shade, const gpu::Buffer& intensity, TileRange tiles,
                                               rg::Handle<rg::Texture> halfTarget) {
  if (!pc->world->has("probes")) return halfTarget;  // no probe light this frame: nothing to shadow
  auto& bb = graph.blackboard();
  const bool withAo = bb.contains("ao.term");  // as the probes pass: its light was multiplied by it
  struct Data {
    render::DeferredInputs g;
    rg::Handle<rg::Texture> target, ao;
  };
  const auto& data = graph.addPass<Data>(
      "sl.shadow",
      [&](rg::Builder& b, Data& d) {
        d.g = render::readDeferredInputs(b, bb);
        d.target = b.write(half_ ? halfTarget : bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
        if (withAo) d.ao = b.read(bb.get<rg::Texture>("ao.term"), rg::Usage::SampledFragment);
      },
      [this, pc, withAo, &shade, &intensity, tiles](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet inputs = pc->frame().descriptors->allocate(inputLayout_);
        gpu::DescriptorWriter w;
        render::writeDeferredInputs(w, d.g, *pc, res, point)
            .sampledImage(3, probes_.sh->view(), point)
            .sampledImage(4, probes_.moments->view(), point)
            .sampledImage(5, view(withAo ? d.ao : d.g.albedo), point);
        w.buffer(kTilesBinding, *tiles.buffer);
        shade.write(w, kFirstShadeBinding, intensity, point);
        w.update(ctx_, inputs);
        gpu::Image& target = pc->backend->image(res.texture(d.target));
        render::Attachment color{target.view(), true};  // additive: keep what is there
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, nullptr);
        pipeline_.bind(cmd);
        pipeline_.bindSet(cmd, 0, pc->frameSet);
        pipeline_.bindSet(cmd, 1, inputs);
        // One push block for both stages: probe_sh.glsl's (fragment), then shadow_tiles.vert's.
        struct Push {
          probes::ProbePush probe;
          TilePush tile;
        };
        static_assert(sizeof(probes::ProbePush) == 48, "shadow_tiles.vert: SL_TILE_PUSH_OFFSET");
        const Push push{probes::probePush(*probes_.volume, withAo ? 1.0f : 0.0f),
               TilePush{glm::vec2(1.0f / float(extent.width), 1.0f / float(extent.height)), kScreenTile, 0u}};
        pipeline_.push(cmd, push);
        if (tiles.count > 0) vkCmdDraw(cmd, 6, tiles.count, 0, tiles.first);
        ctx_.cmdEndRendering(cmd);
      });
  if (!half_) bb.put("lighting.hdr", data.target);
  return data.target;
}

}  // namespace bounce::gi::sl
