#include "engine/gi/sl/local_light_pass.hpp"

#include "engine/gi/sl/tiles.hpp"
#include "engine/render/gpu_types.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/hdr_format.hpp"

namespace bounce::gi::sl {

namespace {
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kUniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
constexpr std::uint32_t kTilesBinding = 6;                     // tiles.glsl: SlTiles
constexpr std::uint32_t kFirstShadeBinding = 7;                // local_light.frag: SL_BINDING

// local_light.frag's push block, then tiles.glsl's at SL_TILE_PUSH_OFFSET 16 (local_tiles.vert).
struct LightPush {
  std::uint32_t lightCount = 0, shadowsOn = 0, pad0 = 0, pad1 = 0;
};
static_assert(sizeof(LightPush) == 16, "local_tiles.vert: SL_TILE_PUSH_OFFSET");

std::vector<gpu::Binding> inputBindings() {
  // G-buffer albedo, normal, depth; shadow atlas, shadow matrices, lights; the tiles; the SLs.
  std::vector<gpu::Binding> b = {{0, kSampled}, {1, kSampled}, {2, kSampled}, {3, kSampled}, {4, kUniform}, {5, kUniform},
                                 {kTilesBinding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
  for (const gpu::Binding& s : ShadeData::bindings(kFirstShadeBinding)) b.push_back(s);
  return b;
}
}  // namespace

LocalLightPass::LocalLightPass(gpu::Context& ctx, const render::Pipelines& shared, int order, Blocking blocking,
                               std::uint32_t spheres, float influence)
    : ctx_(ctx),
      inputLayout_(ctx, inputBindings(), "sl.local.inputs"),
      layout_(ctx, {shared.frameLayout, inputLayout_},
              {{VK_SHADER_STAGE_ALL, 0, sizeof(LightPush) + sizeof(TilePush)}}, "sl.local") {
  gpu::ShaderModule vert(ctx, "sl/local_tiles.vert.spv");
  gpu::ShaderModule frag(ctx, "sl/local_light.frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert;
  d.fragment = &frag;
  d.colorFormats = {render::kLightingHdrFormat};
  d.blend = gpu::Blend::Additive;  // RGBA16F keeps the negative sum: the shadow takes light away
  d.specialization = ShadeData::specialization(order, blocking, spheres, influence);
  d.name = "sl.local";
  pipeline_ = gpu::createGraphicsPipeline(ctx, layout_, d);
}

void LocalLightPass::addTo(rg::RenderGraph& graph, const render::PassContext* pc, const ShadeData& shade,
                           const gpu::Buffer& intensity, TileRange tiles) {
  auto& bb = graph.blackboard();
  struct Data {
    render::DeferredInputs g;
    rg::Handle<rg::Texture> target;
    std::optional<rg::Handle<rg::Texture>> atlas;
  };
  const auto& data = graph.addPass<Data>(
      "sl.local",
      [&](rg::Builder& b, Data& d) {
        d.g = render::readDeferredInputs(b, bb);
        d.target = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
        if (auto atlas = bb.find<rg::Texture>("shadow.atlas")) d.atlas = b.read(*atlas, rg::Usage::SampledFragment);
      },
      [this, pc, &shade, &intensity, tiles](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        // The lighting pass's compare sampler (shadow.glsl: LESS_OR_EQUAL, linear = 2×2 PCF).
        VkSampler compare = pc->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                               VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 1.0f, true});
        gpu::Image& atlas = d.atlas ? pc->backend->image(res.texture(*d.atlas)) : *pc->dummyShadowAtlas;
        VkDescriptorSet inputs = pc->frame().descriptors->allocate(inputLayout_);
        gpu::DescriptorWriter w;
        render::writeDeferredInputs(w, d.g, *pc, res, point)
            .sampledImage(3, pc->frameView(atlas, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, atlas.desc().layers), compare,
                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
            .buffer(4, *pc->shadowMatrices, kUniform, 0, render::kMaxShadowLayers * sizeof(glm::mat4))
            .buffer(5, *pc->lights, kUniform, 0, render::kMaxLights * sizeof(render::LightGpu));
        w.buffer(kTilesBinding, *tiles.buffer);
        shade.write(w, kFirstShadeBinding, intensity, point);
        w.update(ctx_, inputs);
        gpu::Image& target = pc->backend->image(res.texture(d.target));
        render::Attachment color{target.view(), true};  // additive: keep what is there
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(ctx_, cmd, extent, {&color, 1}, nullptr);
        pipeline_.bind(cmd);
        pipeline_.bindSet(cmd, 0, pc->frameSet);
        pipeline_.bindSet(cmd, 1, inputs);
        struct Push {
          LightPush light;
          TilePush tile;
        };
        const Push push{LightPush{pc->lightCount, d.atlas ? 1u : 0u},
                        TilePush{glm::vec2(1.0f / float(extent.width), 1.0f / float(extent.height)), kScreenTile, 0u}};
        pipeline_.push(cmd, push);
        if (tiles.count > 0) vkCmdDraw(cmd, 6, tiles.count, 0, tiles.first);
        ctx_.cmdEndRendering(cmd);
      });
  bb.put("lighting.hdr", data.target);
}

}  // namespace bounce::gi::sl
