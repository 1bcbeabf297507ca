#include "engine/gi/vlm/node.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

#include "engine/gpu/timestamps.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/scene/components.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/hdr_format.hpp"

namespace bounce::gi::vlm {
namespace {

constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
// Phase-1 target: one RGBA32F texel per virtual light, rows of at most this many texels.
constexpr std::uint32_t kRadianceRow = 1024;

struct LightsPush {
  std::uint32_t count, width, lightCount, shadowsOn;
  float lift;
  std::uint32_t first;
};
struct GridGpu {
  glm::vec4 originK, cellBase;
  glm::ivec4 dims;
};
struct ShadePush {
  GridGpu grids[2];
  glm::uvec4 counts;
  glm::uvec4 lightRange;  // x first, y end: only lights[first, end) are shaded by this draw
};
static_assert(sizeof(ShadePush) <= 128, "push constants: 128 bytes guaranteed");

GridGpu gridGpu(const Grid* g, std::uint32_t firstSlot) {
  if (!g || g->slots.empty()) return {glm::vec4(0.0f), glm::vec4(1.0f, 1.0f, 1.0f, 0.0f), glm::ivec4(0)};
  return {glm::vec4(g->desc.origin, float(g->desc.k)), glm::vec4(g->desc.cellSize, float(firstSlot)),
          glm::ivec4(glm::ivec3(g->desc.dims), 1)};
}

// Grows `buffer` to hold `bytes` (at least 16: a zero-sized binding is invalid) and copies `data`.
void fill(gpu::Context& ctx, gpu::Buffer& buffer, const void* data, std::size_t bytes, const char* name) {
  const VkDeviceSize size = std::max<VkDeviceSize>(16, bytes);
  if (!buffer || buffer.size() < size)
    buffer = gpu::Buffer(ctx, {size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, name});
  if (bytes) std::memcpy(buffer.mapped(), data, bytes);
}


}  // namespace

// The pixels of a `extent` image that world box [lo, hi] covers under `viewProj` (the whole image
// when a corner is at or behind the camera plane, or the box is empty). Pixel = (ndc · ½ + ½) ·
// size, as frame.glsl's worldFromDepth inverts it.
VkRect2D screenRect(const glm::mat4& viewProj, glm::vec3 lo, glm::vec3 hi, VkExtent2D extent) {
  const VkRect2D whole{{0, 0}, extent};
  if (!glm::all(glm::lessThanEqual(lo, hi))) return whole;
  glm::vec2 a(std::numeric_limits<float>::max()), b(-std::numeric_limits<float>::max());
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z);
    const glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
    if (!(clip.w > 1e-6f)) return whole;
    const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(extent.width, extent.height);
    a = glm::min(a, pixel), b = glm::max(b, pixel);
  }
  const glm::vec2 size(extent.width, extent.height);
  a = glm::clamp(glm::floor(a), glm::vec2(0.0f), size), b = glm::clamp(glm::ceil(b), glm::vec2(0.0f), size);
  return {{std::int32_t(a.x), std::int32_t(a.y)}, {std::uint32_t(b.x - a.x), std::uint32_t(b.y - a.y)}};
}

Runtime::Runtime(gpu::Context& ctx, const render::Pipelines& pipelines, ecs::Registry& registry, NodeSettings settings,
                 const std::filesystem::path& cookCache, std::uint32_t framesInFlight)
    : ctx_(ctx),
      update_(registry, std::move(settings), cookCache),
      lightsLayout_(ctx, {{0, kStorage}, {1, kSampled}, {2, kStorage}, {3, kStorage}}, "vlm.lights"),
      shadeLayout_(ctx,
                   {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kStorage}, {5, kSampled},
                    {6, kStorage}, {7, kStorage}},
                   "vlm"),
      lightsPipelineLayout_(ctx, {lightsLayout_}, {{VK_SHADER_STAGE_ALL, 0, sizeof(LightsPush)}}, "vlm.lights"),
      shadePipelineLayout_(ctx, {pipelines.frameLayout, shadeLayout_},
                           {{VK_SHADER_STAGE_ALL, 0, sizeof(ShadePush)}}, "vlm"),
      buffers_(std::max(1u, framesInFlight)) {
  gpu::ShaderModule vert(ctx, "passes/fullscreen.vert.spv");
  gpu::ShaderModule lightsFrag(ctx, "vlm/vlm_lights.frag.spv"), shadeFrag(ctx, "vlm/vlm.frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert;
  d.fragment = &lightsFrag;
  d.colorFormats = {VK_FORMAT_R32G32B32A32_SFLOAT};
  d.name = "vlm.lights";
  lightsPipeline_ = gpu::createGraphicsPipeline(ctx, lightsPipelineLayout_, d);
  d.fragment = &shadeFrag;
  d.colorFormats = {render::kLightingHdrFormat};  // "lighting.hdr"
  d.blend = gpu::Blend::Additive;
  d.name = "vlm";
  shadePipeline_ = gpu::createGraphicsPipeline(ctx, shadePipelineLayout_, d);
}

void Runtime::addTo(rg::RenderGraph& graph, render::PassContext& pc) {
  FrameData f = prepare(*pc.world);
  if (f.lights.empty()) return;
  // Packed now, copied into this frame slot's buffers when phase 1 records (the ring has waited
  // for the slot's fence by then).
  std::vector<VlmLightGpu> packed;
  packed.reserve(f.lights.size());
  for (const auto& l : f.lights) packed.push_back(pack(l));
  std::vector<std::uint32_t> slots = update_.staticGrid().slots;
  const auto dynamicFirst = std::uint32_t(slots.size());
  slots.insert(slots.end(), f.dynamicGrid.slots.begin(), f.dynamicGrid.slots.end());

  const auto count = std::uint32_t(f.lights.size());
  const std::uint32_t width = std::min(count, kRadianceRow), height = (count + width - 1) / width;
  // Phase 2 draws the static grid over the whole image, then each dynamic VLM over the pixels its
  // lights can reach, in its own timestamp scope, from the dynamic grid with only its lights.
  const glm::uvec4 counts(count, std::uint32_t(f.entityTags.size()), width, 0);
  const ShadePush staticShade{{gridGpu(&update_.staticGrid(), 0), gridGpu(nullptr, 0)}, counts, glm::uvec4(0, f.staticCount, 0, 0)};
  const ShadePush dynamicShade{{gridGpu(nullptr, 0), gridGpu(&f.dynamicGrid, dynamicFirst)}, counts, glm::uvec4(0)};
  const std::vector<FrameData::Range> objects = f.dynamicRanges;
  const glm::mat4 viewProj = pc.world->camera.viewProj;
  const render::PassContext* ctx = &pc;
  auto& bb = graph.blackboard();

  // Phase 1: one texel per virtual light.
  struct LightsData {
    rg::Handle<rg::Texture> radiance;
    std::optional<rg::Handle<rg::Texture>> atlas;
  };
  const bool shadows = bb.contains("shadow.atlas");
  const auto& lights = graph.addPass<LightsData>(
      "vlm.lights",
      [&](rg::Builder& b, LightsData& d) {
        d.radiance = b.write(b.create<rg::Texture>("vlm.radiance", rg::TextureDesc{width, height, 1, 1, 1, rg::Format::RGBA32F, false}),
                             rg::Usage::ColorAttachment);
        if (shadows) d.atlas = b.read(bb.get<rg::Texture>("shadow.atlas"), rg::Usage::SampledFragment);
      },
      [this, ctx, width, height, staticCount = f.staticCount, ranges = std::move(f.dynamicRanges),
       packed = std::move(packed), slots = std::move(slots),
       tags = std::move(f.entityTags)](const LightsData& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = ctx->cmd(c);
        SlotBuffers& buf = buffers_[ctx->frame().slot % buffers_.size()];
        fill(ctx_, buf.lights, packed.data(), packed.size() * sizeof(VlmLightGpu), "vlm.lights");
        fill(ctx_, buf.slots, slots.data(), slots.size() * 4, "vlm.slots");
        fill(ctx_, buf.tags, tags.data(), tags.size() * 4, "vlm.tags");
        VkSampler compare = ctx->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                                VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 1.0f, true});
        gpu::Image& atlas = d.atlas ? ctx->backend->image(res.texture(*d.atlas)) : *ctx->dummyShadowAtlas;
        VkDescriptorSet set = ctx->frame().descriptors->allocate(lightsLayout_);
        gpu::DescriptorWriter()
            .buffer(0, buf.lights)
            .sampledImage(1, ctx->frameView(atlas, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, atlas.desc().layers), compare)
            .buffer(2, *ctx->shadowMatrices)
            .buffer(3, *ctx->lights)
            .update(*ctx->gpu, set);
        gpu::Image& target = ctx->backend->image(res.texture(d.radiance));
        render::Attachment color{target.view(), false};
        render::beginRendering(*ctx->gpu, cmd, {width, height}, {&color, 1}, nullptr);
        lightsPipeline_.bind(cmd);
        lightsPipeline_.bindSet(cmd, 0, set);
        // One draw per range, scissored to the rows holding it: the static lights, then each
        // dynamic VLM in its own timestamp scope (issue 5 §7: per-object cost rows).
        auto draw = [&](std::uint32_t first, std::uint32_t n) {
          const std::uint32_t row0 = first / width, row1 = (first + n - 1) / width;
          const VkRect2D scissor{{0, std::int32_t(row0)}, {width, row1 - row0 + 1}};
          vkCmdSetScissor(cmd, 0, 1, &scissor);
          lightsPipeline_.push(cmd, LightsPush{n, width, ctx->lightCount, d.atlas ? 1u : 0u, update_.settings().shadowLift, first});
          vkCmdDraw(cmd, 3, 1, 0, 0);
        };
        if (staticCount) draw(0, staticCount);
        gpu::TimestampPool* ts = ctx->frame().timestamps.get();
        for (const auto& r : ranges) {
          if (!r.count) continue;
          if (ts) ts->begin(cmd, "vlm.lights/" + r.name);
          draw(r.first, r.count);
          if (ts) ts->end(cmd);
        }
        ctx->gpu->cmdEndRendering(cmd);
      });
  const rg::Handle<rg::Texture> radiance = lights.radiance;

  // Phase 2: full screen, additive into "lighting.hdr".
  struct ShadeData {
    render::DeferredInputs g;  // with entity
    rg::Handle<rg::Texture> radiance, hdr;
  };
  const auto& data = graph.addPass<ShadeData>(
      "vlm",
      [&](rg::Builder& b, ShadeData& d) {
        d.g = render::readDeferredInputs(b, bb, /*withEntity=*/true);
        d.radiance = b.read(radiance, rg::Usage::SampledFragment);
        d.hdr = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
      },
      [this, ctx, staticShade, dynamicShade, objects, viewProj, staticCount = f.staticCount](
          const ShadeData& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = ctx->cmd(c);
        SlotBuffers& buf = buffers_[ctx->frame().slot % buffers_.size()];
        VkSampler point = ctx->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return ctx->backend->image(res.texture(h)).view(); };
        VkDescriptorSet set = ctx->frame().descriptors->allocate(shadeLayout_);
        gpu::DescriptorWriter writer;
        render::writeDeferredInputs(writer, d.g, *ctx, res, point)
            .sampledImage(3, view(d.g.entity), point)
            .buffer(4, buf.lights)
            .sampledImage(5, view(d.radiance), point)
            .buffer(6, buf.slots)
            .buffer(7, buf.tags)
            .update(*ctx->gpu, set);
        gpu::Image& target = ctx->backend->image(res.texture(d.hdr));
        render::Attachment color{target.view(), true};  // additive: keep the direct light
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(*ctx->gpu, cmd, extent, {&color, 1}, nullptr);
        shadePipeline_.bind(cmd);
        shadePipeline_.bindSet(cmd, 0, ctx->frameSet);
        shadePipeline_.bindSet(cmd, 1, set);
        if (staticCount) {
          shadePipeline_.push(cmd, staticShade);
          vkCmdDraw(cmd, 3, 1, 0, 0);
        }
        gpu::TimestampPool* ts = ctx->frame().timestamps.get();
        for (const auto& o : objects) {
          const VkRect2D scissor = screenRect(viewProj, o.lo, o.hi, extent);
          if (!o.count || !scissor.extent.width || !scissor.extent.height) continue;
          if (ts) ts->begin(cmd, "vlm/" + o.name);
          vkCmdSetScissor(cmd, 0, 1, &scissor);
          ShadePush push = dynamicShade;
          push.lightRange = glm::uvec4(o.first, o.first + o.count, 0, 0);
          shadePipeline_.push(cmd, push);
          vkCmdDraw(cmd, 3, 1, 0, 0);
          if (ts) ts->end(cmd);
        }
        ctx->gpu->cmdEndRendering(cmd);
      });
  bb.put("lighting.hdr", data.hdr);
}

}  // namespace bounce::gi::vlm
