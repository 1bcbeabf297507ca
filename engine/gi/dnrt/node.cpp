#include "engine/gi/dnrt/node.hpp"

#include <cstring>

#include "engine/core/error.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/render/passes/rendering.hpp"

namespace bounce::gi::dnrt {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // "lighting.hdr" (renderer.cpp)

struct Push {
  std::uint32_t object = 0;
  std::uint32_t fullScreen = 0;
};
}  // namespace

FieldTextures::FieldTextures(gpu::Context& ctx, const Field& field, const std::string& name) {
  for (std::size_t t = 0; t < field.textures.size(); ++t) {
    gpu::ImageDesc d;
    d.type = gpu::ImageType::Tex3D;
    d.format = VK_FORMAT_R8G8B8A8_UNORM;
    d.width = d.height = d.depth = std::uint32_t(field.n());
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    d.name = "dnrt." + name + "." + std::to_string(t);
    images_.push_back(std::make_unique<gpu::Image>(ctx, d));
    gpu::upload(ctx, *images_.back(), field.textures[t]);
  }
  if (images_.empty()) throw InternalError("dnrt: a field without textures");
}

VkImageView FieldTextures::view(int slot) const {
  const std::size_t i = std::size_t(slot);
  return (i < images_.size() ? images_[i] : images_[0])->view();
}

Node::Node(gpu::Context& ctx, const render::Pipelines& shared, std::uint32_t framesInFlight)
    : ctx_(ctx),
      inputLayout_(ctx, {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kStorage}, {4, kSampled}}, "dnrt.inputs"),
      fieldLayout_(ctx, {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kSampled}, {5, kSampled},
                         {6, kSampled}},
                   "dnrt.field"),
      layout_(ctx, {shared.frameLayout.handle(), inputLayout_.handle(), fieldLayout_.handle()},
              {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(Push)}}, "dnrt"),
      objectBuffers_(framesInFlight) {
  gpu::ShaderModule vert(ctx, "dnrt/dnrt.vert.spv"), frag(ctx, "dnrt/dnrt.frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert;
  d.fragment = &frag;
  d.colorFormats = {kHdrFormat};
  d.blend = gpu::Blend::Additive;
  d.cull = VK_CULL_MODE_FRONT_BIT;  // back faces of the cube: each covered pixel once, inside or out
  d.name = "dnrt.box";
  box_ = gpu::createGraphicsPipeline(ctx, layout_, d);
  d.cull = VK_CULL_MODE_NONE;
  d.name = "dnrt.fullscreen";
  fullScreen_ = gpu::createGraphicsPipeline(ctx, layout_, d);
}

void Node::addTo(rg::RenderGraph& graph, const render::PassContext& pcIn, std::vector<NodeObject> objects,
                 NodeSettings settings) {
  if (objects.empty()) return;
  for (const NodeObject& o : objects)
    if (!o.textures) throw InternalError("dnrt: object '" + o.name + "' has no field textures");
  struct Data {
    rg::Handle<rg::Texture> albedo, normal, depth, entity, hdr;
  };
  auto& bb = graph.blackboard();
  const render::PassContext* pc = &pcIn;
  const auto& data = graph.addPass<Data>(
      "dnrt",
      [&](rg::Builder& b, Data& d) {
        d.albedo = b.read(bb.get<rg::Texture>("gbuffer.albedo"), rg::Usage::SampledFragment);
        d.normal = b.read(bb.get<rg::Texture>("gbuffer.normal"), rg::Usage::SampledFragment);
        d.depth = b.read(bb.get<rg::Texture>("gbuffer.depth"), rg::Usage::SampledFragment);
        d.entity = b.read(bb.get<rg::Texture>("gbuffer.entity"), rg::Usage::SampledFragment);
        d.hdr = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
      },
      [this, pc, objects = std::move(objects), settings](const Data& d, const rg::PassResources& res,
                                                          rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        // This slot's object records (the ring waited for the slot's fence before the frame began).
        gpu::Buffer& buffer = objectBuffers_[pc->frame().slot % objectBuffers_.size()];
        const VkDeviceSize bytes = objects.size() * sizeof(DnrtObjectGpu);
        if (!buffer || buffer.size() < bytes)
          buffer = gpu::Buffer(ctx_, {bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, "dnrt.objects"});
        for (std::size_t i = 0; i < objects.size(); ++i)
          std::memcpy(buffer.mapped() + i * sizeof(DnrtObjectGpu), &objects[i].data, sizeof(DnrtObjectGpu));

        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        VkSampler linear = pc->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet inputs = pc->frame().descriptors->allocate(inputLayout_);
        gpu::DescriptorWriter()
            .sampledImage(0, view(d.albedo), point)
            .sampledImage(1, view(d.normal), point)
            .sampledImage(2, view(d.depth), point)
            .buffer(3, buffer)
            .sampledImage(4, view(d.entity), point)
            .update(ctx_, inputs);

        gpu::Image& target = pc->backend->image(res.texture(d.hdr));
        render::Attachment color{target.view(), res.keepsContents(d.hdr)};
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, nullptr);
        const gpu::Pipeline& p = settings.fullScreen ? fullScreen_ : box_;
        p.bind(cmd);
        p.bindSet(cmd, 0, pc->frameSet);
        p.bindSet(cmd, 1, inputs);
        gpu::TimestampPool* ts = pc->frame().timestamps.get();
        for (std::size_t i = 0; i < objects.size(); ++i) {
          VkDescriptorSet fieldSet = pc->frame().descriptors->allocate(fieldLayout_);
          gpu::DescriptorWriter w;
          for (int s = 0; s < 7; ++s) w.sampledImage(std::uint32_t(s), objects[i].textures->view(s), linear);
          w.update(ctx_, fieldSet);
          p.bindSet(cmd, 2, fieldSet);
          p.push(cmd, Push{std::uint32_t(i), settings.fullScreen ? 1u : 0u});
          if (ts) ts->begin(cmd, "dnrt/" + objects[i].name);
          vkCmdDraw(cmd, settings.fullScreen ? 3 : 36, 1, 0, 0);
          if (ts) ts->end(cmd);
        }
        ctx_.cmdEndRendering(cmd);
      });
  bb.put("lighting.hdr", data.hdr);
}

}  // namespace bounce::gi::dnrt
