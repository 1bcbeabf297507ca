#include "engine/gi/upsample_pass.hpp"

#include <utility>

#include "engine/core/error.hpp"
#include "engine/gi/resolution.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/hdr_format.hpp"

namespace bounce::gi {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
}  // namespace

ReducedUpsample::ReducedUpsample(gpu::Context& ctx, const render::Pipelines& shared, std::string name)
    : ctx_(ctx),
      name_(std::move(name)),
      inputs_(ctx, {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}}, name_ + ".inputs"),
      layout_(ctx, {shared.frameLayout, inputs_}, {}, name_) {}

const gpu::Pipeline& ReducedUpsample::pipeline(std::uint32_t step) {
  if (checkedStep(step) == 1u) throw InternalError(name_ + ": no upsample at full resolution");
  gpu::Pipeline& p = steps_[stepIndex(step) - 1];  // step 2, 4
  if (p.handle()) return p;
  if (!frag_.handle()) {
    vert_ = gpu::ShaderModule(ctx_, "passes/fullscreen.vert.spv");
    frag_ = gpu::ShaderModule(ctx_, "passes/reduced_upsample.frag.spv");
  }
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert_;
  d.fragment = &frag_;
  d.colorFormats = {render::kLightingHdrFormat};
  d.blend = gpu::Blend::Additive;  // added to "lighting.hdr", as a full-resolution draw would
  d.specialization = {step};       // reduced_upsample.frag kStep
  d.name = name_ + ".step" + std::to_string(step);
  p = gpu::createGraphicsPipeline(ctx_, layout_, d);
  return p;
}

void ReducedUpsample::addTo(rg::RenderGraph& graph, const render::PassContext& pcIn, rg::Handle<rg::Texture> reducedIn,
                            std::uint32_t step) {
  pipeline(step);  // a bad step is a bug: thrown while the graph is built, not while it runs
  auto& bb = graph.blackboard();
  const render::PassContext* pc = &pcIn;
  struct Data {
    render::DeferredInputs g;
    rg::Handle<rg::Texture> reduced, hdr;
  };
  const auto& up = graph.addPass<Data>(
      name_,
      [&](rg::Builder& b, Data& d) {
        d.g = render::readDeferredInputs(b, bb);
        d.reduced = b.read(reducedIn, rg::Usage::SampledFragment);
        d.hdr = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
      },
      [this, pc, step](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        VkDescriptorSet inputs = pc->frame().descriptors->allocate(inputs_);
        gpu::DescriptorWriter w;
        // The reduced target is read by texelFetch only (the edge-aware blend), which ignores the
        // sampler: the point one, as the G-buffer's.
        render::writeDeferredInputs(w, d.g, *pc, res, point)
            .sampledImage(3, pc->backend->image(res.texture(d.reduced)).view(), point)
            .update(ctx_, inputs);
        gpu::Image& target = pc->backend->image(res.texture(d.hdr));
        render::Attachment color{target.view(), res.keepsContents(d.hdr)};
        render::beginRendering(ctx_, cmd, {target.desc().width, target.desc().height}, {&color, 1}, nullptr);
        const gpu::Pipeline& p = pipeline(step);
        p.bind(cmd);
        p.bindSet(cmd, 0, pc->frameSet);
        p.bindSet(cmd, 1, inputs);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        ctx_.cmdEndRendering(cmd);
      });
  bb.put("lighting.hdr", up.hdr);
}

}  // namespace bounce::gi
