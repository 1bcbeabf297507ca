#pragma once
// SL pass 2's device data (shaders/sl/sl_data.glsl declares it, sl.glsl reads it): the
// scene-independent tables as one rgba32f texture read with texelFetch (the blocker log ZH and
// Eq. 16's weight ZH by angular radius, the optimal-linear (a, b) by ‖f̂‖) and this frame's SLs as
// a uniform block (DESIGN.md: no SSBOs in llvmpipe fragment shaders). Pass 1's intensity buffer
// (IntensityPass::intensity()) is the third resource. The hybrid exp's squarings use the Gaunt
// tensor as generated code (shaders/sl/gaunt.glsl), not a buffer: unrolled, g stays in registers. Order, blocking and the
// per-receiver array size are specialization constants of the pipelines that read it
// (specialization() below).
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/incident/incident.hpp"
#include "engine/gi/sl/evaluate.hpp"
#include "engine/gi/sl/intensity_words.hpp"
#include "engine/gi/sl/update.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"

namespace bounce::gi::sl {

// sl_data.glsl's capacity: the SLs one pass shades (the spheres block is 128·4 vec4 and more, the
// intensity block 128 · 24 words = 12 KiB, both within the smallest maxUniformBufferRange Vulkan allows).
inline constexpr std::uint32_t kMaxShadedSpheres = 128;
// Bytes of the intensity uniform block (fp16 pairs, intensity_words.hpp): IntensityPass allocates at
// least this.
inline constexpr std::size_t kIntensityBlockBytes = std::size_t(kMaxShadedSpheres) * kIntensityWordsPerSl * 4;
// sl_data.glsl's SlIndirect block ("blocked_light": "sphere") holds one of two layouts, sized per
// layout (the shaders size it by the same rule, from their kBlockedMap and kSpheres constants):
// "blocked_read": "sh": 16 words (27 fp16) per SL, kShIndirectBlockBytes = 8 KiB for 128 SLs.
// "map": each SL's blended 16² direction map, one word a texel, RGB9E5 (glm::packF3x9_E1x5: 9-bit
// mantissas under a shared 5-bit exponent, each channel within 2^-9 of the brightest one's value, ≥ 0),
// 1 KiB per SL for specSpheres(N) SLs (N rounded up to 8, as pass 2's kSpheres), at most
// kMaxMappedSpheres: 64 KiB, lavapipe's maxUniformBufferRange (fp16 RGB would hold 42 SLs there; the
// accuracy rows' 2 × 32 need 64). technique.cpp refuses a level with more, and reads the SH instead
// (one warning) where the device's maxUniformBufferRange is below the map block (Vulkan guarantees 16
// KiB: 16 SLs).
inline constexpr std::size_t kIndirectWordsPerSl = 16;
inline constexpr std::uint32_t kMaxMappedSpheres = 64;
inline constexpr std::size_t kMapWordsPerSl = std::size_t(math::kOctMapTexels);
inline constexpr std::size_t kShIndirectBlockBytes = std::size_t(kMaxShadedSpheres) * kIndirectWordsPerSl * 4;
// Pass 2's per-receiver array size for `spheres` SLs (sl.glsl kSpheres, constant id 2): rounded up to
// a multiple of 8, at least 8.
constexpr std::uint32_t specSpheres(std::uint32_t spheres) { return std::max<std::uint32_t>(8, (spheres + 7) / 8 * 8); }
// Bytes of the SlIndirect block: the SH layout (`mappedSpheres` 0), or the maps of that many SLs.
constexpr std::size_t indirectBlockBytes(std::uint32_t mappedSpheres) {
  return mappedSpheres == 0 ? kShIndirectBlockBytes : std::size_t(specSpheres(mappedSpheres)) * kMapWordsPerSl * 4;
}
// Whether "blocked_read": "map" for `spheres` SLs fits a device's maxUniformBufferRange (bytes); if not
// the level reads the SH (technique.cpp warns once at load).
constexpr bool mapsFitUniformRange(std::uint32_t spheres, std::uint64_t maxUniformBufferRange) {
  return spheres <= kMaxMappedSpheres && indirectBlockBytes(spheres) <= maxUniformBufferRange;
}

// One SL as pass 2 reads it.
struct ShadedSphere {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
  glm::mat3 rotation{1.0f};  // SL local → world
  std::uint32_t object = 0;  // SLs of one object may intersect (baked occlusion)
  float share = 1.0f;        // its object's union share u_o (probe_shadow.hpp; "sl.shadow", "sl.local")
  float silhouette = 1.0f;   // its set's shadow scale (SlSphere::shadowScale; "sl.shadow", "sl.local")
};

class ShadeData {
 public:
  // `mappedSpheres` 0: SlIndirect holds the SH layout (8 KiB); N > 0 ("blocked_read": "map"): the
  // maps of up to N SLs (indirectBlockBytes(N)).
  ShadeData(gpu::Context& ctx, int order, std::uint32_t mappedSpheres = 0);
  int order() const { return order_; }
  // This frame's SLs (host-visible: read at the next submitted use). At most kMaxShadedSpheres.
  // `parents` (§7.3 hierarchy, sl/hierarchy.glsl): object o's parent SL at index count() + o (header.z
  // = their count), world frame; they take no part in the means or overlap masks.
  // `indirect` (empty, or one per sphere): the probes' radiance SH at each SL's posed centre, for
  // sl_data.glsl's SlIndirect ("blocked_light": "sphere"), packed to fp16; empty leaves zeros.
  // `maps` (empty, or one per sphere, at most the constructor's mappedSpheres; "blocked_read": "map"):
  // the blended direction maps at the SLs' posed centres, written to SlIndirect in place of `indirect`.
  void setSpheres(std::span<const ShadedSphere> spheres, std::span<const PosedSphere> parents = {},
                  std::span<const incident::RadianceSH> indirect = {}, std::span<const incident::DirectionMap> maps = {});
  std::uint32_t count() const { return count_; }
  // Writes the three sl_data.glsl bindings first … first + 2 (intensity: pass 1's buffer, ≥
  // kIntensityBlockBytes).
  void write(gpu::DescriptorWriter& w, std::uint32_t first, const gpu::Buffer& intensity, VkSampler nearest) const;
  // The bindings' types, for a set layout.
  static std::vector<gpu::Binding> bindings(std::uint32_t first);
  // sl_data.glsl's SlIndirect block (SL_INDIRECT_BINDING) at `binding`.
  void writeIndirect(gpu::DescriptorWriter& w, std::uint32_t binding) const;
  // The SlIndirect block's bytes (indirectBlockBytes(mappedSpheres)): its buffer and descriptor range.
  std::size_t indirectBytes() const { return indirectBytes_; }
  // Constant ids 0–3 of sl.glsl's includers: kOrder, kPerObject, kSpheres (the per-receiver
  // arrays' size: the SL count rounded up to a multiple of 8, at least 8), kInfluence (F, 0: off).
  static gpu::SpecConstants specialization(int order, Blocking blocking, std::uint32_t spheres, float influence = 0.0f);

 private:
  int order_ = 4;
  std::uint32_t count_ = 0;
  std::uint32_t mappedSpheres_ = 0;
  std::size_t indirectBytes_ = kShIndirectBlockBytes;
  gpu::Image tables_;
  gpu::Buffer spheres_;
  gpu::Buffer indirect_;
};

}  // namespace bounce::gi::sl
