#include "engine/gi/probes/node.hpp"

#include "engine/gpu/commands.hpp"
#include "engine/render/passes/rendering.hpp"

namespace bounce::gi::probes {
namespace {

template <class T>
gpu::Buffer uploadBuffer(gpu::Context& ctx, const std::vector<T>& data, const char* name) {
  // At least one element: a zero-sized binding is invalid.
  const VkDeviceSize bytes = std::max<VkDeviceSize>(sizeof(T), data.size() * sizeof(T));
  gpu::Buffer b(ctx, {bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      gpu::MemoryUsage::GpuOnly, name});
  if (!data.empty())
    gpu::upload(ctx, b, {reinterpret_cast<const std::uint8_t*>(data.data()), data.size() * sizeof(T)});
  return b;
}

struct Push {
  glm::vec4 originSpacing;
  glm::ivec4 countOrder;
  glm::vec4 bias;
};

}  // namespace

ProbeNode::ProbeNode(gpu::Context& ctx, const render::Pipelines& pipelines, ProbeVolume volume)
    : volume_(std::move(volume)),
      sh_(uploadBuffer(ctx, volume_.sh, "probes.sh")),
      moments_(uploadBuffer(ctx, volume_.moments, "probes.moments")),
      valid_(uploadBuffer(ctx, volume_.valid, "probes.valid")),
      setLayout_(ctx,
                 {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}},
                 "probes") {
  static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::vec2) == 8, "std430 float[] / vec2[] layouts");
  layout_ = gpu::PipelineLayout(ctx, {pipelines.frameLayout.handle(), setLayout_.handle()},
                                {{VK_SHADER_STAGE_ALL, 0, sizeof(Push)}}, "probes");
  gpu::ShaderModule vert(ctx, "passes/fullscreen.vert.spv");
  gpu::ShaderModule frag(ctx, "probes/probes.frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert;
  d.fragment = &frag;
  d.colorFormats = {VK_FORMAT_R16G16B16A16_SFLOAT};
  d.blend = gpu::Blend::Additive;
  d.name = "probes";
  pipeline_ = gpu::createGraphicsPipeline(ctx, layout_, d);
}

void ProbeNode::addPasses(rg::RenderGraph& graph, const render::PassContext* pc) {
  struct Data {
    rg::Handle<rg::Texture> albedo, normal, depth, hdr, ao;
  };
  auto& bb = graph.blackboard();
  // An AO node (ssao/hbao) set before this one publishes "ao.term": the indirect term is then
  // multiplied by it, the way the DNRT paper's baselines use AO (§6.4). Without one, binding 6
  // repeats the albedo and the shader ignores it.
  const bool withAo = bb.contains("ao.term");
  const auto& data = graph.addPass<Data>(
      "probes",
      [&](rg::Builder& b, Data& d) {
        d.albedo = b.read(bb.get<rg::Texture>("gbuffer.albedo"), rg::Usage::SampledFragment);
        d.normal = b.read(bb.get<rg::Texture>("gbuffer.normal"), rg::Usage::SampledFragment);
        d.depth = b.read(bb.get<rg::Texture>("gbuffer.depth"), rg::Usage::SampledFragment);
        d.hdr = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
        if (withAo) d.ao = b.read(bb.get<rg::Texture>("ao.term"), rg::Usage::SampledFragment);
      },
      [this, pc, withAo](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet set = pc->frame().descriptors->allocate(setLayout_);
        gpu::DescriptorWriter()
            .sampledImage(0, view(d.albedo), point)
            .sampledImage(1, view(d.normal), point)
            .sampledImage(2, view(d.depth), point)
            .buffer(3, sh_)
            .buffer(4, moments_)
            .buffer(5, valid_)
            .sampledImage(6, view(withAo ? d.ao : d.albedo), point)
            .update(*pc->gpu, set);
        gpu::Image& target = pc->backend->image(res.texture(d.hdr));
        render::Attachment color{target.view(), true};  // additive: keep the direct light
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(*pc->gpu, cmd, extent, {&color, 1}, nullptr);
        pipeline_.bind(cmd);
        pipeline_.bindSet(cmd, 0, pc->frameSet);
        pipeline_.bindSet(cmd, 1, set);
        const ProbeGrid& g = volume_.grid;
        const Push push{glm::vec4(g.origin, g.spacing), glm::ivec4(g.count, volume_.order),
                        glm::vec4(g.spacing * volume_.bias.normal, g.spacing * volume_.bias.view,
                                  volume_.minVariance(), withAo ? 1.0f : 0.0f)};
        pipeline_.push(cmd, push);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        pc->gpu->cmdEndRendering(cmd);
      });
  bb.put("lighting.hdr", data.hdr);
}

}  // namespace bounce::gi::probes
