#pragma once
// SL pass 1 (paper §5.1): the light intensity SH vector L^c of every SL this frame — on the GPU
// (IntensityPass, shaders/sl/intensity.comp) and its C++ reference (sampleReflection below, then
// evaluate.hpp's intensityFromSamples: Eq. 10–11). tests/unit/sl/intensity_gpu_test.cpp checks one
// against the other.
//
// Per surface sample point p_j (baked in the mesh's local frame, sphere_set.hpp):
//   world position  p = c' + R · (p_local − c) · (r' / r)     (c, r the baked SL, c', r', R its pose:
//   world normal    n = normalize(R · n_local)                  update.hpp, §7.1)
//   L_pj = max(0, E(n)) / π   (Eq. 3 with ρ_n the white Lambertian BRDF — the albedo enters at
//                              Eq. 11 — so W/(m²·sr) per channel)
// Eq. 11's c_S is multiplied by the set's bounce scale (SlSphere::bounceScale, bounce_scale.hpp:
// the spheres are fatter than the mesh and their overlaps add, measured 2–4× the mesh's light).
// with E(n) the irradiance from the order-3 radiance SH of the light arriving at p: the level's real
// lights through incident.glsl (radius 0: a point receiver) each times its visibility, plus the
// probes' indirect light blocked by the SLs (§5.1: "SLs act as blockers and environment lighting as
// light source", Eq. 3 and 6): E += ΔE of probe_shadow.hpp (sl::probeShadow, the same function pass
// 2's sl.shadow evaluates, same exp, tables, receiver rules, union share and shadow scale), over
// every SL of the frame; the receiver rules shrink or cull the sample's own SL and the neighbours
// that contain it, so what blocks is the rest of its object and the other objects. The real lights
// need no spheres: their shadow maps hold every object's real mesh.
// DEPARTURES: (1) the probes are sampled once per SL, at its posed centre, on the CPU (an SL is
// small next to the probe spacing, and 64 lookups a frame are cheaper than one per sample on the
// device; measured: moving that point by ±1 radius changes the characters level's indirect-only
// error by ≤ 0.004, README "SL accuracy"); (2) visibility is the lighting pass's shadow-map lookup (shadow.glsl),
// so an SL's own object shadows its back-facing samples as the renderer shades them; the C++
// reference has no shadow map and takes every light as visible (the GPU test runs unshadowed).
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/incident/incident.hpp"
#include "engine/gi/sl/probe_shadow.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/gi/sl/sphere_set.hpp"
#include "engine/gi/sl/update.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/render/gpu_types.hpp"

namespace bounce::gi::sl {

// The sample's world position and normal under the SL's pose (the header's formulas).
struct WorldSample {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};
};
WorldSample worldSample(const SurfaceSample& sample, const SlSphere& rest, const PosedSphere& posed);

// The SLs that block the indirect light at the samples (the header), and probeShadow's settings.
// Empty `lights`: nothing blocks.
struct SampleBlockers {
  std::span<const Light> lights;  // world spheres and object ids (intensity unused)
  ShadowSettings settings;
  // §7.3 local lights ("sl": {"local_lights": true}): the same SLs also block the point and spot
  // lights at the samples, by sl::localLightVisibility (Cap form, each sphere's object share and
  // shadow scale from `settings`) — their shadow maps no longer hold the SL objects.
  bool localLights = false;
};

// L_pj (the header), every light unoccluded: the C++ reference of intensity.comp's steps 1–2.
glm::vec3 sampleReflection(const SurfaceSample& sample, const SlSphere& rest, const PosedSphere& posed,
                           std::span<const render::LightGpu> lights, const incident::RadianceSH& indirect,
                           const SampleBlockers& blockers = {});

// The whole pass 1 of one SL in C++ (double sums): sampleReflection per sample, then Eq. 10–11
// (intensityFromSamples). Returns order² RGB coefficients in the SL's local frame.
std::vector<glm::dvec3> intensityReference(const SlSphere& rest, int order, const PosedSphere& posed,
                                           std::span<const render::LightGpu> lights,
                                           const incident::RadianceSH& indirect, const SampleBlockers& blockers = {});

// Pass 1 on the device for every SL of every participating set (concatenated in the order given;
// SL index = running index over the sets' spheres). The samples, albedo SH and Gaunt tensor are
// uploaded once; setSpheres() writes the poses and indirect light, setLights()/bindLights() the lights (read at the
// next record()). The result stays in intensity(): kIntensityWordsPerSl fp16-pair words per SL
// (intensity_words.hpp: L^c_k in the SL's local frame), usable as a storage or uniform buffer by pass 2.
class IntensityPass {
 public:
  // `order` (3 or 4) is the result's; sets baked at order 3 take part in an order-4 pass with their
  // band-3 basis sums and albedo zero. Throws InternalError for a set of a higher order or more SLs
  // than pass 2's blocks hold (kMaxShadedSpheres). `influence`: evaluate.hpp rule 0's F for the
  // blockers (pass 2's, 0: off). `parents` (§7.3 hierarchy, hierarchy.hpp): one parent SL per set
  // (object o = set o) after the children — its sphere from setSpheres (update.hpp parentSpheres),
  // its intensity at SL index sphereCount() + o of intensity(), formed by a second dispatch at the
  // end of record() (shaders/sl/parent_intensity.comp: hierarchy.hpp parentOf's sum on the device).
  IntensityPass(gpu::Context& ctx, std::span<const SphereSet* const> sets, int order, float influence = 0.0f,
                bool parents = false);
  std::uint32_t sphereCount() const { return spheres_; }
  // The parents (one per set with `parents`, else none) as setSpheres posed them: world frame.
  std::span<const PosedSphere> parents() const { return parentPosed_; }
  int order() const { return order_; }
  // posed[i], indirect[i]: SL i's pose and the probes' radiance SH at its posed centre (host-visible:
  // read at the next record()).
  void setSpheres(std::span<const PosedSphere> posed, std::span<const incident::RadianceSH> indirect);
  // The lights and their shadow matrices from the CPU, into the pass's own uniform buffers (tests;
  // ≤ render::kMaxLights, ≤ kMaxShadowLayers).
  void setLights(std::span<const render::LightGpu> lights, std::span<const glm::mat4> shadowMatrices);
  // Or the renderer's: its light and shadow-matrix uniform buffers (render::PassContext), `count`
  // lights. Rewrites the set: not while a recorded pass that reads it is in flight.
  void bindLights(const gpu::Buffer& lights, std::uint32_t count, const gpu::Buffer& shadowMatrices);
  // The shadow atlas (a 2D-array depth image, read with a compare sampler) in `layout`; with
  // shadowsOn = false every light is unoccluded (the atlas is still bound: a dummy will do). Same
  // rule as bindLights.
  void setShadowAtlas(VkImageView atlas, VkSampler compareSampler, VkImageLayout layout, bool shadowsOn);
  // The SLs that block the indirect light at the samples (the header): pass 2's data for this frame
  // (ShadeData, same SL order as setSpheres) and a nearest sampler for its tables. Without a call,
  // or with on = false, nothing blocks. Same rule as bindLights.
  void setBlockers(const ShadeData& blockers, VkSampler nearest, bool on = true, bool localLights = false);
  // One dispatch (a workgroup per SL), with `parents` a second (a workgroup per object), and a barrier making intensity() visible to later compute
  // and fragment shader reads.
  void record(VkCommandBuffer cmd);
  const gpu::Buffer& intensity() const { return intensity_; }

 private:
  struct Push {
    std::uint32_t lightCount = 0, shadowsOn = 0, gaunts = 0, blockers = 0;
  };
  gpu::Context& ctx_;
  int order_ = 4;
  std::uint32_t spheres_ = 0;
  std::vector<glm::vec4> rest_;                                // per SL: local centre, radius
  std::vector<std::pair<std::uint32_t, std::uint32_t>> range_;  // per SL: first sample, count
  Push push_{};
  gpu::Buffer samples_, spheresBuf_, albedo_, gaunt_, lights_, shadowMatrices_, intensity_;
  gpu::DescriptorSetLayout setLayout_;
  gpu::PipelineLayout layout_;
  gpu::Pipeline pipeline_;
  gpu::DescriptorAllocator descriptors_;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  bool atlasBound_ = false;
  gpu::Buffer unreadIntensity_;  // sl_data.glsl's intensity block (not read by pass 1: no aliasing of intensity_)
  gpu::SamplerCache samplers_;
  std::unique_ptr<ShadeData> noBlockers_;
  // §7.3 parents (empty without `parents`): per set its SLs' first index and count; the posed
  // parents; parent_intensity.comp's inputs (host-visible, written by setSpheres) and pipeline.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> setRange_;
  std::vector<PosedSphere> parentPosed_;
  gpu::Buffer parentObjects_, parentChildren_;
  gpu::DescriptorSetLayout parentSetLayout_;
  gpu::PipelineLayout parentLayout_;
  gpu::Pipeline parentPipeline_;
  VkDescriptorSet parentSet_ = VK_NULL_HANDLE;  // bound until setBlockers (lavapipe: no unwritten descriptors)
};

}  // namespace bounce::gi::sl
