#include "engine/gi/sl/node.hpp"

#include "engine/core/error.hpp"
#include "engine/gi/sl/probe_shadow.hpp"
#include "engine/render/passes/rendering.hpp"

namespace bounce::gi::sl {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // "lighting.hdr" (renderer.cpp)
constexpr std::uint32_t kFirstShadeBinding = 3;                // sl.frag: SL_BINDING

std::vector<gpu::Binding> inputBindings() {
  std::vector<gpu::Binding> b = {{0, kSampled}, {1, kSampled}, {2, kSampled}};
  for (const gpu::Binding& s : ShadeData::bindings(kFirstShadeBinding)) b.push_back(s);
  return b;
}
}  // namespace

Node::Node(gpu::Context& ctx, const render::Pipelines& shared, std::uint32_t framesInFlight,
           std::span<const SphereSet* const> sets, int order, Blocking blocking, float influence,
           const probes::ProbeVolume* probes)
    : ctx_(ctx),
      order_(order),
      blocking_(blocking),
      inputLayout_(ctx, inputBindings(), "sl.inputs"),
      layout_(ctx, {shared.frameLayout.handle(), inputLayout_.handle()}, {}, "sl") {
  for (std::uint32_t i = 0; i < std::max<std::uint32_t>(framesInFlight, 1); ++i) {
    Slot s;
    s.intensity = std::make_unique<IntensityPass>(ctx, sets, order);
    s.shade = std::make_unique<ShadeData>(ctx, order);
    slots_.push_back(std::move(s));
  }
  spheres_ = slots_[0].intensity->sphereCount();
  vert_ = gpu::ShaderModule(ctx, "passes/fullscreen.vert.spv");
  frag_ = gpu::ShaderModule(ctx, "sl/sl.frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert_;
  d.fragment = &frag_;
  d.colorFormats = {kHdrFormat};
  d.blend = gpu::Blend::Additive;
  d.specialization = ShadeData::specialization(order, blocking, spheres_, influence);
  d.name = std::string("sl.") + (blocking == Blocking::PerObject ? "per-object" : "per-sphere") + ".sh" +
           std::to_string(order * order);
  pipeline_ = gpu::createGraphicsPipeline(ctx, layout_, d);
  for (const SphereSet* set : sets) {
    std::vector<Sphere> local;
    for (const SlSphere& s : set->spheres) local.push_back({glm::dvec3(s.centre), double(s.radius)});
    share_.push_back(float(unionShare(local)));
    silhouette_.push_back(set->spheres.empty() ? 1.0f : set->spheres.front().shadowScale);
  }
  if (probes && spheres_ > 0)
    shadow_ = std::make_unique<ProbeShadowPass>(ctx, shared, *probes, order, blocking, spheres_, influence);
}

void Node::addTo(rg::RenderGraph& graph, const render::PassContext& pcIn, std::span<const PosedSphere> posed,
                 std::span<const std::uint32_t> objects, std::span<const incident::RadianceSH> indirect) {
  if (spheres_ == 0) return;
  if (posed.size() != spheres_ || objects.size() != spheres_ || indirect.size() != spheres_)
    throw InternalError("sl::Node: one pose, object and indirect SH per SL");
  const render::PassContext* pc = &pcIn;
  Slot& slot = slots_[pc->frame().slot % slots_.size()];
  // CPU writes of this slot's host-visible blocks: the ring waited for the slot's last frame.
  slot.intensity->setSpheres(posed, indirect);
  std::vector<ShadedSphere> shaded(spheres_);
  for (std::uint32_t i = 0; i < spheres_; ++i)
    shaded[i] = {posed[i].centre, posed[i].radius, posed[i].rotation, objects[i],
                 objects[i] < share_.size() ? share_[objects[i]] : 1.0f,
                 objects[i] < silhouette_.size() ? silhouette_[objects[i]] : 1.0f};
  slot.shade->setSpheres(shaded);

  auto& bb = graph.blackboard();
  struct IntensityData {
    std::optional<rg::Handle<rg::Texture>> atlas;
  };
  graph.addPass<IntensityData>(
      "sl.intensity",
      [&](rg::Builder& b, IntensityData& d) {
        if (auto atlas = bb.find<rg::Texture>("shadow.atlas")) d.atlas = b.read(*atlas, rg::Usage::SampledCompute);
        // The pass writes no graph resource; keep it (its buffer feeds "sl").
        b.sideEffect();
      },
      [this, pc, &slot](const IntensityData& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler compare = pc->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                               VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 1.0f, true});
        gpu::Image& atlas = d.atlas ? pc->backend->image(res.texture(*d.atlas)) : *pc->dummyShadowAtlas;
        slot.intensity->bindLights(*pc->lights, pc->lightCount, *pc->shadowMatrices);
        slot.intensity->setShadowAtlas(pc->frameView(atlas, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, atlas.desc().layers), compare,
                                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, d.atlas.has_value());
        slot.intensity->record(cmd);
      });

  struct Data {
    rg::Handle<rg::Texture> albedo, normal, depth, hdr;
  };
  const auto& data = graph.addPass<Data>(
      "sl",
      [&](rg::Builder& b, Data& d) {
        d.albedo = b.read(bb.get<rg::Texture>("gbuffer.albedo"), rg::Usage::SampledFragment);
        d.normal = b.read(bb.get<rg::Texture>("gbuffer.normal"), rg::Usage::SampledFragment);
        d.depth = b.read(bb.get<rg::Texture>("gbuffer.depth"), rg::Usage::SampledFragment);
        d.hdr = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
      },
      [this, pc, &slot](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet inputs = pc->frame().descriptors->allocate(inputLayout_);
        gpu::DescriptorWriter w;
        w.sampledImage(0, view(d.albedo), point).sampledImage(1, view(d.normal), point).sampledImage(2, view(d.depth), point);
        slot.shade->write(w, kFirstShadeBinding, slot.intensity->intensity(), point);
        w.update(ctx_, inputs);
        gpu::Image& target = pc->backend->image(res.texture(d.hdr));
        render::Attachment color{target.view(), res.keepsContents(d.hdr)};
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, nullptr);
        pipeline_.bind(cmd);
        pipeline_.bindSet(cmd, 0, pc->frameSet);
        pipeline_.bindSet(cmd, 1, inputs);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        ctx_.cmdEndRendering(cmd);
      });
  bb.put("lighting.hdr", data.hdr);
  if (shadow_) shadow_->addTo(graph, pc, *slot.shade, slot.intensity->intensity());
}

}  // namespace bounce::gi::sl
