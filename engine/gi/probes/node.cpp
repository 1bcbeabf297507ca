#include "engine/gi/probes/node.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/packing.hpp>

#include "engine/core/error.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/render/passes/rendering.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"

namespace bounce::gi::probes {
namespace {

// Probe p = x + count.x·row of the volume in texel row `row`, `slots` texels per probe in that row
// (probes.frag probeTexel). Throws when the layout exceeds the device's 2D image size.
gpu::ImageDesc probeImageDesc(gpu::Context& ctx, const ProbeGrid& g, std::uint32_t slots, VkFormat format,
                              const char* name) {
  gpu::ImageDesc d;
  d.format = format;
  d.width = slots * std::uint32_t(g.count.x);
  d.height = std::uint32_t(g.count.y) * std::uint32_t(g.count.z);
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  d.name = name;
  const std::uint32_t limit = ctx.limits().maxImageDimension2D;
  if (d.width > limit || d.height > limit)
    throw InternalError(std::string("probes: ") + name + " image " + std::to_string(d.width) + "x" +
                        std::to_string(d.height) + " exceeds the device's " + std::to_string(limit) +
                        " (fewer probes per axis: a larger spacing)");
  return d;
}

// SH texels per probe: 3 floats a coefficient, then the valid flag, 4 floats a texel (probes.frag kTexels).
std::uint32_t shTexels(const ProbeVolume& v) { return std::uint32_t(3 * v.coeffs() + 4) / 4; }

// SH texels, probe-major: probe p's texel t at 4·(t + shTexels·p), packing L_0.rgb, L_1.rgb, …,
// valid, as probe_sh.glsl reads them (the row-major image layout, and the uniform block's).
std::vector<float> shTexelFloats(const ProbeVolume& v) {
  const std::size_t probes = v.grid.probeCount(), coeffs = std::size_t(v.coeffs()), stride = 4 * shTexels(v);
  std::vector<float> floats(probes * stride, 0.0f);
  for (std::size_t p = 0; p < probes; ++p) {
    float* out = floats.data() + p * stride;
    for (std::size_t i = 0; i < coeffs; ++i)
      for (int ch = 0; ch < 3; ++ch) out[3 * i + std::size_t(ch)] = v.sh[p * coeffs + i][ch];
    out[3 * coeffs] = v.valid[p] != 0 ? 1.0f : 0.0f;
  }
  return floats;
}

// The uniform block's texels per probe: shTexelFloats' 3·coeffs + 1 values as halves, 8 a texel
// (probe_sh.glsl kHalfTexels): order 3: 4, order 2: 2.
std::uint32_t shHalfTexels(const ProbeVolume& v) { return std::uint32_t(3 * v.coeffs() + 1 + 7) / 8; }

// The largest finite half; a volume with a larger |value| keeps the image path.
constexpr float kHalfMax = 65504.0f;

// probe_sh.glsl's ProbeShBlock: shTexelFloats' values per probe, rounded to halves (nearest) and
// packed two a word as GLSL's packHalf2x16 (low half first), 4 words a texel, probe p's texel t at
// word 4·(t + shHalfTexels·p). Then, after the last probe's texels, the valid flags as bits:
// probe p's is bit p % 32 of the first word of texel shHalfTexels·probes + p / 32 (probeValid reads
// that one word; reading the texel holding the valid half cost ~0.25 of the lighting pass on
// llvmpipe, this ~0.1: README "DNRT and probes cost, session 8"). Empty when a value is past kHalfMax.
std::vector<std::uint32_t> shHalfTexelWords(const ProbeVolume& v) {
  const std::size_t probes = v.grid.probeCount(), values = std::size_t(3 * v.coeffs() + 1);
  const std::size_t floatStride = 4 * shTexels(v), wordStride = 4 * shHalfTexels(v);
  const std::vector<float> floats = shTexelFloats(v);
  std::vector<std::uint32_t> words(probes * wordStride + 4 * ((probes + 31) / 32), 0u);
  for (std::size_t p = 0; p < probes; ++p)
    if (v.valid[p] != 0) words[probes * wordStride + 4 * (p / 32)] |= 1u << (p % 32);
  for (std::size_t p = 0; p < probes; ++p)
    for (std::size_t h = 0; h < values; h += 2) {
      const float a = floats[p * floatStride + h], b = h + 1 < values ? floats[p * floatStride + h + 1] : 0.0f;
      if (!(std::abs(a) <= kHalfMax && std::abs(b) <= kHalfMax)) return {};
      words[p * wordStride + h / 2] = glm::packHalf2x16(glm::vec2(a, b));
    }
  return words;
}

// probe_sh.glsl's ProbeMomentsBlock: bin b of probe p at word kVisBins·p + b, packHalf2x16 of
// (mean, σ) with σ = sqrt(max(mean square − mean², 0)) (m). Empty when a value is past kHalfMax.
std::vector<std::uint32_t> momentHalfWords(const ProbeVolume& v) {
  std::vector<std::uint32_t> words(v.moments.size(), 0u);
  for (std::size_t i = 0; i < v.moments.size(); ++i) {
    const double mean = v.moments[i].x, variance = double(v.moments[i].y) - mean * mean;
    const float sigma = float(std::sqrt(std::max(variance, 0.0)));
    if (!(std::abs(v.moments[i].x) <= kHalfMax && sigma <= kHalfMax)) return {};
    words[i] = glm::packHalf2x16(glm::vec2(v.moments[i].x, sigma));
  }
  return words;
}

// probes.frag's ProbeShBlock: 4096 uvec4 = 64 KiB, lavapipe's maxUniformBufferRange (the Vulkan
// minimum is 16 KiB; a device below 64 KiB keeps the image path). Order 3: 1016 probes with their
// valid bits (a 0.125 m grid over cornell-1, 9³ = 729, fits); order 2: 2032.
constexpr VkDeviceSize kShUboBytes = 4096 * 16;
// probes.frag's ProbeMomentsBlock, the same 64 KiB: 256 B a probe, so up to 256 probes (cornell-1's
// 0.25 m volume, 6³ = 216, fits; the 0.125 m one, 9³, keeps the image).
constexpr VkDeviceSize kMomentsUboBytes = 4096 * 16;

}  // namespace

// SH texels (t + shTexels·x, row).
std::unique_ptr<gpu::Image> uploadSh(gpu::Context& ctx, const ProbeVolume& v) {
  auto image = std::make_unique<gpu::Image>(ctx, probeImageDesc(ctx, v.grid, shTexels(v), VK_FORMAT_R32G32B32A32_SFLOAT, "probes.sh"));
  const std::vector<float> floats = shTexelFloats(v);
  gpu::upload(ctx, *image, {reinterpret_cast<const std::uint8_t*>(floats.data()), floats.size() * sizeof(float)});
  return image;
}

// Moments texels (bin + kVisBins·x, row) = (mean, mean square).
std::unique_ptr<gpu::Image> uploadMoments(gpu::Context& ctx, const ProbeVolume& v) {
  auto image = std::make_unique<gpu::Image>(
      ctx, probeImageDesc(ctx, v.grid, std::uint32_t(kVisBins), VK_FORMAT_R32G32_SFLOAT, "probes.moments"));
  static_assert(sizeof(glm::vec2) == 8, "RG32F texels");
  gpu::upload(ctx, *image, {reinterpret_cast<const std::uint8_t*>(v.moments.data()), v.moments.size() * sizeof(glm::vec2)});
  return image;
}

ProbePush probePush(const ProbeVolume& v, float flag) {
  const ProbeGrid& g = v.grid;
  return {glm::vec4(g.origin, g.spacing), glm::ivec4(g.count, v.order),
          glm::vec4(g.spacing * v.bias.normal, g.spacing * v.bias.view, v.minVariance(), flag)};
}

ProbeNode::ProbeNode(gpu::Context& ctx, const render::Pipelines& pipelines, ProbeVolume volume, bool shInUbo)
    : volume_(std::move(volume)),
      sh_(uploadSh(ctx, volume_)),
      moments_(uploadMoments(ctx, volume_)),
      setLayout_(ctx,
                 {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {5, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                  {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {7, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}},
                 "probes") {
  {
    const std::vector<std::uint32_t> words = shHalfTexelWords(volume_);
    const VkDeviceSize bytes = words.size() * sizeof(std::uint32_t);
    shInUbo_ = shInUbo && !words.empty() && bytes <= kShUboBytes && kShUboBytes <= ctx.limits().maxUniformBufferRange;
    shUbo_ = gpu::Buffer(ctx, {kShUboBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               gpu::MemoryUsage::GpuOnly, "probes.sh.ubo"});
    if (shInUbo_) gpu::upload(ctx, shUbo_, {reinterpret_cast<const std::uint8_t*>(words.data()), std::size_t(bytes)});
  }
  {
    const std::vector<std::uint32_t> words = momentHalfWords(volume_);
    const VkDeviceSize bytes = words.size() * sizeof(std::uint32_t);
    momentsInUbo_ = shInUbo_ && !words.empty() && bytes <= kMomentsUboBytes &&
                    kMomentsUboBytes <= ctx.limits().maxUniformBufferRange;
    momentsUbo_ = gpu::Buffer(ctx, {kMomentsUboBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    gpu::MemoryUsage::GpuOnly, "probes.moments.ubo"});
    if (momentsInUbo_)
      gpu::upload(ctx, momentsUbo_, {reinterpret_cast<const std::uint8_t*>(words.data()), std::size_t(bytes)});
  }
  layout_ = gpu::PipelineLayout(ctx, {pipelines.frameLayout.handle(), setLayout_.handle()},
                                {{VK_SHADER_STAGE_ALL, 0, sizeof(ProbePush)}}, "probes");
  gpu::ShaderModule vert(ctx, "passes/fullscreen.vert.spv");
  gpu::ShaderModule frag(ctx, "probes/probes.frag.spv");
  gpu::GraphicsPipelineDesc d;
  d.vertex = &vert;
  d.fragment = &frag;
  d.colorFormats = {VK_FORMAT_R16G16B16A16_SFLOAT};
  d.blend = gpu::Blend::Additive;
  d.specialization = {std::uint32_t(volume_.coeffs()), shInUbo_ ? 1u : 0u,
                      momentsInUbo_ ? 1u : 0u};  // probes.frag kCoeffs, kShInUbo, kMomentsInUbo
  d.name = "probes";
  pipeline_ = gpu::createGraphicsPipeline(ctx, layout_, d);
}

void ProbeNode::addPasses(rg::RenderGraph& graph, const render::PassContext* pc) {
  struct Data {
    render::DeferredInputs g;
    rg::Handle<rg::Texture> hdr, ao;
  };
  auto& bb = graph.blackboard();
  // An AO node (ssao/hbao) set before this one publishes "ao.term": the indirect term is then
  // multiplied by it, the way the DNRT paper's baselines use AO (§6.4). Without one, binding 6
  // repeats the albedo and the shader ignores it.
  const bool withAo = bb.contains("ao.term");
  const auto& data = graph.addPass<Data>(
      "probes",
      [&](rg::Builder& b, Data& d) {
        d.g = render::readDeferredInputs(b, bb);
        d.hdr = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
        if (withAo) d.ao = b.read(bb.get<rg::Texture>("ao.term"), rg::Usage::SampledFragment);
      },
      [this, pc, withAo](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler point = pc->samplers->get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
        auto view = [&](rg::Handle<rg::Texture> h) { return pc->backend->image(res.texture(h)).view(); };
        VkDescriptorSet set = pc->frame().descriptors->allocate(setLayout_);
        gpu::DescriptorWriter()
            .sampledImage(0, view(d.g.albedo), point)
            .sampledImage(1, view(d.g.normal), point)
            .sampledImage(2, view(d.g.depth), point)
            .sampledImage(3, sh_->view(), point)
            .sampledImage(4, moments_->view(), point)
            .buffer(5, shUbo_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kShUboBytes)
            .buffer(7, momentsUbo_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kMomentsUboBytes)
            .sampledImage(6, view(withAo ? d.ao : d.g.albedo), point)
            .update(*pc->gpu, set);
        gpu::Image& target = pc->backend->image(res.texture(d.hdr));
        render::Attachment color{target.view(), true};  // additive: keep the direct light
        const VkExtent2D extent{target.desc().width, target.desc().height};
        render::beginRendering(*pc->gpu, cmd, extent, {&color, 1}, nullptr);
        pipeline_.bind(cmd);
        pipeline_.bindSet(cmd, 0, pc->frameSet);
        pipeline_.bindSet(cmd, 1, set);
        pipeline_.push(cmd, probePush(volume_, withAo ? 1.0f : 0.0f));
        vkCmdDraw(cmd, 3, 1, 0, 0);
        pc->gpu->cmdEndRendering(cmd);
      });
  bb.put("lighting.hdr", data.hdr);
}

}  // namespace bounce::gi::probes
