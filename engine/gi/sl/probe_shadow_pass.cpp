#include "engine/gi/sl/probe_shadow_pass.hpp"

#include "engine/gi/probes/node.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"

namespace bounce::gi::sl {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // "lighting.hdr" (renderer.cpp)
constexpr std::uint32_t kFirstShadeBinding = 6;                // probe_shadow.frag: SL_BINDING

std::vector<gpu::Binding> inputBindings() {
  // G-buffer albedo, normal, depth; probe SH, moments; "ao.term".
  std::vector<gpu::Binding> b = {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kSampled}, {5, kSampled}};
  for (const gpu::Binding& s : ShadeData::bindings(kFirstShadeBinding)) b.push_back(s);
  return b;
}
}  // namespace

ProbeShadowPass::ProbeShadowPass(gpu::Context& ctx, const render::Pipelines& shared, const probes::ProbeVolume& volume,
                                 int order, Blocking blocking, std::uint32_t spheres, float influence)
    : ctx_(ctx),
      volume_(volume),
      sh_(probes::uploadSh(ctx, volume)),
      moments_(probes::uploadMoments(ctx, volume)),
      inputLayout_(ctx, inputBindings(), "sl.shadow.inputs"),
      layout_(ctx, {shared.frameLayout.handle(), inputLayout_.handle()},
              {{VK_SHADER_STAGE_ALL, 0, sizeof(probes::ProbePush)}}, "sl.shadow") {
  gpu::ShaderModule vert(ctx, "passes/fullscreen.vert.spv");
  gpu::ShaderModule frag(ctx, "sl/probe_shadow.frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert;
  d.fragment = &frag;
  d.colorFormats = {kHdrFormat};
  d.blend = gpu::Blend::Additive;  // RGBA16F keeps the negative sum: the shadow takes light away
  d.specialization = ShadeData::specialization(order, blocking, spheres, influence);
  d.specialization.push_back(std::uint32_t(volume.coeffs()));  // probe_shadow.frag kCoeffs
  d.name = "sl.shadow";
  pipeline_ = gpu::createGraphicsPipeline(ctx, layout_, d);
}

void ProbeShadowPass::addTo(rg::RenderGraph& graph, const render::PassContext* pc, const ShadeData& shade,
                            const gpu::Buffer& intensity) {
  if (!pc->world->has("probes")) return;  // no probe light this frame: nothing to shadow
  auto& bb = graph.blackboard();
  const bool withAo = bb.contains("ao.term");  // as the probes pass: its light was multiplied by it
  struct Data {
    render::DeferredInputs g;
    rg::Handle<rg::Texture> hdr, ao;
  };
  const auto& data = graph.addPass<Data>(
      "sl.shadow",
      [&](rg::Builder& b, Data& d) {
        d.g = render::readDeferredInputs(b, bb);
        d.hdr = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
        if (withAo) d.ao = b.read(bb.get<rg::Texture>("ao.term"), rg::Usage::SampledFragment);
      },
      [this, pc, withAo, &shade, &intensity](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet inputs = pc->frame().descriptors->allocate(inputLayout_);
        gpu::DescriptorWriter w;
        w.sampledImage(0, view(d.g.albedo), point)
            .sampledImage(1, view(d.g.normal), point)
            .sampledImage(2, view(d.g.depth), point)
            .sampledImage(3, sh_->view(), point)
            .sampledImage(4, moments_->view(), point)
            .sampledImage(5, view(withAo ? d.ao : d.g.albedo), point);
        shade.write(w, kFirstShadeBinding, intensity, point);
        w.update(ctx_, inputs);
        gpu::Image& target = pc->backend->image(res.texture(d.hdr));
        render::Attachment color{target.view(), true};  // additive: keep what is there
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, nullptr);
        pipeline_.bind(cmd);
        pipeline_.bindSet(cmd, 0, pc->frameSet);
        pipeline_.bindSet(cmd, 1, inputs);
        pipeline_.push(cmd, probes::probePush(volume_, withAo ? 1.0f : 0.0f));
        vkCmdDraw(cmd, 3, 1, 0, 0);
        ctx_.cmdEndRendering(cmd);
      });
  bb.put("lighting.hdr", data.hdr);
}

}  // namespace bounce::gi::sl
