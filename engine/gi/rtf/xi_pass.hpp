#pragma once
// One object's RTF on the GPU: the bouncing step's caches (Eq. 11–12, shaders/rtf/xi.glsl, compiled as xi.comp and
// xi_subgroup.comp): one object's CPCA field
// uploaded once, the proxies' light each frame, the shading step's X into an 8-bit 3D image (net()) and, when
// asked (XiPassOptions::keepXi), ξ into an rgba32f 2D-array image (layer sphere·16 + i, texel (face·n_r + x,
// y)). The CPU reference is xiCache() (evaluate.hpp); tests/unit/rtf/xi_gpu_test.cpp compares the two.
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/rtf/field.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"

namespace bounce::gi::rtf {

struct XiPassOptions {
  // Stage 1 also stores ξ in xi(). Only tests read ξ (the shading step reads X), so frames skip the 16
  // rgba32f stores a sample; without it xi() throws.
  bool keepXi = false;
  // Each slot's range is reduced over the subgroup before its atomicMax (xi_subgroup.comp), where the
  // device's compute stage has subgroup arithmetic; false, or without it: xi.comp, one atomicMax a lane (same ranges).
  bool subgroupMax = true;
};

// Whether the device's compute stage has subgroup arithmetic (Vulkan 1.1 subgroup properties).
bool computeSubgroupArithmetic(const gpu::Context& ctx);

class XiPass {
 public:
  XiPass(gpu::Context& ctx, const Field& field, XiPassOptions options = {});
  // The proxies' incident light, m·16 RGB in the object's frame: record() writes it into the
  // command buffer (vkCmdUpdateBuffer), so it takes effect at the next record().
  void setProxyLight(std::span<const glm::vec3> light);
  // The three dispatches with the barriers they need; ξ is in GENERAL layout from construction on (no
  // layout change is recorded here), its writes made visible to later compute and fragment reads.
  void record(VkCommandBuffer cmd);
  // The shading step's blocked light folded per sample (xi.comp: X_i = Â_l/π ξ_i − Σ_j T'_ij (u − V)_j):
  // T'_ij = blocked[j·9 + i].rgb (update.hpp RtfObjectGpu::blocked), 144 entries; zero until set.
  // Written with the light by the next record().
  void setBlockedLight(std::span<const glm::vec4> blocked);
  // Per sample (field.hpp's order), rgb: the factor of the blocked light at that sample — the
  // session passes overlap.hpp sharedOcclusion's scale (the occlusion other objects' terms already
  // take off); update.hpp blockedScale (the light's level there) also fits; w: the factor of the
  // interreflected light ξ for receivers off the rtf objects (w_off: the share the nearer objects let
  // through). `onObjects`: the same factor for receivers on an rtf object's surface (w_on), the second
  // variant of X (net()). Empty scale: 1 everywhere (the light at o, ξ whole); empty onObjects: scale's w,
  // so both variants are the same. Written by the next record().
  void setBlockedScale(std::span<const glm::vec4> scale, std::span<const float> onObjects = {});
  // X for i < 9 in 8 bits (xi.comp): RGBA8 UNORM 3D, texel (face·n_r + x, y, (v·kNetTexels + k)·spheres + sphere)
  // for variant v < kNetVariants and texel k < kNetTexels in DNRT's Table 2 order; slot k·4 + c holds t = Y/(2m) + ½ of Y = r_s² X
  // (netScale: X weighted by its sphere's squared radius) with m = netRange()'s slot (float max |Y| this
  // frame), so X = m(2t − 1)/r_s². GENERAL layout from construction on.
  // Two variants of X (overlap.hpp): slices [0, kNetTexels·spheres) hold X off the rtf objects' surfaces
  // (w_off), the next kNetTexels·spheres X on them (w_on); each slot's m is shared by both.
  static constexpr std::uint32_t kNetTexels = 7, kNetVariants = 2;
  // Why r_s²: what X carries (the light an object sends to q and the light it hides there) falls as the
  // object's solid angle, ~1/|q|² (evaluate.hpp radialWeight), so one range per slot over X itself spent
  // the 8 bits on the innermost spheres: a sample on sphere s got m/255 steps of an X ≈ (r_1/r_s)² of m,
  // and the second bounce (≈ 1 % of X on cornell-5) was below a step on the middle and outer spheres
  // (README "RTF's second bounce in 8 bits, session 20"). Y ≈ flat across the spheres instead. The
  // lookup stays one trilinear fetch and exact: between spheres a < b Eq. 10's weight w (linear in 1/|q|²)
  // gives (1 − w) Y_a/r_a² + w Y_b/r_b² = ((1 − w') Y_a + w' Y_b)/|q|² with w' = (|q|² − r_a²)/(r_b² − r_a²),
  // since (1 − w)/r_a² + w/r_b² = 1/|q|² (rtf.frag); inside the innermost sphere Y_0/r_0², beyond the
  // outermost Y_N/|q|² times the end's ramp (= tailFade · X_N). Radii in η.
  static float netScale(const FieldSettings& s, int sphere) {
    const float r = sphereRadius(s, sphere);
    return r * r;
  }
  // The slot (texel k · 4 + component) of channel c's X_i, i < 9 (xi.comp rtfNetSlot).
  static constexpr int netSlot(int c, int i) { return i < 8 ? ((i / 4) * 3 + c) * 4 + i % 4 : 24 + c; }
  gpu::Image& net() { return net_; }
  // 28 floats (vec4[7]): each slot's m; the shading pass binds it as a uniform block.
  gpu::Buffer& netRange() { return range_; }
  gpu::Image& xi();  // needs XiPassOptions::keepXi
  // The object occlusion field, uploaded once: rgba32f 2D array, layer sphere·4 + i/4, texel
  // (face·n_r + x, y), component i%4 (shaders/rtf/rtf.glsl), SHADER_READ_ONLY_OPTIMAL.
  gpu::Image& oof() { return oof_; }

 private:
  struct Push {
    std::uint32_t stage, proxies, clusters, components, samples, faceSize, byteComponents;
    float innerRadius, outerRadius;  // η: the spheres' radii (field.hpp sphereRadius; netScale)
  };
  FieldSettings settings_;
  bool keepXi_ = false;
  Push push_{};
  gpu::Buffer basis_, alpha_, cluster_, light_, eigen_, basisCodes_, alphaCodes_, codeScales_;
  std::vector<glm::vec4> pending_;  // the light record() writes: m·16 proxy light, then 144 of T'
  std::vector<glm::vec4> blocked_;
  std::vector<glm::vec4> scale_;  // N, or empty: ones
  std::vector<float> onObjects_;  // N, or empty: scale_'s w
  bool scaleIsOnes_ = true;       // what the GPU buffer holds now
  bool onObjectsAreOnes_ = true;  // what the on-objects buffer holds now: ones (as at construction)
  gpu::Buffer scaleBuffer_, onObjectsBuffer_;
  gpu::Image xi_, oof_, net_;
  gpu::Buffer oofBuffer_;  // the OOF again as floats, for xi.comp's X
  gpu::Buffer range_, netValue_;  // X's per-slot range and X itself before the encoding
  gpu::DescriptorSetLayout setLayout_;
  gpu::PipelineLayout layout_;
  gpu::Pipeline pipeline_;
  gpu::DescriptorAllocator descriptors_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace bounce::gi::rtf
