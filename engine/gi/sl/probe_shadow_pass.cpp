#include "engine/gi/sl/probe_shadow_pass.hpp"

#include <tuple>

#include "engine/core/error.hpp"
#include "engine/gi/probes/node.hpp"
#include "engine/gi/sl/resolution.hpp"
#include "engine/gi/sl/tiles.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/hdr_format.hpp"

namespace bounce::gi::sl {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
// "lighting.hdr" (renderer.cpp), "sl.half" / "sl.quarter".
constexpr std::uint32_t kTilesBinding = 6;                     // tiles.vert: SlTiles
constexpr std::uint32_t kFirstShadeBinding = 7;                // probe_shadow.frag: SL_BINDING
constexpr std::uint32_t kRatiosBinding = 10;                   // shadow_hierarchy_tiles.vert: SlRatios
constexpr std::uint32_t kIndirectBinding = 11;                 // probe_shadow_frag.glsl: SL_INDIRECT_BINDING

// probe_shadow_ratio.comp's set 1 and push block.
std::vector<gpu::Binding> ratioBindings() {
  std::vector<gpu::Binding> b = {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled},
                                 {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}, {7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
  for (const gpu::Binding& s : ShadeData::bindings(8)) b.push_back(s);
  return b;
}
struct RatioPush {
  probes::ProbePush probe;
  std::uint32_t tileSize = 0, tileCount = 0, pad0 = 0, pad1 = 0;
};

std::vector<gpu::Binding> inputBindings(bool hierarchy) {
  // G-buffer albedo, normal, depth; probe SH, moments; "ao.term"; the tiles.
  std::vector<gpu::Binding> b = {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kSampled}, {5, kSampled},
                                 {kTilesBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                 {kIndirectBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}};
  for (const gpu::Binding& s : ShadeData::bindings(kFirstShadeBinding)) b.push_back(s);
  if (hierarchy) b.push_back({kRatiosBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  return b;
}
}  // namespace

ProbeShadowPass::ProbeShadowPass(gpu::Context& ctx, const render::Pipelines& shared, ProbeLight probes, int order,
                                 Blocking blocking, std::uint32_t spheres, float influence, std::uint32_t step,
                                 bool hierarchy, bool fuse, std::uint32_t terms, bool blockedAtSphere, bool tileCut,
                                 bool blockedMap)
    : ctx_(ctx),
      probes_(probes),
      reduced_(checkedStep(step) > 1u),  // 1, 2 or 4 only (resolution.hpp)
      step_(step),
      inputLayout_(ctx, inputBindings(hierarchy), "sl.shadow.inputs"),
      layout_(ctx, {shared.frameLayout, inputLayout_},
              {{VK_SHADER_STAGE_ALL, 0, sizeof(probes::ProbePush) + sizeof(TilePush)}}, "sl.shadow") {
  hierarchy_ = hierarchy;
  tileCut_ = tileCut && !hierarchy;
  gpu::ShaderModule vert(ctx, hierarchy ? "sl/shadow_hierarchy_tiles.vert.spv"
                                        : (tileCut_ ? "sl/shadow_cut_tiles.vert.spv" : "sl/shadow_tiles.vert.spv"));
  gpu::ShaderModule frag(ctx, hierarchy ? "sl/probe_shadow_hierarchy.frag.spv" : "sl/probe_shadow.frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert;
  d.fragment = &frag;
  d.colorFormats = {render::kLightingHdrFormat};
  d.blend = gpu::Blend::Additive;  // RGBA16F keeps the negative sum: the shadow takes light away
  d.specialization = ShadeData::specialization(order, blocking, spheres, influence);
  d.specialization.push_back(std::uint32_t(probes.volume->coeffs()));  // probe_shadow.frag kCoeffs
  d.specialization.push_back(step);                                     // probe_shadow.frag kStep
  if (blockedAtSphere && hierarchy)
    throw InternalError("sl::ProbeShadowPass: the blocked light read at the spheres is not built for the hierarchy");
  if (blockedMap && !blockedAtSphere) throw InternalError("sl::ProbeShadowPass: the direction maps are read at the spheres only");
  d.specialization.push_back(blockedAtSphere ? 1u : 0u);                // probe_shadow.frag kBlockedAtSphere (6)
  d.specialization.push_back(blockedMap ? 1u : 0u);                     // probe_shadow.frag kBlockedMap (7)
  const bool reduced = reduced_;
  d.name = std::string("sl.shadow") + (reduced ? ".step" + std::to_string(step) : "") + (hierarchy ? ".hierarchy" : "");
  pipeline_ = gpu::createGraphicsPipeline(ctx, layout_, d);
  if (fuse && !hierarchy) {
    // One walk for both terms (sl_shadow.frag): the same vertex shader, set and push block; "sl"'s
    // blend (half / quarter: written into the cleared "sl.half" / "sl.quarter", which it creates).
    gpu::ShaderModule fusedFrag(ctx, "sl/sl_shadow.frag.spv");
    d.fragment = &fusedFrag;
    d.blend = reduced ? gpu::Blend::None : gpu::Blend::Additive;
    d.specialization.resize(6);         // ids 0–5 as above; sl_shadow.frag's own from 6 on
    d.specialization.push_back(terms);  // sl_shadow.frag kTerms (constant_id 6): Node's `terms`
    d.specialization.push_back(0u);     // sl_shadow.frag kSingleObject (constant_id 7)
    d.specialization.push_back(blockedAtSphere ? 1u : 0u);  // sl_shadow.frag kBlockedAtSphere (constant_id 8)
    d.specialization.push_back(blockedMap ? 1u : 0u);       // sl_shadow.frag kBlockedMap (constant_id 9)
    d.name = std::string("sl+shadow") + (reduced ? ".step" + std::to_string(step) : "");
    fused_ = gpu::createGraphicsPipeline(ctx, layout_, d);
    if (blocking == Blocking::PerObject) {
      d.specialization[7] = 1u;  // kSingleObject
      d.name += ".single-object";
      fusedSingle_ = gpu::createGraphicsPipeline(ctx, layout_, d);
    }
  }
  if (hierarchy) {
    ratioInputs_ = gpu::DescriptorSetLayout(ctx, ratioBindings(), "sl.shadow.hierarchy.inputs");
    ratioLayout_ = gpu::PipelineLayout(ctx, {shared.frameLayout, ratioInputs_},
                                       {{VK_SHADER_STAGE_ALL, 0, sizeof(RatioPush)}}, "sl.shadow.hierarchy");
    gpu::SpecConstants spec = ShadeData::specialization(order, blocking, spheres, 0.0f);  // τ: uncut
    spec.push_back(std::uint32_t(probes.volume->coeffs()));
    spec.push_back(step);
    ratioPipeline_ = gpu::createComputePipeline(ctx, ratioLayout_, gpu::ShaderModule(ctx, "sl/probe_shadow_ratio.comp.spv"),
                                                "sl.shadow.hierarchy", nullptr, spec);
  }
}

rg::Handle<rg::Texture> ProbeShadowPass::addTo(rg::RenderGraph& graph, const render::PassContext* pc,
                                               const ShadeData& shade, const gpu::Buffer& intensity, TileRange tiles,
                                               rg::Handle<rg::Texture> reducedTarget, const gpu::Buffer* ratios) {
  if (!pc->world->has("probes")) return reducedTarget;  // no probe light this frame: nothing to shadow
  auto& bb = graph.blackboard();
  const bool withAo = bb.contains("ao.term");  // as the probes pass: its light was multiplied by it
  // The tile pass writes tile t's τ at 4t; the vertex shader reads them at gl_InstanceIndex: both
  // count from the buffer's start.
  if (hierarchy_ && (!ratios || tiles.first != 0))
    throw InternalError("sl::ProbeShadowPass: the hierarchy needs a ratio buffer and tiles from the buffer's start");
  if (hierarchy_) {
    struct RatioData {
      rg::Handle<rg::Texture> normal, depth;
    };
    graph.addPass<RatioData>(
        "sl.shadow.hierarchy",
        [&](rg::Builder& b, RatioData& d) {
          d.normal = b.read(bb.get<rg::Texture>("gbuffer.normal"), rg::Usage::SampledCompute);
          d.depth = b.read(bb.get<rg::Texture>("gbuffer.depth"), rg::Usage::SampledCompute);
          b.sideEffect();  // its buffer feeds "sl.shadow"
        },
        [this, pc, &shade, &intensity, tiles, ratios](const RatioData& d, const rg::PassResources& res, rg::CommandContext& c) {
          if (tiles.count == 0) return;
          VkCommandBuffer cmd = pc->cmd(c);
          VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
          auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
          VkDescriptorSet set = pc->frame().descriptors->allocate(ratioInputs_);
          gpu::DescriptorWriter w;
          w.sampledImage(0, view(d.normal), point)
              .sampledImage(1, view(d.depth), point)
              .sampledImage(2, probes_.sh->view(), point)
              .sampledImage(3, probes_.moments->view(), point)
              .buffer(6, *tiles.buffer)
              .buffer(7, *ratios);
          shade.write(w, 8, intensity, point);
          w.update(ctx_, set);
          ratioPipeline_.bind(cmd);
          ratioPipeline_.bindSet(cmd, 0, pc->frameSet);
          ratioPipeline_.bindSet(cmd, 1, set);
          ratioPipeline_.push(cmd, RatioPush{probes::probePush(*probes_.volume, 0.0f), kScreenTile, tiles.count});
          vkCmdDispatch(cmd, (tiles.count + 63) / 64, 1, 1);
          VkMemoryBarrier done{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT};
          vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_VERTEX_SHADER_BIT, 0, 1, &done, 0,
                               nullptr, 0, nullptr);
        });
  }
  struct Data {
    render::DeferredInputs g;
    rg::Handle<rg::Texture> target, ao;
  };
  const auto& data = graph.addPass<Data>(
      "sl.shadow",
      [&](rg::Builder& b, Data& d) {
        // shadow_cut_tiles.vert reads "gbuffer.depth" in the vertex stage (tiles.glsl slCutTile).
        d.g = render::readDeferredInputs(b, bb, false, depthUsage());
        d.target = b.write(reduced_ ? reducedTarget : bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
        if (withAo) d.ao = b.read(bb.get<rg::Texture>("ao.term"), rg::Usage::SampledFragment);
      },
      [this, pc, withAo, &shade, &intensity, tiles, ratios](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkDescriptorSet inputs = writeInputs(pc, res, d.g, withAo ? d.ao : d.g.albedo, shade, intensity, *tiles.buffer, ratios);
        gpu::Image& target = pc->backend->image(res.texture(d.target));
        render::Attachment color{target.view(), true};  // additive: keep what is there
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, nullptr);
        pipeline_.bind(cmd);
        pipeline_.bindSet(cmd, 0, pc->frameSet);
        pipeline_.bindSet(cmd, 1, inputs);
        push(cmd, pipeline_, withAo, extent);
        if (tiles.count > 0) vkCmdDraw(cmd, 6, tiles.count, 0, tiles.first);
        ctx_.cmdEndRendering(cmd);
      });
  if (!reduced_) bb.put("lighting.hdr", data.target);
  return data.target;
}

VkDescriptorSet ProbeShadowPass::writeInputs(const render::PassContext* pc, const rg::PassResources& res,
                                             const render::DeferredInputs& g, rg::Handle<rg::Texture> ao,
                                             const ShadeData& shade, const gpu::Buffer& intensity, const gpu::Buffer& tiles,
                                             const gpu::Buffer* ratios) const {
  VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
  VkDescriptorSet inputs = pc->frame().descriptors->allocate(inputLayout_);
  gpu::DescriptorWriter w;
  render::writeDeferredInputs(w, g, *pc, res, point)
      .sampledImage(3, probes_.sh->view(), point)
      .sampledImage(4, probes_.moments->view(), point)
      .sampledImage(5, pc->backend->image(res.texture(ao)).view(), point);
  w.buffer(kTilesBinding, tiles);
  shade.write(w, kFirstShadeBinding, intensity, point);
  shade.writeIndirect(w, kIndirectBinding);
  if (hierarchy_) w.buffer(kRatiosBinding, *ratios);
  w.update(ctx_, inputs);
  return inputs;
}

void ProbeShadowPass::push(VkCommandBuffer cmd, const gpu::Pipeline& pipeline, bool withAo, VkExtent2D extent) const {
  // One push block for both stages: probe_sh.glsl's (fragment), then shadow_tiles.vert's.
  struct Push {
    probes::ProbePush probe;
    TilePush tile;
  };
  static_assert(sizeof(probes::ProbePush) == 48, "shadow_tiles.vert: SL_TILE_PUSH_OFFSET");
  const Push p{probes::probePush(*probes_.volume, withAo ? 1.0f : 0.0f),
               TilePush{glm::vec2(1.0f / float(extent.width), 1.0f / float(extent.height)), kScreenTile, 0u}};
  pipeline.push(cmd, p);
}

bool ProbeShadowPass::fusesThisFrame(const render::PassContext* pc) const {
  return fused_.handle() != VK_NULL_HANDLE && pc->world->has("probes");
}

rg::Handle<rg::Texture> ProbeShadowPass::addFused(rg::RenderGraph& graph, const render::PassContext* pc,
                                                  const ShadeData& shade, const gpu::Buffer& intensity, TileRange tiles,
                                                  std::uint32_t singleTiles, glm::uvec2 reducedExtent) {
  auto& bb = graph.blackboard();
  const bool withAo = bb.contains("ao.term");
  struct Data {
    render::DeferredInputs g;
    rg::Handle<rg::Texture> target, ao;
  };
  // Named "sl": its timestamp holds both terms (README's pass table); "sl.shadow" does not run.
  const auto& data = graph.addPass<Data>(
      "sl",
      [&](rg::Builder& b, Data& d) {
        d.g = render::readDeferredInputs(b, bb, false, depthUsage());
        d.target = reduced_ ? b.write(b.create<rg::Texture>(reducedTargetName(step_),
                                                            rg::TextureDesc{reducedExtent.x, reducedExtent.y, 1, 1, 1,
                                                                            rg::Format::RGBA16F, false}),
                                      rg::Usage::ColorAttachment)
                            : b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
        if (withAo) d.ao = b.read(bb.get<rg::Texture>("ao.term"), rg::Usage::SampledFragment);
      },
      [this, pc, withAo, &shade, &intensity, tiles, singleTiles](const Data& d, const rg::PassResources& res,
                                                                rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkDescriptorSet inputs =
            writeInputs(pc, res, d.g, withAo ? d.ao : d.g.albedo, shade, intensity, *tiles.buffer, nullptr);
        gpu::Image& target = pc->backend->image(res.texture(d.target));
        // "sl.half" / "sl.quarter" starts at zero (tiles no SL reaches are not drawn); "lighting.hdr"
        // keeps its light.
        render::Attachment color{target.view(), !reduced_ && res.keepsContents(d.target)};
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, nullptr);
        // As "sl": per-object, the tiles of one object first, without the closer objects' exp.
        for (const auto& [pipeline, first, count] :
             {std::tuple<const gpu::Pipeline*, std::uint32_t, std::uint32_t>{&fusedSingle_, tiles.first, singleTiles},
              {&fused_, tiles.first + singleTiles, tiles.count - singleTiles}}) {
          if (count == 0) continue;
          pipeline->bind(cmd);
          pipeline->bindSet(cmd, 0, pc->frameSet);
          pipeline->bindSet(cmd, 1, inputs);
          push(cmd, *pipeline, withAo, extent);
          vkCmdDraw(cmd, 6, count, 0, first);
        }
        ctx_.cmdEndRendering(cmd);
      });
  if (!reduced_) bb.put("lighting.hdr", data.target);
  return data.target;
}

}  // namespace bounce::gi::sl
