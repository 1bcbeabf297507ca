#include "engine/gi/rtf/node.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "engine/core/error.hpp"
#include "engine/gi/resolution.hpp"  // header only: the steps and the reduced size
#include "engine/gpu/commands.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/hdr_format.hpp"

namespace bounce::gi::rtf {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kUniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
}  // namespace

Node::Node(gpu::Context& ctx, const render::Pipelines& shared, std::uint32_t framesInFlight)
    : ctx_(ctx),
      inputLayout_(ctx, {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}}, "rtf.inputs"),
      objectLayout_(ctx, {{0, kUniform}, {1, kSampled}, {2, kUniform}}, "rtf.object"),
      layout_(ctx, {shared.frameLayout, inputLayout_, objectLayout_}, {}, "rtf"),
      vert_(ctx, "rtf/rtf.vert.spv"),
      frag_(ctx, "rtf/rtf.frag.spv"),
      upsample_(ctx, shared, "rtf.upsample"),
      records_(framesInFlight) {
  // rtf.vert hands rtf.frag 19 flat varyings (locations 0–18), above the 16 Vulkan guarantees (desktop GPUs
  // and lavapipe take 32): say so here rather than fail in pipeline creation.
  constexpr std::uint32_t kComponents = 19 * 4;
  if (ctx.limits().maxVertexOutputComponents < kComponents || ctx.limits().maxFragmentInputComponents < kComponents)
    throw InternalError("rtf: the shading pass passes " + std::to_string(kComponents) + " varying components; this device takes " +
                        std::to_string(std::min(ctx.limits().maxVertexOutputComponents, ctx.limits().maxFragmentInputComponents)));
}

// One pipeline per SH count, self test and step (rtf.frag's kSh9, kSelfInNormal, kStep): llvmpipe runs
// an untaken branch in full.
const gpu::Pipeline& Node::pipeline(bool sh4, bool entity, std::uint32_t step) {
  gpu::Pipeline& p = pipelines_[sh4 ? 1 : 0][entity ? 1 : 0][gi::stepIndex(step)];
  if (p.handle()) return p;
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert_;
  d.fragment = &frag_;
  d.colorFormats = {render::kLightingHdrFormat};  // "lighting.hdr", or "rtf.half" / "rtf.quarter" (the same format)
  d.blend = gpu::Blend::Additive;
  d.cull = VK_CULL_MODE_NONE;  // rtf.vert's camera-facing octagon (or full-screen triangle): each covered pixel once
  d.name = std::string("rtf") + (sh4 ? ".sh4" : "") + (entity ? ".entity" : "") +
           (step > 1u ? ".step" + std::to_string(step) : "");
  d.specialization = {sh4 ? 0u : 1u, entity ? 0u : 1u, step};
  p = gpu::createGraphicsPipeline(ctx_, layout_, d);
  return p;
}

void Node::addTo(rg::RenderGraph& graph, const render::PassContext& pcIn, std::vector<NodeObject> objects,
                 std::uint32_t step) {
  if (objects.empty()) return;
  const bool reduced = gi::checkedStep(step) > 1u;
  for (const NodeObject& o : objects)
    if (!o.xi) throw InternalError("rtf: object '" + o.name + "' has no field on the GPU");
  auto& bb = graph.blackboard();
  const render::PassContext* pc = &pcIn;

  // The ξ caches: written into images the graph does not track (each XiPass's own), so a
  // side-effect pass; XiPass::record's barriers order them before this frame's fragment reads and
  // after the previous frame's. Declaration order is execution order (render_graph.hpp).
  struct BounceData {};
  struct Light {
    XiPass* xi;
    std::vector<glm::vec3> proxies;
    std::vector<glm::vec4> blocked;
    std::vector<glm::vec4> scale;
    std::vector<float> onObjects;
  };
  std::vector<Light> lights;
  std::vector<std::string> names;
  for (NodeObject& o : objects) {
    lights.push_back({o.xi, std::move(o.proxyLight), {std::begin(o.record.blocked), std::end(o.record.blocked)}, std::move(o.blockedScale),
                      std::move(o.onObjects)});
    names.push_back(o.name);
  }
  graph.addPass<BounceData>(
      "rtf.bounce", [](rg::Builder& b, BounceData&) { b.sideEffect(); },
      [pc, lights = std::move(lights), names](const BounceData&, const rg::PassResources&, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        gpu::TimestampPool* ts = pc->frame().timestamps.get();
        for (std::size_t i = 0; i < lights.size(); ++i) {
          lights[i].xi->setProxyLight(lights[i].proxies);
          lights[i].xi->setBlockedLight(lights[i].blocked);
          lights[i].xi->setBlockedScale(lights[i].scale, lights[i].onObjects);
          if (ts) ts->begin(cmd, "rtf.bounce/" + names[i]);
          lights[i].xi->record(cmd);
          if (ts) ts->end(cmd);
        }
      });

  struct Data {
    render::DeferredInputs g;  // with entity
    rg::Handle<rg::Texture> hdr;
  };
  const auto& data = graph.addPass<Data>(
      "rtf",
      [&](rg::Builder& b, Data& d) {
        d.g = render::readDeferredInputs(b, bb, /*withEntity=*/true);
        // Full resolution: the draws add to "lighting.hdr". Half, quarter: into the transient "rtf.half" /
        // "rtf.quarter" (⌈size/step⌉, cleared), which "rtf.upsample" below adds to "lighting.hdr".
        const glm::uvec2 size = gi::reducedSize(
            {std::uint32_t(pc->world->camera.resolution.x), std::uint32_t(pc->world->camera.resolution.y)}, step);
        d.hdr = reduced ? b.write(b.create<rg::Texture>(std::string("rtf.") + gi::resolutionName(step),
                                                        rg::TextureDesc{size.x, size.y, 1, 1, 1, rg::Format::RGBA16F, false}),
                                  rg::Usage::ColorAttachment)
                        : b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
      },
      [this, pc, step, reduced, objects = std::move(objects)](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        // This slot's records (the ring waited for the slot's fence before the frame began).
        gpu::Buffer& buffer = records_[pc->frame().slot % records_.size()];
        const VkDeviceSize bytes = objects.size() * kRtfObjectStride;
        if (!buffer || buffer.size() < bytes)
          buffer = gpu::Buffer(ctx_, {bytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::Upload, "rtf.objects"});
        for (std::size_t i = 0; i < objects.size(); ++i)
          std::memcpy(buffer.mapped() + i * kRtfObjectStride, &objects[i].record, sizeof(RtfObjectGpu));

        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        // The fields: bilinear within a cube face is the sampler's (shaders/rtf/rtf.glsl rtfTaps).
        VkSampler linear = pc->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet inputs = pc->frame().descriptors->allocate(inputLayout_);
        gpu::DescriptorWriter writer;
        render::writeDeferredInputs(writer, d.g, *pc, res, point)
            .sampledImage(3, view(d.g.entity), point)
            .update(ctx_, inputs);

        gpu::Image& target = pc->backend->image(res.texture(d.hdr));
        // "rtf.half" / "rtf.quarter" starts at zero (samples no object reaches stay 0); "lighting.hdr" keeps its light.
        render::Attachment color{target.view(), !reduced && res.keepsContents(d.hdr)};
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, nullptr);
        // The pipelines share the layout: sets bound through one stay bound for the others. Each variant is
        // made on its first use (an object with it), as DNRT's.
        const gpu::Pipeline* bound = nullptr;
        gpu::TimestampPool* ts = pc->frame().timestamps.get();
        for (std::size_t i = 0; i < objects.size(); ++i) {
          VkDescriptorSet set = pc->frame().descriptors->allocate(objectLayout_);
          gpu::DescriptorWriter()
              .buffer(0, buffer, kUniform, i * kRtfObjectStride, sizeof(RtfObjectGpu))
              .sampledImage(1, objects[i].xi->net().view(), linear, VK_IMAGE_LAYOUT_GENERAL)
              .buffer(2, objects[i].xi->netRange(), kUniform)
              .update(ctx_, set);
          // The self test and the on-object test read the entity id + 1 from the normal's w while every id
          // they compare fits there (gbuffer.glsl).
          bool entity = objects[i].record.ids.x > render::kEntityInNormalMax;
          for (const glm::uvec4& ids : objects[i].record.onObject)
            for (int k = 0; k < 4; ++k) entity = entity || (ids[k] != kRtfNoEntity && ids[k] > render::kEntityInNormalMax);
          const gpu::Pipeline* want = &pipeline(objects[i].record.ids.y == 4u, entity, step);
          if (want != bound) {
            want->bind(cmd);
            if (!bound) want->bindSet(cmd, 0, pc->frameSet), want->bindSet(cmd, 1, inputs);
            bound = want;
          }
          bound->bindSet(cmd, 2, set);
          if (ts) ts->begin(cmd, "rtf/" + objects[i].name);
          vkCmdDraw(cmd, 18, 1, 0, 0);  // rtf.vert: the octagon's fan
          if (ts) ts->end(cmd);
        }
        ctx_.cmdEndRendering(cmd);
      });
  if (reduced)
    upsample_.addTo(graph, *pc, data.hdr, step);
  else
    bb.put("lighting.hdr", data.hdr);
}

}  // namespace bounce::gi::rtf
