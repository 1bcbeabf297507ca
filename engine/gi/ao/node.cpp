#include "engine/gi/ao/node.hpp"

#include "engine/render/passes/rendering.hpp"

namespace bounce::gi::ao {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;

struct Push {
  float radius, bias;
  std::uint32_t samples, directions;
};

// The graph state of the persistent image from its tracked layout (renderer.cpp does the same for
// "lighting.hdr"): the first barrier of a frame waits for whatever touched it last.
rg::ResourceState importedState(const gpu::Image& image) {
  rg::ResourceState s;
  switch (image.layout()) {
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: s.layout = rg::Layout::ColorAttachment; break;
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: s.layout = rg::Layout::ShaderReadOnly; break;
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: s.layout = rg::Layout::TransferSrc; break;
    default: s.layout = rg::Layout::Undefined; return s;
  }
  s.stages = rg::Stage::FragmentShader | rg::Stage::ColorAttachmentOutput | rg::Stage::Transfer;
  s.access = rg::Access::ColorAttachmentWrite | rg::Access::TransferWrite;
  return s;
}
}  // namespace

const char* kindName(Kind k) { return k == Kind::Ssao ? "ssao" : "hbao"; }

Node::Node(gpu::Context& ctx, const render::Pipelines& shared, Kind kind, Settings settings)
    : ctx_(ctx),
      kind_(kind),
      settings_(settings),
      inputLayout_(ctx, {{0, kSampled}, {1, kSampled}}, std::string("ao.") + kindName(kind)),
      layout_(ctx, {shared.frameLayout, inputLayout_},
              {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(Push)}}, std::string("ao.") + kindName(kind)) {
  gpu::ShaderModule vert(ctx, "passes/fullscreen.vert.spv");
  gpu::ShaderModule frag(ctx, std::string("ao/") + kindName(kind) + ".frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert;
  d.fragment = &frag;
  d.colorFormats = {VK_FORMAT_R16_SFLOAT};
  d.name = std::string("ao.") + kindName(kind);
  pipeline_ = gpu::createGraphicsPipeline(ctx, layout_, d);
}

render::Renderer::GraphNode Node::node() {
  return [this](rg::RenderGraph& graph, render::PassContext& pc) { addTo(graph, pc); };
}

void Node::addTo(rg::RenderGraph& graph, render::PassContext& pcRef) {
  auto& bb = graph.blackboard();
  const auto depthHandle = bb.get<rg::Texture>("gbuffer.depth");
  // The frame's size, as the camera holds it (the G-buffer's size).
  const std::uint32_t width = std::uint32_t(pcRef.world->camera.resolution.x);
  const std::uint32_t height = std::uint32_t(pcRef.world->camera.resolution.y);
  if (pcRef.gpu && (!image_ || image_->desc().width != width || image_->desc().height != height)) {
    if (image_) pcRef.frames->waitIdle();
    gpu::ImageDesc d;
    d.width = width;
    d.height = height;
    d.format = VK_FORMAT_R16_SFLOAT;
    d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    d.name = std::string("ao.") + kindName(kind_);
    image_ = std::make_unique<gpu::Image>(ctx_, d);
  }
  const rg::TextureDesc desc{width, height, 1, 1, 1, rg::Format::R16F, false};
  // graphDot builds the graph without a device: any id names the import there.
  const rg::PhysicalId physical = pcRef.backend && image_ ? pcRef.backend->importImage(*image_) : 1000;
  auto target = graph.importTexture(std::string("ao.") + kindName(kind_), desc,
                                    image_ ? importedState(*image_) : rg::ResourceState{}, physical);
  struct Data {
    rg::Handle<rg::Texture> normal, depth, out;
  };
  const render::PassContext* pc = &pcRef;
  const Push push{settings_.radius, settings_.bias, settings_.samples, settings_.directions};
  const auto& data = graph.addPass<Data>(
      kindName(kind_),
      [&](rg::Builder& b, Data& d) {
        d.normal = b.read(bb.get<rg::Texture>("gbuffer.normal"), rg::Usage::SampledFragment);
        d.depth = b.read(depthHandle, rg::Usage::SampledFragment);
        d.out = b.write(target, rg::Usage::ColorAttachment);
      },
      [this, pc, push](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet set = pc->frame().descriptors->allocate(inputLayout_);
        gpu::DescriptorWriter().sampledImage(0, view(d.normal), point).sampledImage(1, view(d.depth), point).update(ctx_, set);
        gpu::Image& out = pc->backend->image(res.texture(d.out));
        render::Attachment color{out.view(), false};
        render::beginRendering(ctx_, cmd, {out.desc().width, out.desc().height}, {&color, 1}, nullptr);
        pipeline_.bind(cmd);
        pipeline_.bindSet(cmd, 0, pc->frameSet);
        pipeline_.bindSet(cmd, 1, set);
        pipeline_.push(cmd, push);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        ctx_.cmdEndRendering(cmd);
      });
  bb.put(std::string("ao.") + kindName(kind_), data.out);
  bb.put("ao.term", data.out);
  graph.markOutput(data.out, rg::Usage::TransferSrc);
}

}  // namespace bounce::gi::ao
