#include "engine/gi/sl/node.hpp"

#include <algorithm>
#include <cstring>
#include <tuple>

#include "engine/core/error.hpp"
#include "engine/gi/sl/resolution.hpp"
#include "engine/gi/sl/tiles.hpp"
#include "engine/gi/sl/probe_shadow.hpp"
#include "engine/gi/probes/relight_pass.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/hdr_format.hpp"

namespace bounce::gi::sl {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr std::uint32_t kFirstShadeBinding = 3;                // sl.frag: SL_BINDING
constexpr std::uint32_t kTilesBinding = 6;                     // tiles.vert: SlTiles
constexpr std::uint32_t kReducedBinding = 7;                   // upsample.frag: slReduced
constexpr std::uint32_t kRatiosBinding = 8;                    // hierarchy_tiles.vert: SlRatios

std::vector<gpu::Binding> inputBindings(bool hierarchy) {
  std::vector<gpu::Binding> b = {{0, kSampled}, {1, kSampled}, {2, kSampled}};
  for (const gpu::Binding& s : ShadeData::bindings(kFirstShadeBinding)) b.push_back(s);
  b.push_back({kTilesBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  if (hierarchy) b.push_back({kRatiosBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  return b;
}

// hierarchy_ratio.comp's set 0 and push constants.
std::vector<gpu::Binding> ratioBindings() {
  std::vector<gpu::Binding> b = {{0, kSampled}, {1, kSampled}};
  for (const gpu::Binding& s : ShadeData::bindings(3)) b.push_back(s);
  b.push_back({6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  b.push_back({7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  return b;
}
struct RatioPush {
  glm::mat4 invViewProj;
  glm::vec4 screen;  // G-buffer width, height, 1/width, 1/height
  std::uint32_t tileSize;
  std::uint32_t tileCount;
  std::uint32_t pad[2] = {0, 0};
};
constexpr VkDeviceSize kRatioBytesPerTile = 4 * sizeof(glm::vec4);  // sl/hierarchy.glsl kSlHierObjects vec4

// upsample.frag's set 1 (every binding written: lavapipe reads a bound set's unwritten image
// descriptors and crashes).
std::vector<gpu::Binding> upsampleBindings() {
  return {{0, kSampled}, {1, kSampled}, {2, kSampled}, {kTilesBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
          {kReducedBinding, kSampled}};
}
}  // namespace

Node::Node(gpu::Context& ctx, const render::Pipelines& shared, std::uint32_t framesInFlight,
           std::span<const SphereSet* const> sets, int order, Blocking blocking, float influence, Resolution resolution,
           ProbeLight probes, bool localLights, bool hierarchy, bool fuse, std::uint32_t terms, bool blockedAtSphere, bool tileCut,
           bool blockedMap)
    : ctx_(ctx),
      order_(order),
      blocking_(blocking),
      influence_(influence),
      resolution_(resolution),
      inputLayout_(ctx, inputBindings(hierarchy), "sl.inputs"),
      layout_(ctx, {shared.frameLayout, inputLayout_},
              {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(TilePush)}}, "sl") {
  hierarchy_ = hierarchy;
  if (hierarchy && sets.size() > kMaxHierarchyObjects)
    throw InternalError("sl::Node: more objects than the hierarchy serves (kMaxHierarchyObjects)");
  for (std::uint32_t i = 0; i < std::max<std::uint32_t>(framesInFlight, 1); ++i) {
    Slot s;
    s.intensity = std::make_unique<IntensityPass>(ctx, sets, order, influence, hierarchy);
    // SlIndirect sized per layout (shade.hpp indirectBlockBytes): 8 KiB of SH, or one map per SL.
    s.shade = std::make_unique<ShadeData>(ctx, order, blockedMap ? s.intensity->sphereCount() : 0u);
    slots_.push_back(std::move(s));
  }
  spheres_ = slots_[0].intensity->sphereCount();
  vert_ = gpu::ShaderModule(ctx, "sl/tiles.vert.spv");
  frag_ = gpu::ShaderModule(ctx, hierarchy ? "sl/sl_hierarchy.frag.spv" : "sl/sl.frag.spv");
  tileCut_ = tileCut && !hierarchy;
  if (hierarchy)
    hierarchyVert_ = gpu::ShaderModule(ctx, "sl/hierarchy_tiles.vert.spv");
  else if (tileCut_)
    cutVert_ = gpu::ShaderModule(ctx, "sl/cut_tiles.vert.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = hierarchy ? &hierarchyVert_ : (tileCut_ ? &cutVert_ : &vert_);
  d.fragment = &frag_;
  const std::uint32_t step = resolutionStep(resolution);
  const bool reduced = step > 1u;
  d.colorFormats = {render::kLightingHdrFormat};
  // Full: added to "lighting.hdr"; half, quarter: written into the cleared "sl.half" / "sl.quarter"
  // for the upsample.
  d.blend = reduced ? gpu::Blend::None : gpu::Blend::Additive;
  d.specialization = ShadeData::specialization(order, blocking, spheres_, influence);
  d.specialization.push_back(step);  // sl.frag kStep (constant_id 4)
  d.specialization.push_back(0u);    // sl.frag kSingleObject (constant_id 5)
  d.name = std::string("sl.") + (blocking == Blocking::PerObject ? "per-object" : "per-sphere") + ".sh" +
           std::to_string(order * order) + (reduced ? ".step" + std::to_string(step) : "") +
           (hierarchy ? ".hierarchy" : "");
  pipeline_ = gpu::createGraphicsPipeline(ctx, layout_, d);
  if (blocking == Blocking::PerObject) {
    d.specialization.back() = 1u;
    d.name += ".single-object";
    singleObject_ = gpu::createGraphicsPipeline(ctx, layout_, d);
  }
  if (reduced) {
    upsampleInputs_ = gpu::DescriptorSetLayout(ctx, upsampleBindings(), "sl.upsample.inputs");
    upsampleLayout_ = gpu::PipelineLayout(ctx, {shared.frameLayout, upsampleInputs_},
                                          {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(TilePush)}}, "sl.upsample");
    upsampleFrag_ = gpu::ShaderModule(ctx, "sl/upsample.frag.spv");
    gpu::GraphicsPipelineDesc u;
    u.vertex = &vert_;
    u.fragment = &upsampleFrag_;
    u.colorFormats = {render::kLightingHdrFormat};
    u.blend = gpu::Blend::Additive;
    u.specialization = {step};  // upsample.frag kStep (constant_id 0)
    u.name = "sl.upsample.step" + std::to_string(step);
    upsample_ = gpu::createGraphicsPipeline(ctx, upsampleLayout_, u);
  }
  for (const SphereSet* set : sets) {
    std::vector<Sphere> local;
    for (const SlSphere& s : set->spheres) local.push_back({glm::dvec3(s.centre), double(s.radius)});
    share_.push_back(float(unionShare(local)));
    silhouette_.push_back(set->spheres.empty() ? 1.0f : set->spheres.front().shadowScale);
  }
  // terms is a 2-bit mask (kSlBounce | kSlShadow, sl_shadow.frag kTerms): 0..3.
  if (terms > 3u) throw InternalError("sl::Node: terms is a mask of two bits (0..3)");
  terms_ = terms;
  if (terms != 3u && !(probes && fuse && !hierarchy))
    throw InternalError("sl::Node: one term alone needs the fused pass (probes, \"fused\", no hierarchy)");
  if (probes && spheres_ > 0)
    shadow_ = std::make_unique<ProbeShadowPass>(ctx, shared, probes, order, blocking, spheres_, influence, step, hierarchy, fuse,
                                                terms, blockedAtSphere, tileCut_, blockedMap);
  if (localLights && spheres_ > 0)
    local_ = std::make_unique<LocalLightPass>(ctx, shared, order, blocking, spheres_, influence);
  if (hierarchy) {
    ratioInputs_ = gpu::DescriptorSetLayout(ctx, ratioBindings(), "sl.hierarchy.inputs");
    ratioLayout_ = gpu::PipelineLayout(ctx, {ratioInputs_}, {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(RatioPush)}},
                                       "sl.hierarchy");
    gpu::SpecConstants spec = ShadeData::specialization(order, blocking, spheres_, 0.0f);  // Eq. 25: uncut
    spec.push_back(step);                                                                  // kStep
    ratioPipeline_ = gpu::createComputePipeline(ctx, ratioLayout_, gpu::ShaderModule(ctx, "sl/hierarchy_ratio.comp.spv"),
                                                "sl.hierarchy", nullptr, spec);
  }
}

void Node::enableRelightBounce(probes::RelightPass& relight) {
  if (spheres_ == 0) return;
  relightBounce_ = &relight;
  std::vector<gpu::Binding> b = ShadeData::bindings(0);
  b.push_back({3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  b.push_back({4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER});
  bounceInputs_ = gpu::DescriptorSetLayout(ctx_, b, "sl.relight_bounce.inputs");
  bounceLayout_ = gpu::PipelineLayout(ctx_, {bounceInputs_}, {VkPushConstantRange{VK_SHADER_STAGE_ALL, 0, sizeof(glm::uvec4)}},
                                      "sl.relight_bounce");
  // Pass 2's cut (rule 0's F, in sphere radii): the room carries on the first bounce that pass 2
  // shows, no more. Uncut here against a cut pass 2 measured worse on cornell-1 (0.592 → 0.785 at 12:
  // the full 2nd bounce against a faded bounce and shadow; README "SL's bounce in relight's
  // transport, session 15"). An uncut level is uncut in both.
  bouncePipeline_ = gpu::createComputePipeline(ctx_, bounceLayout_, gpu::ShaderModule(ctx_, "sl/relight_bounce.comp.spv"),
                                               "sl.relight_bounce", nullptr,
                                               ShadeData::specialization(order_, blocking_, spheres_, influence_));
}

void Node::addTo(rg::RenderGraph& graph, const render::PassContext& pcIn, std::span<const PosedSphere> posed,
                 std::span<const std::uint32_t> objects, std::span<const incident::RadianceSH> indirect,
                 std::span<const incident::DirectionMap> maps) {
  if (spheres_ == 0) return;
  if (posed.size() != spheres_ || objects.size() != spheres_ || indirect.size() != spheres_)
    throw InternalError("sl::Node: one pose, object and indirect SH per SL");
  if (!maps.empty() && maps.size() != spheres_) throw InternalError("sl::Node: one direction map per SL or none");
  const render::PassContext* pc = &pcIn;
  // `bounce graph` builds the graph without a frame ring (and records nothing): no CPU writes then.
  const bool recording = pc->frames != nullptr;
  Slot& slot = slots_[recording ? pc->frame().slot % slots_.size() : 0];
  std::vector<ShadedSphere> shaded(spheres_);
  for (std::uint32_t i = 0; i < spheres_; ++i)
    shaded[i] = {posed[i].centre, posed[i].radius, posed[i].rotation, objects[i],
                 objects[i] < share_.size() ? share_[objects[i]] : 1.0f,
                 objects[i] < silhouette_.size() ? silhouette_[objects[i]] : 1.0f};
  // §7.3: one parent per object, after the SLs in the blocks and in the tile masks (bit spheres_ + o),
  // listed in the tiles of its own influence ball.
  const std::vector<PosedSphere> parents = hierarchy_ ? parentSpheres(posed, objects) : std::vector<PosedSphere>{};
  if (recording) {
    // CPU writes of this slot's host-visible blocks: the ring waited for the slot's last frame.
    slot.intensity->setSpheres(posed, indirect);
    slot.shade->setSpheres(shaded, parents, indirect, maps);  // SlIndirect ("blocked_light": "sphere")
  }
  std::vector<ShadedSphere> binned = shaded;
  for (std::size_t o = 0; o < parents.size(); ++o)
    binned.push_back({parents[o].centre, parents[o].radius, glm::mat3(1.0f), std::uint32_t(o)});
  // The tiles this frame's SLs may reach (tiles.hpp), in the target's pixels: at half or quarter
  // resolution the reduced target's tiles for pass 2, then the full-size ones for the upsample.
  const glm::uvec2 resolution(std::uint32_t(pc->world->camera.resolution.x), std::uint32_t(pc->world->camera.resolution.y));
  const std::uint32_t step = resolutionStep(resolution_);
  const bool reduced = step > 1u;  // half or quarter
  const glm::uvec2 reducedExtent = reducedSize(resolution, step);
  std::vector<ShadeTile> tiles = binTiles(pc->world->camera.viewProj, reducedExtent, binned, influence_);
  const std::uint32_t shadeTiles = std::uint32_t(tiles.size());
  // Per-object blocking: the tiles whose SLs all belong to one object first (singleObject_).
  std::uint32_t singleTiles = 0;
  if (blocking_ == Blocking::PerObject) {
    const auto oneObject = [&](const ShadeTile& t) {
      std::int64_t object = -1;
      for (std::uint32_t i = 0; i < spheres_; ++i)
        if (t.mask[i / kTileMaskBits] >> (i % kTileMaskBits) & 1u) {
          if (object >= 0 && object != std::int64_t(shaded[i].object)) return false;
          object = shaded[i].object;
        }
      return true;
    };
    singleTiles = std::uint32_t(std::stable_partition(tiles.begin(), tiles.end(), oneObject) - tiles.begin());
  }
  if (reduced) {
    const std::vector<ShadeTile> full = binTiles(pc->world->camera.viewProj, resolution, binned, influence_);
    tiles.insert(tiles.end(), full.begin(), full.end());
  }
  const VkDeviceSize tileBytes = std::max<std::size_t>(tiles.size(), 1) * sizeof(ShadeTile);
  if (recording && (!slot.tiles || slot.tiles.size() < tileBytes))
    slot.tiles = gpu::Buffer(ctx_, {tileBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, "sl.tiles"});
  if (recording && !tiles.empty()) std::memcpy(slot.tiles.mapped(), tiles.data(), tiles.size() * sizeof(ShadeTile));
  const std::uint32_t tileCount = shadeTiles;
  const std::uint32_t upsampleTiles = std::uint32_t(tiles.size()) - shadeTiles;
  const VkDeviceSize ratioBytes = std::max<VkDeviceSize>(tileCount, 1) * kRatioBytesPerTile;
  if (hierarchy_ && recording && (!slot.ratios || slot.ratios.size() < ratioBytes)) {
    slot.ratios = gpu::Buffer(ctx_, {ratioBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuOnly, "sl.ratios"});
    slot.shadowRatios = gpu::Buffer(ctx_, {ratioBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuOnly, "sl.shadow.ratios"});
  }
  const gpu::Buffer* shadowRatios = hierarchy_ ? &slot.shadowRatios : nullptr;

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
        // §5.1: this frame's SLs block the indirect light at the samples (intensity.hpp).
        // §7.3 local lights: their shadow maps no longer hold the SL objects, so the SLs block them at
        // the samples too ("In the first pass, we do the same calculation for local light sources").
        slot.intensity->setBlockers(*slot.shade, pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST}),
                                    true, local_ != nullptr);
        slot.intensity->record(cmd);
      });

  // The SLs' bounce at relight's surfels (enableRelightBounce), after pass 1 (its barrier makes L^c
  // visible to compute), for the next frame's "probes.relight". Skipped for `terms` rows without the
  // bounce, and with local lights: their objects leave the lights' shadow maps, so relight carries
  // none of their shadow, and their bounce alone would be one side of their effect on the room
  // (measured on cornell-1 uncut: the local-lights rows 0.65–0.82 → 0.99–1.02). The buffer keeps 0
  // from the start: those sessions never write it.
  if (relightBounce_ && (terms_ & 1u) != 0u && !local_) {
    graph.addPass<IntensityData>(
        "sl.relight_bounce", [&](rg::Builder& b, IntensityData&) { b.sideEffect(); },
        [this, pc, &slot](const IntensityData&, const rg::PassResources&, rg::CommandContext& c) {
          VkCommandBuffer cmd = pc->cmd(c);
          VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
          VkDescriptorSet set = pc->frame().descriptors->allocate(bounceInputs_);
          gpu::DescriptorWriter w;
          slot.shade->write(w, 0, slot.intensity->intensity(), point);
          w.buffer(3, relightBounce_->surfelBuffer()).buffer(4, relightBounce_->slBounce());
          w.update(ctx_, set);
          // The previous frame's "probes.relight" read the buffer this dispatch rewrites (write after
          // read); its next one reads it after the barrier below (read after write).
          VkMemoryBarrier before{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_READ_BIT, VK_ACCESS_SHADER_WRITE_BIT};
          vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &before, 0,
                               nullptr, 0, nullptr);
          const glm::uvec4 push(relightBounce_->surfelCount(), 0u, 0u, 0u);
          bouncePipeline_.bind(cmd);
          bouncePipeline_.bindSet(cmd, 0, set);
          bouncePipeline_.push(cmd, push);
          vkCmdDispatch(cmd, (push.x + 63) / 64, 1, 1);
          VkMemoryBarrier done{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT};
          vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &done, 0,
                               nullptr, 0, nullptr);
        });
  }

  if (hierarchy_) {
    // §7.3 Eq. 25 per drawn tile (hierarchy_ratio.comp), after pass 1's parents, before "sl".
    struct RatioData {
      rg::Handle<rg::Texture> normal, depth;
    };
    graph.addPass<RatioData>(
        "sl.hierarchy",
        [&](rg::Builder& b, RatioData& d) {
          d.normal = b.read(bb.get<rg::Texture>("gbuffer.normal"), rg::Usage::SampledCompute);
          d.depth = b.read(bb.get<rg::Texture>("gbuffer.depth"), rg::Usage::SampledCompute);
          b.sideEffect();  // its buffer feeds "sl"
        },
        [this, pc, &slot, tileCount](const RatioData& d, const rg::PassResources& res, rg::CommandContext& c) {
          if (tileCount == 0) return;
          VkCommandBuffer cmd = pc->cmd(c);
          VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
          gpu::Image& depth = pc->backend->image(res.texture(d.depth));
          VkDescriptorSet set = pc->frame().descriptors->allocate(ratioInputs_);
          gpu::DescriptorWriter w;
          w.sampledImage(0, pc->backend->image(res.texture(d.normal)).view(), point).sampledImage(1, depth.view(), point);
          slot.shade->write(w, 3, slot.intensity->intensity(), point);
          w.buffer(6, slot.tiles).buffer(7, slot.ratios);
          w.update(ctx_, set);
          const float width = float(depth.desc().width), height = float(depth.desc().height);
          const RatioPush push{pc->world->camera.invViewProj, glm::vec4(width, height, 1.0f / width, 1.0f / height),
                               kScreenTile, tileCount};
          ratioPipeline_.bind(cmd);
          ratioPipeline_.bindSet(cmd, 0, set);
          ratioPipeline_.push(cmd, push);
          vkCmdDispatch(cmd, (tileCount + 63) / 64, 1, 1);
          VkMemoryBarrier done{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT};
          vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_VERTEX_SHADER_BIT, 0, 1, &done, 0,
                               nullptr, 0, nullptr);
        });
  }

  // One walk for both terms when "sl.shadow" runs too and the hierarchy is off (sl_shadow.frag,
  // README "SL: one walk for sl and sl.shadow"): pass "sl" then holds both.
  if (shadow_ && shadow_->fusesThisFrame(pc)) {
    const rg::Handle<rg::Texture> both = shadow_->addFused(graph, pc, *slot.shade, slot.intensity->intensity(),
                                                           {&slot.tiles, 0, tileCount}, singleTiles, reducedExtent);
    if (!reduced) {
      if (local_) local_->addTo(graph, pc, *slot.shade, slot.intensity->intensity(), {&slot.tiles, 0, tileCount});
      return;
    }
    addUpsample(graph, pc, slot, both, shadeTiles, upsampleTiles);
    return;
  }
  // Only the fused pass honours a partial mask: a frame without it (no "probes" in the world) would
  // add both terms and the decomposition row would silently measure the whole thing.
  if (terms_ != 3u)
    throw InternalError("sl::Node: terms " + std::to_string(terms_) +
                        " (one term alone) but this frame does not fuse (no \"probes\" in the world)");
  struct Data {
    render::DeferredInputs g;
    rg::Handle<rg::Texture> hdr;
  };
  const auto& data = graph.addPass<Data>(
      "sl",
      [&](rg::Builder& b, Data& d) {
        // cut_tiles.vert reads "gbuffer.depth" in the vertex stage (each tile's receivers,
        // tiles.glsl slCutTile), so the graph's barrier must reach the vertex shader.
        d.g = render::readDeferredInputs(b, bb, false,
                                         tileCut_ ? rg::Usage::SampledGraphics : rg::Usage::SampledFragment);
        d.hdr = reduced ? b.write(b.create<rg::Texture>(reducedTargetName(step),
                                                        rg::TextureDesc{reducedExtent.x, reducedExtent.y, 1, 1, 1,
                                                                        rg::Format::RGBA16F, false}),
                                  rg::Usage::ColorAttachment)
                        : b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
      },
      [this, pc, &slot, tileCount, singleTiles](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        VkDescriptorSet inputs = pc->frame().descriptors->allocate(inputLayout_);
        gpu::DescriptorWriter w;
        render::writeDeferredInputs(w, d.g, *pc, res, point);
        slot.shade->write(w, kFirstShadeBinding, slot.intensity->intensity(), point);
        w.buffer(kTilesBinding, slot.tiles);
        if (hierarchy_) w.buffer(kRatiosBinding, slot.ratios);
        w.update(ctx_, inputs);
        gpu::Image& target = pc->backend->image(res.texture(d.hdr));
        // "sl.half" / "sl.quarter" starts at zero (tiles no SL reaches are not drawn); "lighting.hdr"
        // keeps its light.
        render::Attachment color{target.view(), resolution_ == Resolution::Full && res.keepsContents(d.hdr)};
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, nullptr);
        // Two triangles per tile with any SL; the other tiles' pixels do no work. Per-object: the
        // tiles of one object first, without the closer objects' exp.
        const TilePush push{glm::vec2(1.0f / float(extent.width), 1.0f / float(extent.height)), kScreenTile, 0u};
        for (const auto& [pipeline, first, count] :
             {std::tuple<gpu::Pipeline*, std::uint32_t, std::uint32_t>{&singleObject_, 0u, singleTiles},
              {&pipeline_, singleTiles, tileCount - singleTiles}}) {
          if (count == 0) continue;
          pipeline->bind(cmd);
          pipeline->bindSet(cmd, 0, pc->frameSet);
          pipeline->bindSet(cmd, 1, inputs);
          pipeline->push(cmd, push);
          vkCmdDraw(cmd, 6, count, 0, first);
        }
        ctx_.cmdEndRendering(cmd);
      });
  if (!reduced) {
    bb.put("lighting.hdr", data.hdr);
    if (shadow_) shadow_->addTo(graph, pc, *slot.shade, slot.intensity->intensity(), {&slot.tiles, 0, tileCount}, {}, shadowRatios);
    if (local_) local_->addTo(graph, pc, *slot.shade, slot.intensity->intensity(), {&slot.tiles, 0, tileCount});
    return;
  }
  // The shadow on the probes' light joins E in "sl.half" / "sl.quarter" (ao · ΔE, same tiles), so one upsample
  // spreads both.
  const rg::Handle<rg::Texture> reducedE =
      shadow_ ? shadow_->addTo(graph, pc, *slot.shade, slot.intensity->intensity(), {&slot.tiles, 0, tileCount}, data.hdr,
                               shadowRatios)
              : data.hdr;
  addUpsample(graph, pc, slot, reducedE, shadeTiles, upsampleTiles);
}

void Node::addUpsample(rg::RenderGraph& graph, const render::PassContext* pc, Slot& slot,
                       rg::Handle<rg::Texture> reducedE, std::uint32_t shadeTiles, std::uint32_t upsampleTiles) {
  auto& bb = graph.blackboard();
  struct UpData {
    render::DeferredInputs g;
    rg::Handle<rg::Texture> reduced, hdr;
  };
  const auto& up = graph.addPass<UpData>(
      "sl.upsample",
      [&](rg::Builder& b, UpData& d) {
        d.g = render::readDeferredInputs(b, bb);
        d.reduced = b.read(reducedE, rg::Usage::SampledFragment);
        d.hdr = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
      },
      [this, pc, &slot, shadeTiles, upsampleTiles](const UpData& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet inputs = pc->frame().descriptors->allocate(upsampleInputs_);
        gpu::DescriptorWriter w;
        render::writeDeferredInputs(w, d.g, *pc, res, point);
        w.buffer(kTilesBinding, slot.tiles);
        w.sampledImage(kReducedBinding, view(d.reduced), point);
        w.update(ctx_, inputs);
        gpu::Image& target = pc->backend->image(res.texture(d.hdr));
        render::Attachment color{target.view(), res.keepsContents(d.hdr)};
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, nullptr);
        upsample_.bind(cmd);
        upsample_.bindSet(cmd, 0, pc->frameSet);
        upsample_.bindSet(cmd, 1, inputs);
        upsample_.push(cmd, TilePush{glm::vec2(1.0f / float(extent.width), 1.0f / float(extent.height)), kScreenTile, 0u});
        // The full-resolution tiles follow the reduced target's ones in the tile buffer.
        if (upsampleTiles > 0) vkCmdDraw(cmd, 6, upsampleTiles, 0, shadeTiles);
        ctx_.cmdEndRendering(cmd);
      });
  bb.put("lighting.hdr", up.hdr);
  if (local_) local_->addTo(graph, pc, *slot.shade, slot.intensity->intensity(), {&slot.tiles, shadeTiles, upsampleTiles});
}

}  // namespace bounce::gi::sl
