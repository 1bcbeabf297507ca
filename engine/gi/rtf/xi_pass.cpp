#include "engine/gi/rtf/xi_pass.hpp"

#include <algorithm>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "engine/core/error.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/context.hpp"

namespace bounce::gi::rtf {

namespace {

template <class T>
gpu::Buffer storage(gpu::Context& ctx, const std::vector<T>& data, const std::string& name) {
  const std::size_t bytes = std::max<std::size_t>(data.size() * sizeof(T), 16);  // never a 0-byte buffer
  gpu::Buffer b(ctx, {bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUsage::GpuOnly, name});
  if (!data.empty())
    gpu::upload(ctx, b, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(data.data()), data.size() * sizeof(T)));
  return b;
}

// xi.comp's half basis rows and α (cpca.hpp storedParts): halves already (cpca.hpp quantize, so packing loses
// nothing) two to a uint as GLSL's packHalf2x16 lays them out, element 2w in the low 16 bits of word
// w; an odd count ends with a zero half.
std::vector<std::uint32_t> halfWords(const std::vector<float>& v) {
  std::vector<std::uint32_t> w((v.size() + 1) / 2, 0u);
  for (std::size_t i = 0; i < v.size(); i += 2) {
    const glm::vec2 pair(v[i], i + 1 < v.size() ? v[i + 1] : 0.0f);
    w[i / 2] = glm::packHalf2x16(pair);
    if (glm::unpackHalf2x16(w[i / 2]) != pair) throw InternalError("rtf::XiPass: CPCA not rounded to fp16 (rtf::quantize)");
  }
  return w;
}

// xi.comp's 8-bit codes, four to a uint, element 4w + b in bits 8b..8b+7 of word w (two's
// complement, read with bitfieldExtract); a count not a multiple of 4 ends with zero bytes.
std::vector<std::uint32_t> byteWords(const std::vector<std::int8_t>& q) {
  std::vector<std::uint32_t> w((q.size() + 3) / 4, 0u);
  for (std::size_t i = 0; i < q.size(); ++i) w[i / 4] |= std::uint32_t(std::uint8_t(q[i])) << (8 * (i % 4));
  return w;
}

// vkCmdUpdateBuffer in 64 KiB calls (its limit; in the command stream, so frames in flight keep theirs).
template <class T>
void updateChunked(VkCommandBuffer cmd, const gpu::Buffer& buffer, std::span<const T> data) {
  constexpr std::size_t kChunk = 65536 / sizeof(T);
  for (std::size_t at = 0; at < data.size(); at += kChunk)
    vkCmdUpdateBuffer(cmd, buffer.handle(), at * sizeof(T), std::min(kChunk, data.size() - at) * sizeof(T), data.data() + at);
}

}  // namespace

bool computeSubgroupArithmetic(const gpu::Context& ctx) {
  VkPhysicalDeviceSubgroupProperties sub{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES, nullptr, 0, 0, 0, VK_FALSE};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &sub, {}};
  vkGetPhysicalDeviceProperties2(ctx.physicalDevice(), &props);
  return (sub.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) != 0 && (sub.supportedOperations & VK_SUBGROUP_FEATURE_ARITHMETIC_BIT) != 0;
}

XiPass::XiPass(gpu::Context& ctx, const Field& f, XiPassOptions options)
    : settings_(f.settings),
      keepXi_(options.keepXi),
      setLayout_(ctx,
                 {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                  {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
                  {8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {11, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {12, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {13, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {14, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                 "rtf.xi"),
      layout_(ctx, {setLayout_}, {{VK_SHADER_STAGE_ALL, 0, sizeof(Push)}}, "rtf.xi"),
      descriptors_(ctx) {
  const FieldSettings& s = f.settings;
  push_ = {0, std::uint32_t(s.proxies), std::uint32_t(f.itf.clusters), std::uint32_t(f.itf.components),
           std::uint32_t(sampleCount(s)), std::uint32_t(s.faceSize), std::uint32_t(f.itf.byteComponents),
           s.innerRadius, s.outerRadius};
  const CpcaParts parts = storedParts(f.itf);
  basis_ = storage(ctx, halfWords(parts.basisHalves), "rtf.basis");
  alpha_ = storage(ctx, halfWords(parts.alphaHalves), "rtf.alpha");
  basisCodes_ = storage(ctx, byteWords(parts.basisCodes), "rtf.basis_codes");
  alphaCodes_ = storage(ctx, byteWords(parts.alphaCodes), "rtf.alpha_codes");
  std::vector<float> scales = f.itf.basisScale;  // xi.comp `scales`: n_c·n₈ row scales, then N sample scales
  scales.insert(scales.end(), f.itf.alphaScale.begin(), f.itf.alphaScale.end());
  codeScales_ = storage(ctx, scales, "rtf.code_scales");
  cluster_ = storage(ctx, f.itf.cluster, "rtf.cluster");
  // Written by vkCmdUpdateBuffer in record(): ordered in the command stream, so a frame in flight
  // never sees the next frame's light (m·16·16 bytes ≤ 16 KiB < the command's 64 KiB limit).
  light_ = gpu::Buffer(ctx, {(std::size_t(s.proxies) * kShCount + kShCount * 9) * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             gpu::MemoryUsage::GpuOnly, "rtf.light"});
  eigen_ = gpu::Buffer(ctx, {std::size_t(f.itf.clusters) * std::size_t(f.itf.components + 1) * kShCount * 16,
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuOnly, "rtf.eigen"});
  gpu::ImageDesc d;
  d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  d.width = std::uint32_t(6 * s.faceSize);
  d.height = std::uint32_t(s.faceSize);
  d.layers = std::uint32_t(s.spheres * kShCount);
  d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.name = "rtf.xi";
  {
    gpu::ImageDesc xd = d;  // without keepXi nothing is stored there: two 1×1 layers keep binding 5 a valid 2D array
    if (!keepXi_) {
      xd.width = xd.height = 1;
      xd.layers = 2;
    }
    xi_ = gpu::Image(ctx, xd);
  }
  gpu::ImageDesc nd = d;
  nd.format = VK_FORMAT_R8G8B8A8_UNORM;  // X in DNRT's Table 2 order, kNetVariants × 7 texels per sample (xi.glsl)
  nd.type = gpu::ImageType::Tex3D;
  nd.layers = 1;
  nd.depth = std::uint32_t(s.spheres) * kNetTexels * kNetVariants;
  if (nd.depth > ctx.limits().maxImageDimension3D)
    throw InternalError("rtf: a field of " + std::to_string(s.spheres) + " spheres needs a 3D image " + std::to_string(nd.depth) +
                        " texels deep for X; this device allows " + std::to_string(ctx.limits().maxImageDimension3D) +
                        " (fewer spheres: the level's \"rtf\": {\"spheres\"})");
  nd.name = "rtf.net";
  net_ = gpu::Image(ctx, nd);
  // ξ and X stay in GENERAL for the pass's life (written as storage images, sampled in GENERAL).
  // The one move out of UNDEFINED happens here, in a one-time submit, not in the first frame's
  // command buffer: a layout change recorded by a pass is outside the render graph's layout journal,
  // so a first frame abandoned after recording it would leave the tracked layout at GENERAL while
  // the GPU still holds UNDEFINED (review 15, item 2).
  gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    gpu::transition(cmd, xi_, VK_IMAGE_LAYOUT_GENERAL);
    gpu::transition(cmd, net_, VK_IMAGE_LAYOUT_GENERAL);
  });
  // Read by xi.comp (atomicMax, then the encoding) and by the shading pass as a uniform block.
  range_ = gpu::Buffer(ctx, {kNetTexels * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
                                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                             gpu::MemoryUsage::GpuOnly, "rtf.net-range"});
  netValue_ = gpu::Buffer(ctx, {sampleCount(s) * kNetVariants * 9 * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuOnly, "rtf.net-value"});
  oofBuffer_ = storage(ctx, f.oof, "rtf.oof-buffer");
  scaleBuffer_ = storage(ctx, std::vector<glm::vec4>(sampleCount(s), glm::vec4(1.0f)), "rtf.blocked-scale");
  onObjectsBuffer_ = storage(ctx, std::vector<float>(sampleCount(s), 1.0f), "rtf.on-objects");
  gpu::ImageDesc o = d;
  o.layers = std::uint32_t(s.spheres * 4);
  o.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  o.name = "rtf.oof";
  oof_ = gpu::Image(ctx, o);
  {
    const std::size_t w = d.width, h = d.height;
    std::vector<float> texels(std::size_t(o.layers) * w * h * 4, 0.0f);
    const int n2 = s.faceSize * s.faceSize, per = samplesPerSphere(s);
    for (std::size_t r = 0; r < sampleCount(s); ++r) {
      const int sphere = int(r) / per, rest = int(r) % per, face = rest / n2, y = rest % n2 / s.faceSize, x = rest % s.faceSize;
      for (int i = 0; i < kShCount; ++i) {
        const std::size_t layer = std::size_t(sphere * 4 + i / 4);
        texels[((layer * h + std::size_t(y)) * w + std::size_t(face * s.faceSize + x)) * 4 + std::size_t(i % 4)] = f.oof[r * kShCount + std::size_t(i)];
      }
    }
    gpu::upload(ctx, oof_, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(texels.data()), texels.size() * sizeof(float)));
  }
  const bool subgroupMax = options.subgroupMax && computeSubgroupArithmetic(ctx);
  // Two modules, not a specialization constant: the subgroup capability must not reach a device without it.
  pipeline_ = gpu::createComputePipeline(ctx, layout_, gpu::ShaderModule(ctx, subgroupMax ? "rtf/xi_subgroup.comp.spv" : "rtf/xi.comp.spv"),
                                         "rtf.xi", nullptr, {keepXi_ ? 1u : 0u});
  set_ = descriptors_.allocate(setLayout_);
  gpu::DescriptorWriter()
      .buffer(0, basis_)
      .buffer(1, alpha_)
      .buffer(2, cluster_)
      .buffer(3, light_)
      .buffer(4, eigen_)
      .storageImage(5, xi_.view())
      .buffer(6, oofBuffer_)
      .storageImage(7, net_.view())
      .buffer(8, range_)
      .buffer(9, netValue_)
      .buffer(10, scaleBuffer_)
      .buffer(11, basisCodes_)
      .buffer(12, alphaCodes_)
      .buffer(13, codeScales_)
      .buffer(14, onObjectsBuffer_)
      .update(ctx, set_);
  blocked_.assign(kShCount * 9, glm::vec4(0.0f));
  std::vector<glm::vec3> zero(std::size_t(s.proxies) * kShCount, glm::vec3(0.0f));
  setProxyLight(zero);
}

gpu::Image& XiPass::xi() {
  if (!keepXi_) throw InternalError("rtf::XiPass: ξ is stored only with XiPassOptions::keepXi");
  return xi_;
}

void XiPass::setProxyLight(std::span<const glm::vec3> light) {
  if (light.size() != std::size_t(settings_.proxies) * kShCount) throw InternalError("rtf::XiPass: proxy light is not m·16 coefficients");
  pending_.clear();
  for (const glm::vec3& l : light) pending_.emplace_back(l, 0.0f);
}

void XiPass::setBlockedLight(std::span<const glm::vec4> blocked) {
  if (blocked.size() != std::size_t(kShCount) * 9) throw InternalError("rtf::XiPass: blocked light is not 16·9 entries");
  blocked_.assign(blocked.begin(), blocked.end());
}

void XiPass::setBlockedScale(std::span<const glm::vec4> scale, std::span<const float> onObjects) {
  if (!scale.empty() && scale.size() != sampleCount(settings_)) throw InternalError("rtf::XiPass: blocked scale is not one per sample");
  if (!onObjects.empty() && onObjects.size() != sampleCount(settings_))
    throw InternalError("rtf::XiPass: the on-object factor is not one per sample");
  scale_.assign(scale.begin(), scale.end());
  onObjects_.assign(onObjects.begin(), onObjects.end());
}

void XiPass::record(VkCommandBuffer cmd) {
  // The previous frame's reads (X in fragment shaders, its ranges in vertex shaders, light and eigen here) finish before this
  // frame's writes (write-after-read: an execution dependency suffices).
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr, 0,
                       nullptr);
  std::vector<glm::vec4> data = pending_;
  data.insert(data.end(), blocked_.begin(), blocked_.end());
  vkCmdUpdateBuffer(cmd, light_.handle(), 0, data.size() * sizeof(glm::vec4), data.data());
  if (!scale_.empty() || !scaleIsOnes_) {
    const std::vector<glm::vec4> ones(scale_.empty() ? sampleCount(settings_) : 0, glm::vec4(1.0f));
    updateChunked(cmd, scaleBuffer_, std::span<const glm::vec4>(scale_.empty() ? ones : scale_));
    scaleIsOnes_ = scale_.empty();
  }
  if (!onObjects_.empty() || !scale_.empty() || !onObjectsAreOnes_) {
    // Without its own values the on-object factor is the scale's w (1 with no scale): both variants alike.
    std::vector<float> w;
    if (onObjects_.empty())
      for (std::size_t r = 0; r < sampleCount(settings_); ++r) w.push_back(scale_.empty() ? 1.0f : scale_[r].w);
    updateChunked(cmd, onObjectsBuffer_, std::span<const float>(onObjects_.empty() ? w : onObjects_));
    onObjectsAreOnes_ = onObjects_.empty() && scale_.empty();
  }
  vkCmdFillBuffer(cmd, range_.handle(), 0, VK_WHOLE_SIZE, 0u);  // atomicMax starts from +0.0
  VkMemoryBarrier uploaded{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};  // the atomics read and write
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &uploaded, 0, nullptr,
                       0, nullptr);
  pipeline_.bind(cmd);
  pipeline_.bindSet(cmd, 0, set_);
  Push p = push_;
  p.stage = 0;
  pipeline_.push(cmd, p);
  const std::uint32_t eigenRows = p.clusters * (p.components + 1);  // one invocation per (h, e)
  vkCmdDispatch(cmd, (eigenRows + 63) / 64, 1, 1);
  // Stage 1 reads what stage 0 wrote.
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
  p.stage = 1;
  pipeline_.push(cmd, p);
  vkCmdDispatch(cmd, (p.samples + 63) / 64, 1, 1);  // one invocation per sample
  // Stage 2 reads every X and the finished ranges.
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
  p.stage = 2;
  pipeline_.push(cmd, p);
  vkCmdDispatch(cmd, (p.samples + 63) / 64, 1, 1);  // one invocation per sample, all kNetVariants·kNetTexels texels
  VkMemoryBarrier done{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_UNIFORM_READ_BIT};
  // The shading pass reads the ranges in its vertex shader (rtf.vert), X in its fragment shader.
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                           VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                       0, 1, &done, 0,
                       nullptr, 0, nullptr);
}

}  // namespace bounce::gi::rtf
