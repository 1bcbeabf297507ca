#pragma once
// The GPU pass `probes.relight` (shaders/probes/relight.comp; what it computes: relight.hpp): per
// frame, kRelightIterationsPerFrame × (surfel ΔE, probe gather), then baked + ΔSH packed into the
// probes pass's uniform block (node.cpp shPackedWords' format; that buffer carries STORAGE usage)
// when the pass reads it, and written as the "probes.sh" image's fp32 texels (copied into the image:
// the probes pass's source past 2016 probes, and the SL shadow's always; session 10) on the frames
// something reads the image (ProbeNode::addRelightPass). ΔSH persists between frames (the room's
// bounce continues over frames).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/gi/probes/probe_volume.hpp"
#include "engine/gi/probes/relight.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/render/gpu_types.hpp"

namespace bounce::gi::probes {

class RelightPass {
 public:
  // `packed`: the probes pass's ProbeShBlock buffer (STORAGE usage), its valid bits already in it;
  // written only when `block` (the volume fits it: the probes pass reads it). `image` (optional): the
  // volume's "probes.sh" image (uploadSh; TRANSFER_DST usage, SHADER_READ_ONLY between passes),
  // rewritten each frame with baked + ΔSH in fp32: what probes.frag reads when the volume does not
  // fit the block, and what the SL shadow on the probes' light reads (probe_sh.glsl).
  RelightPass(gpu::Context& ctx, const ProbeVolume& volume, RelightData data, const gpu::Buffer& packed,
              gpu::Image* image = nullptr, bool block = true);

  // V_static for these lights (CPU, Embree through the static scene), recomputed only when the
  // lights differ from the last call's. At most render::kMaxLights.
  void setLights(std::span<const render::LightGpu> lights, const ref::SceneBvh& staticScene);
  // Tests: V_now per (surfel, light) from this buffer instead of the shadow atlas (empty: atlas).
  void setTestVisibility(std::span<const float> vNow);
  // Records the frame's dispatches with a descriptor set from `descriptors` (the frame's allocator).
  // `lights`/`lightCount`/`shadowMatrices`: the lighting pass's blocks; `atlas` a 2D-array view of
  // the shadow atlas (or a dummy with shadowsOn false). `writeImage` false: nothing reads the image
  // this frame, so the pack stage writes no texels and the image is not copied (it keeps what it last
  // held); the block is written as always.
  void record(VkCommandBuffer cmd, gpu::DescriptorAllocator& descriptors, const gpu::Buffer& lights,
              std::uint32_t lightCount, const gpu::Buffer& shadowMatrices, VkImageView atlas, VkSampler compare,
              bool shadowsOn, int iterations = kRelightIterationsPerFrame, bool pack = true, int readbackSlot = -1,
              bool writeImage = true);
  // The ΔSH that the last record() with this readbackSlot copied out (probes × 9, order-3 layout), for
  // the CPU readers of the probes: false when that slot has not been recorded yet. Call only once
  // the slot's frame has finished (FrameRing::begin waited for it): no stall, a frames-in-flight lag.
  bool readDelta(std::uint32_t slot, std::vector<glm::vec3>& out) const;
  // Zero ΔSH (the next frame restarts the series).
  void reset();
  // Level `"probes": {"sl_bounce": true}`: the surfel stage adds slBounce() (E_SL per surfel, vec4
  // rgb, W/m²) to ΔE, so the room's iterations carry the SLs' bounce on. The SL node writes it
  // (pass "sl.relight_bounce", after "sl.intensity"); the effects run probes before sl, so this
  // frame's relight reads the E_SL of the previous frame's poses and intensities (one frame late;
  // ΔSH itself converges over frames). The buffer starts at 0.
  void setSlBounce(bool on) { push_.outputs.z = on ? 1u : 0u; }
  bool slBounceOn() const { return push_.outputs.z != 0u; }
  const gpu::Buffer& slBounce() const { return slBounce_; }
  gpu::Buffer& slBounce() { return slBounce_; }  // tests upload E_SL into it
  const gpu::Buffer& surfelBuffer() const { return surfels_; }  // relight.comp's Surfel: 3 vec4 each
  std::uint32_t surfelCount() const { return std::uint32_t(data_.surfels.size()); }

  const RelightData& data() const { return data_; }
  const gpu::Buffer& delta() const { return delta_; }                  // probe·9 + i: vec4 (rgb)
  const gpu::Buffer& surfelRadiance() const { return radiance_; }      // surfel: vec4 (rgb ΔL)
  std::uint32_t lightsSet() const { return lightCount_; }

 private:
  struct Push {
    glm::vec4 originSpacing;
    glm::ivec4 countOrder;
    glm::vec4 params;
    glm::uvec4 sizes;
    glm::uvec4 flags;
    glm::uvec4 outputs;  // relight.comp pc.outputs: x: write the block, y: the image's texels
  };
  gpu::Context& ctx_;
  RelightData data_;
  const gpu::Buffer& packed_;
  gpu::Image* image_ = nullptr;
  gpu::Buffer texels_;  // the image's texels, probe-major (node.cpp shTexelFloats), copied into image_
  Push push_{};
  std::vector<render::LightGpu> lights_;
  std::uint32_t lightCount_ = 0;
  bool testVis_ = false;
  std::vector<gpu::Buffer> readback_;  // per frame slot: ΔSH copied after the pack stage
  std::vector<bool> readbackWritten_;
  gpu::Buffer surfels_, rays_, vStatic_, radiance_, delta_, baked_, valid_, moments_, vTest_, slBounce_;
  gpu::DescriptorSetLayout setLayout_;
  gpu::PipelineLayout layout_;
  gpu::Pipeline pipeline_;
};

}  // namespace bounce::gi::probes
