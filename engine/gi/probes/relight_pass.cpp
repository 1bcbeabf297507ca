#include "engine/gi/probes/relight_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "engine/core/error.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/math/sampling.hpp"

namespace bounce::gi::probes {
namespace {

template <class T>
gpu::Buffer deviceBuffer(gpu::Context& ctx, const std::vector<T>& data, const char* name) {
  const std::size_t bytes = std::max<std::size_t>(data.size() * sizeof(T), 16);
  gpu::Buffer b(ctx, {bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                      gpu::MemoryUsage::GpuOnly, name});
  if (!data.empty())
    gpu::upload(ctx, b, {reinterpret_cast<const std::uint8_t*>(data.data()), data.size() * sizeof(T)});
  return b;
}

void computeBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst,
                    VkAccessFlags dstAccess) {
  VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, srcAccess, dstAccess};
  vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &b, 0, nullptr, 0, nullptr);
}

// The stages that read the probe image: probes.frag, sl.shadow and the fused sl pass (fragment);
// compute for any compute reader of probe_sh.glsl.
constexpr VkPipelineStageFlags kImageReaders = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;

}  // namespace

RelightPass::RelightPass(gpu::Context& ctx, const ProbeVolume& volume, RelightData data, const gpu::Buffer& packed,
                         gpu::Image* image, bool block)
    : ctx_(ctx),
      data_(std::move(data)),
      packed_(packed),
      image_(image),
      setLayout_(ctx,
                 {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {3, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                  {4, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                  {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                  {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {10, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {11, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {12, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {13, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                  {14, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                 "probes.relight"),
      layout_(ctx, {setLayout_}, {{VK_SHADER_STAGE_ALL, 0, sizeof(Push)}}, "probes.relight") {
  const std::size_t probes = volume.grid.probeCount();
  if (data_.probes() != probes) throw InternalError("probes::RelightPass: relight data for another grid");
  std::vector<glm::vec4> surfels;
  for (const Surfel& s : data_.surfels) {
    surfels.push_back(glm::vec4(s.position, 1.0f));
    surfels.push_back(glm::vec4(s.normal, 0.0f));
    surfels.push_back(glm::vec4(s.albedo, 0.0f));
  }
  std::vector<glm::vec4> rays(data_.dirs.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    float w;
    std::memcpy(&w, &data_.hit[i], sizeof w);  // relight.comp floatBitsToUint(r.w)
    rays[i] = glm::vec4(data_.dirs[i], w);
  }
  std::vector<glm::vec4> baked(probes * 9, glm::vec4(0.0f));
  for (std::size_t p = 0; p < probes; ++p)
    for (int i = 0; i < volume.coeffs(); ++i) baked[p * 9 + std::size_t(i)] = glm::vec4(volume.sh[p * std::size_t(volume.coeffs()) + std::size_t(i)], 0.0f);
  surfels_ = deviceBuffer(ctx, surfels, "probes.relight.surfels");
  rays_ = deviceBuffer(ctx, rays, "probes.relight.rays");
  baked_ = deviceBuffer(ctx, baked, "probes.relight.baked");
  valid_ = deviceBuffer(ctx, volume.valid, "probes.relight.valid");
  moments_ = deviceBuffer(ctx, volume.moments, "probes.relight.moments");
  radiance_ = deviceBuffer(ctx, std::vector<glm::vec4>(data_.surfels.size(), glm::vec4(0.0f)), "probes.relight.radiance");
  delta_ = deviceBuffer(ctx, std::vector<glm::vec4>(probes * 9, glm::vec4(0.0f)), "probes.relight.delta");
  // E_SL per surfel (setSlBounce): written by "sl.relight_bounce", 0 until its first frame.
  slBounce_ = deviceBuffer(ctx, std::vector<glm::vec4>(data_.surfels.size(), glm::vec4(0.0f)), "probes.relight.sl_bounce");
  const std::size_t visCount = std::max<std::size_t>(data_.surfels.size() * render::kMaxLights, 4);
  vStatic_ = gpu::Buffer(ctx, {visCount * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload,
                               "probes.relight.vstatic"});
  vTest_ = gpu::Buffer(ctx, {visCount * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload,
                             "probes.relight.vtest"});
  std::fill_n(reinterpret_cast<float*>(vStatic_.mapped()), visCount, 1.0f);
  std::fill_n(reinterpret_cast<float*>(vTest_.mapped()), visCount, 1.0f);

  const ProbeGrid& g = volume.grid;
  push_.originSpacing = glm::vec4(g.origin, g.spacing);
  push_.countOrder = glm::ivec4(g.count, volume.order);
  push_.params = glm::vec4(g.spacing * volume.bias.normal, volume.minVariance(),
                           float(4.0 * math::kPi / double(std::max<std::uint32_t>(data_.rays, 1))), 0.0f);
  push_.sizes = glm::uvec4(std::uint32_t(data_.surfels.size()), std::uint32_t(probes), data_.rays, 0u);
  push_.outputs = glm::uvec4(block ? 1u : 0u, image_ ? 1u : 0u, 0u, 0u);
  // 16 B a texel, (3·order² + 4)/4 texels a probe (probe_sh.glsl kTexels); a 16 B stand-in when no
  // image is written (binding 13 is always bound).
  const std::size_t texelBytes = image_ ? probes * std::size_t(3 * volume.coeffs() + 4) / 4 * 16 : 16;
  texels_ = gpu::Buffer(ctx, {texelBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                              gpu::MemoryUsage::GpuOnly, "probes.relight.texels"});
  pipeline_ = gpu::createComputePipeline(ctx, layout_, gpu::ShaderModule(ctx, "probes/relight.comp.spv"), "probes.relight");
}

void RelightPass::setLights(std::span<const render::LightGpu> lights, const ref::SceneBvh& staticScene) {
  if (lights.size() > render::kMaxLights) throw InternalError("probes::RelightPass: more lights than the block holds");
  const bool same = lights.size() == lights_.size() &&
                    (lights.empty() || std::memcmp(lights.data(), lights_.data(), lights.size_bytes()) == 0);
  lightCount_ = std::uint32_t(lights.size());
  if (same) return;
  lights_.assign(lights.begin(), lights.end());
  const std::vector<float> v = staticVisibility(staticScene, data_.surfels, lights);
  if (!v.empty()) std::memcpy(vStatic_.mapped(), v.data(), v.size() * sizeof(float));
}

void RelightPass::setTestVisibility(std::span<const float> vNow) {
  testVis_ = !vNow.empty();
  if (testVis_) std::memcpy(vTest_.mapped(), vNow.data(), std::min(vNow.size_bytes(), std::size_t(vTest_.size())));
}

void RelightPass::reset() {
  const std::vector<glm::vec4> zero(data_.probes() * 9, glm::vec4(0.0f));
  gpu::upload(ctx_, delta_, {reinterpret_cast<const std::uint8_t*>(zero.data()), zero.size() * sizeof(glm::vec4)});
}

void RelightPass::record(VkCommandBuffer cmd, gpu::DescriptorAllocator& descriptors, const gpu::Buffer& lights,
                         std::uint32_t lightCount, const gpu::Buffer& shadowMatrices, VkImageView atlas,
                         VkSampler compare, bool shadowsOn, int iterations, bool pack, int readbackSlot,
                         bool writeImage) {
  VkDescriptorSet set = descriptors.allocate(setLayout_);
  gpu::DescriptorWriter()
      .buffer(0, surfels_)
      .buffer(1, rays_)
      .buffer(2, vStatic_)
      .buffer(3, lights, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, render::kMaxLights * sizeof(render::LightGpu))
      .buffer(4, shadowMatrices, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, render::kMaxShadowLayers * sizeof(glm::mat4))
      .sampledImage(5, atlas, compare)
      .buffer(6, radiance_)
      .buffer(7, delta_)
      .buffer(8, baked_)
      .buffer(9, packed_)
      .buffer(10, valid_)
      .buffer(11, moments_)
      .buffer(12, vTest_)
      .buffer(13, texels_)
      .buffer(14, slBounce_)
      .update(ctx_, set);
  // The lights whose V_static is set (setLights) and the block's count must agree: use the fewer.
  push_.sizes.w = std::min(lightCount, lightCount_);
  push_.flags = glm::uvec4(0u, shadowsOn ? 1u : 0u, testVis_ ? 1u : 0u, 1u);
  const bool image = image_ && writeImage;
  push_.outputs.y = image ? 1u : 0u;  // no texels when no copy follows
  // The previous frame's probes pass read the block this pass rewrites, and its copies read the
  // texels and ΔSH (transfer) that the dispatches rewrite: write after read.
  computeBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT,
                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  pipeline_.bind(cmd);
  pipeline_.bindSet(cmd, 0, set);
  const std::uint32_t surfelGroups = (push_.sizes.x + 63) / 64, probeGroups = (push_.sizes.y + 63) / 64;
  auto rw = [&] {
    computeBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                   VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  };
  for (int it = 0; it < iterations; ++it) {
    push_.flags.x = 0u;
    pipeline_.push(cmd, push_);
    vkCmdDispatch(cmd, std::max(surfelGroups, 1u), 1, 1);
    rw();
    push_.flags.x = 1u;
    pipeline_.push(cmd, push_);
    vkCmdDispatch(cmd, std::max(probeGroups, 1u), 1, 1);
    rw();
  }
  if (!pack) return;
  push_.flags.x = 2u;
  pipeline_.push(cmd, push_);
  vkCmdDispatch(cmd, std::max(probeGroups, 1u), 1, 1);
  computeBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                 VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
  if (image) {
    // The texels into the probe image (row-major texels = probe-major, node.cpp shTexelFloats).
    // Before: the previous frame's reads of the image (probes, sl.shadow: fragment or compute) and
    // its copy (transfer write) finish before this copy writes it — write after read / write.
    gpu::transition(cmd, *image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kImageReaders | VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {image_->desc().width, image_->desc().height, 1};
    vkCmdCopyBufferToImage(cmd, texels_.handle(), image_->handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    // After: this frame's readers see the copy (read after write).
    gpu::transition(cmd, *image_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                    VK_ACCESS_TRANSFER_WRITE_BIT, kImageReaders, VK_ACCESS_SHADER_READ_BIT);
  }
  if (readbackSlot < 0) return;
  // ΔSH for the CPU readers (DNRT's c_j, SL's pass 1, RTF's proxies through incident::ProbeSource),
  // read back when this slot comes round again: no wait on the GPU.
  const auto slot = std::size_t(readbackSlot);
  if (readback_.size() <= slot) readback_.resize(slot + 1), readbackWritten_.resize(slot + 1, false);
  if (!readback_[slot])
    readback_[slot] = gpu::Buffer(ctx_, {delta_.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUsage::Readback,
                                         "probes.relight.readback"});
  const VkBufferCopy region{0, 0, delta_.size()};
  vkCmdCopyBuffer(cmd, delta_.handle(), readback_[slot].handle(), 1, &region);
  computeBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                 VK_ACCESS_HOST_READ_BIT);
  readbackWritten_[slot] = true;
}

bool RelightPass::readDelta(std::uint32_t slot, std::vector<glm::vec3>& out) const {
  if (slot >= readback_.size() || !readbackWritten_[slot] || !readback_[slot].mapped()) return false;
  const std::size_t n = data_.probes() * 9;
  out.resize(n);
  const auto* v = reinterpret_cast<const glm::vec4*>(readback_[slot].mapped());
  for (std::size_t i = 0; i < n; ++i) out[i] = glm::vec3(v[i]);
  return true;
}

}  // namespace bounce::gi::probes

// ---- the node's pass (ProbeNode::addRelightPass, declared in node.hpp) ------------------------------

#include "engine/gi/probes/node.hpp"
#include "engine/render/pass_context.hpp"
#include "engine/render/render_world.hpp"

namespace bounce::gi::probes {

rg::Handle<rg::Buffer> ProbeNode::addRelightPass(rg::RenderGraph& graph, const render::PassContext* pc) {
  struct Data {
    std::optional<rg::Handle<rg::Texture>> atlas;
    rg::Handle<rg::Buffer> block;
  };
  auto& bb = graph.blackboard();
  // The CPU part (V_static) runs while the graph is built, as SL's sphere poses do: only when the
  // frame's lights differ from the last frame's.
  if (pc->world) relight_->setLights(pc->world->lights, *relightScene_);
  // With kRelightCpuReaders (off, relight.hpp) the CPU readers of the volume (incident::ProbeSource:
  // DNRT's c_j, SL's pass 1, RTF's proxies) get baked + the ΔSH this frame slot computed last time
  // round (FrameRing::begin has waited for it).
  int slot = kRelightCpuReaders && pc->frames ? int(pc->frames->current().slot) : -1;
  std::vector<glm::vec3> delta;
  if (slot >= 0 && relight_->readDelta(std::uint32_t(slot), delta)) {
    const std::size_t coeffs = std::size_t(volume_.coeffs());
    for (std::size_t p = 0; p < volume_.grid.probeCount(); ++p)
      for (std::size_t i = 0; i < coeffs; ++i) volume_.sh[p * coeffs + i] = relightBaked_[p * coeffs + i] + delta[p * 9 + i];
  }
  // The "probes.sh" image has readers this frame when the probes pass reads it (the volume does not
  // fit the block) or an SL pass may shadow the probes' light with it (sl.shadow, fused sl: the
  // Services::probeSh readers); otherwise the texels and their copy are skipped.
  const bool slReads = pc->world && pc->world->has("sl");
  const bool imageRead = !shInUbo_ || slReads;
  // The block (and with it the image) as a graph buffer that the probes' own passes read
  // (probes.tiles, probes): this pass follows its readers, culled with them (a debug view that culls
  // `probes`). The SL passes read the image outside the graph, so with SL it stays a side effect.
  // graphDot builds the graph without a device: any id names the import there, one apart from the
  // other placeholders (Renderer::graphDot's 1–3, the AO node's 1000).
  constexpr rg::PhysicalId kGraphDotBlock = 1001;
  const rg::PhysicalId physical = pc->backend ? pc->backend->importBuffer(shUbo_) : kGraphDotBlock;
  const auto block = graph.importBuffer("probes.sh.block", rg::BufferDesc{shUbo_.size()}, rg::ResourceState{}, physical);
  const auto& relit = graph.addPass<Data>(
      "probes.relight",
      [&](rg::Builder& b, Data& d) {
        if (auto atlas = bb.find<rg::Texture>("shadow.atlas")) d.atlas = b.read(*atlas, rg::Usage::SampledCompute);
        d.block = b.write(block, rg::Usage::StorageWrite);
        if (slReads) b.sideEffect();  // its image has readers outside the graph
      },
      [this, pc, slot, imageRead](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
        VkCommandBuffer cmd = pc->cmd(c);
        VkSampler compare = pc->samplers->get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST,
                                               VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, 1.0f, true});
        gpu::Image& atlas = d.atlas ? pc->backend->image(res.texture(*d.atlas)) : *pc->dummyShadowAtlas;
        relight_->record(cmd, *pc->frame().descriptors, *pc->lights, pc->lightCount, *pc->shadowMatrices,
                         pc->frameView(atlas, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, atlas.desc().layers), compare,
                         d.atlas.has_value(), kRelightIterationsPerFrame, true, slot, imageRead);
      });
  return relit.block;
}

}  // namespace bounce::gi::probes
