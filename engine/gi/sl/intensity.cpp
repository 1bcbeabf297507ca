#include "engine/gi/sl/intensity.hpp"

#include <algorithm>
#include <cstring>

#include "engine/core/error.hpp"
#include "engine/gi/placement.hpp"
#include "engine/gi/sl/evaluate.hpp"
#include "engine/gi/sl/local_light.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"
#include "engine/math/sh_product.hpp"
#include "engine/math/sh_rotate.hpp"

namespace bounce::gi::sl {

namespace {
// parent_intensity.comp's floats per child: (r_j / r_P)², then bands 1–3 of its SH rotation (9 + 25 + 49).
constexpr std::size_t kParentChildFloats = 84;
}  // namespace

WorldSample worldSample(const SurfaceSample& sample, const SlSphere& rest, const PosedSphere& posed) {
  const float scale = rest.radius > 0.0f ? posed.radius / rest.radius : 1.0f;
  return {posed.centre + posed.rotation * ((sample.position - rest.centre) * scale),
          glm::normalize(posed.rotation * sample.normal)};
}

glm::vec3 sampleReflection(const SurfaceSample& sample, const SlSphere& rest, const PosedSphere& posed,
                           std::span<const render::LightGpu> lights, const incident::RadianceSH& indirect,
                           const SampleBlockers& blockers) {
  const WorldSample w = worldSample(sample, rest, posed);
  incident::RadianceSH sh = indirect;
  std::vector<Sphere> spheres;
  std::vector<double> share, scale;
  if (blockers.localLights)
    for (const Light& l : blockers.lights) {
      const auto object = std::size_t(l.object);
      spheres.push_back(l.sphere);
      share.push_back(object < blockers.settings.objectShare.size() ? blockers.settings.objectShare[object] : 1.0);
      scale.push_back(object < blockers.settings.objectSilhouette.size() ? blockers.settings.objectSilhouette[object] : 1.0);
    }
  for (const render::LightGpu& light : lights) {
    float v = 1.0f;
    if (blockers.localLights && std::uint32_t(light.positionType.w + 0.5f) != std::uint32_t(render::LightType::Directional))
      v = float(localLightVisibility(spheres, {glm::dvec3(glm::vec3(light.positionType)), double(light.radiance.w)},
                                     glm::dvec3(w.position), glm::dvec3(w.normal), blockers.settings.order,
                                     blockers.settings.influence, LocalForm::Cap, blockers.settings.log, share, scale));
    incident::addLight(light, w.position, 0.0f, v, sh);
  }
  const incident::RadianceSH e = incident::irradianceSH(sh);
  // E(n) = Σ c_j Y_j(n) (irradianceSH's convention), then Eq. 3's white Lambertian: / π.
  glm::vec3 E = sh::evalSum<glm::vec3, float>(std::span<const glm::vec3>(e), w.normal);
  if (!blockers.lights.empty()) {  // §5.1: the indirect light blocked by the SLs (probe_shadow.hpp's ΔE ≤ 0)
    std::vector<glm::dvec3> radiance(indirect.begin(), indirect.end());
    E += glm::vec3(probeShadow(blockers.lights, glm::dvec3(w.position), glm::dvec3(w.normal), radiance, blockers.settings).delta);
  }
  return glm::max(E, glm::vec3(0.0f)) / float(math::kPi);
}

std::vector<glm::dvec3> intensityReference(const SlSphere& rest, int order, const PosedSphere& posed,
                                           std::span<const render::LightGpu> lights,
                                           const incident::RadianceSH& indirect, const SampleBlockers& blockers) {
  std::vector<glm::dvec3> radiance;
  std::vector<std::vector<float>> basis;
  for (const SurfaceSample& s : rest.samples) {
    radiance.push_back(glm::dvec3(sampleReflection(s, rest, posed, lights, indirect, blockers)));
    basis.push_back(s.basis);
  }
  // Eq. 11 with the set's bounce scale folded into c_S (bounce_scale.hpp), as IntensityPass uploads it.
  std::vector<float> albedo = rest.albedo;
  for (float& a : albedo) a *= rest.bounceScale;
  return intensityFromSamples(radiance, basis, albedo, order);
}

namespace {

// std430 mirrors of intensity.comp's structs (byte sizes in the shader's header).
struct SampleGpu {
  glm::vec4 position, normal;
  float basis[16];
};
struct SphereGpu {
  glm::vec4 rest, posed;
  glm::vec4 rotation[3];
  std::uint32_t range[4];
  glm::vec4 indirect[9];
};
struct GauntGpu {
  std::uint32_t i, j, k;
  float value;
};
static_assert(sizeof(SampleGpu) == 96 && sizeof(SphereGpu) == 240 && sizeof(GauntGpu) == 16);

template <class T>
gpu::Buffer deviceBuffer(gpu::Context& ctx, const std::vector<T>& data, VkBufferUsageFlags usage, const std::string& name) {
  const std::size_t bytes = std::max<std::size_t>(data.size() * sizeof(T), 16);  // never a 0-byte buffer
  gpu::Buffer b(ctx, {bytes, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUsage::GpuOnly, name});
  if (!data.empty())
    gpu::upload(ctx, b, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(data.data()), data.size() * sizeof(T)));
  return b;
}

}  // namespace

namespace {
constexpr std::uint32_t kBlockerBinding = 8;  // intensity.comp's SL_BINDING
std::vector<gpu::Binding> passBindings() {
  std::vector<gpu::Binding> b = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},        {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                 {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},        {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                 {4, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},        {5, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
                                 {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}, {7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
  for (const gpu::Binding& x : ShadeData::bindings(kBlockerBinding)) b.push_back(x);
  return b;
}
}  // namespace

IntensityPass::IntensityPass(gpu::Context& ctx, std::span<const SphereSet* const> sets, int order, float influence,
                             bool parents)
    : ctx_(ctx),
      order_(order),
      setLayout_(ctx, passBindings(), "sl.intensity"),
      layout_(ctx, {setLayout_}, {{VK_SHADER_STAGE_ALL, 0, sizeof(Push)}}, "sl.intensity"),
      descriptors_(ctx, "sl.intensity"),
      samplers_(ctx) {
  if (order != 3 && order != 4) throw InternalError("sl::IntensityPass: order must be 3 or 4");
  const std::size_t nc = std::size_t(order) * std::size_t(order);
  std::vector<SampleGpu> samples;
  std::vector<glm::vec4> albedo;
  for (const SphereSet* set : sets) {
    if (set->settings.order > order) throw InternalError("sl::IntensityPass: a sphere set of a higher SH order");
    if (parents) setRange_.emplace_back(std::uint32_t(rest_.size()), std::uint32_t(set->spheres.size()));
    for (const SlSphere& s : set->spheres) {
      rest_.emplace_back(s.centre, s.radius);
      range_.emplace_back(std::uint32_t(samples.size()), std::uint32_t(s.samples.size()));
      for (const SurfaceSample& x : s.samples) {
        SampleGpu g{glm::vec4(x.position, 1.0f), glm::vec4(x.normal, 0.0f), {}};
        for (std::size_t k = 0; k < nc && k < x.basis.size(); ++k) g.basis[k] = x.basis[k];
        samples.push_back(g);
      }
      for (std::size_t k = 0; k < 16; ++k)
        albedo.push_back(k < nc && k * 3 + 2 < s.albedo.size()
                             ? s.bounceScale * glm::vec4(s.albedo[k * 3], s.albedo[k * 3 + 1], s.albedo[k * 3 + 2], 0.0f)
                             : glm::vec4(0.0f));
    }
  }
  spheres_ = std::uint32_t(rest_.size());
  std::vector<GauntGpu> gaunt;
  for (const sh::GauntEntry& e : sh::gauntTensor()) gaunt.push_back({e.i, e.j, e.k, float(e.value)});
  push_.gaunts = std::uint32_t(gaunt.size());

  samples_ = deviceBuffer(ctx, samples, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "sl.samples");
  albedo_ = deviceBuffer(ctx, albedo, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "sl.albedo");
  gaunt_ = deviceBuffer(ctx, gaunt, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "sl.gaunt");
  spheresBuf_ = gpu::Buffer(ctx, {std::max<std::size_t>(spheres_, 1) * sizeof(SphereGpu), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  gpu::MemoryUsage::Upload, "sl.spheres"});
  lights_ = gpu::Buffer(ctx, {render::kMaxLights * sizeof(render::LightGpu), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                              gpu::MemoryUsage::Upload, "sl.lights"});
  shadowMatrices_ = gpu::Buffer(ctx, {render::kMaxShadowLayers * sizeof(glm::mat4), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                      gpu::MemoryUsage::Upload, "sl.shadowMatrices"});
  // Pass 2 reads L^c as a uniform block (DESIGN: no SSBOs in fragment shaders on llvmpipe).
  if (spheres_ + setRange_.size() > kMaxShadedSpheres)
    throw InternalError("sl::IntensityPass: more SLs (and parents) than pass 2's uniform blocks hold");
  intensity_ = gpu::Buffer(ctx, {std::max<std::size_t>(std::size_t(spheres_) * kIntensityWordsPerSl * 4, kIntensityBlockBytes),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                 gpu::MemoryUsage::GpuOnly, "sl.intensity"});
  std::memset(lights_.mapped(), 0, lights_.size());
  std::memset(shadowMatrices_.mapped(), 0, shadowMatrices_.size());
  std::memset(spheresBuf_.mapped(), 0, spheresBuf_.size());

  unreadIntensity_ = gpu::Buffer(ctx, {kIntensityBlockBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::GpuOnly,
                                       "sl.intensity.unread"});
  noBlockers_ = std::make_unique<ShadeData>(ctx, order);
  pipeline_ = gpu::createComputePipeline(ctx, layout_, gpu::ShaderModule(ctx, "sl/intensity.comp.spv"), "sl.intensity",
                                         nullptr, ShadeData::specialization(order, Blocking::PerSphere, spheres_, influence));
  set_ = descriptors_.allocate(setLayout_);
  gpu::DescriptorWriter()
      .buffer(0, samples_)
      .buffer(1, spheresBuf_)
      .buffer(2, albedo_)
      .buffer(3, gaunt_)
      .buffer(4, lights_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
      .buffer(5, shadowMatrices_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
      .buffer(7, intensity_)
      .update(ctx, set_);
  setBlockers(*noBlockers_, samplers_.get({VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST}), false);
  if (!setRange_.empty()) {
    parentObjects_ = gpu::Buffer(ctx, {setRange_.size() * sizeof(glm::uvec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       gpu::MemoryUsage::Upload, "sl.parents.objects"});
    parentChildren_ = gpu::Buffer(ctx, {std::max<std::size_t>(spheres_, 1) * kParentChildFloats * sizeof(float),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, "sl.parents.children"});
    std::memset(parentChildren_.mapped(), 0, parentChildren_.size());
    auto* objects = reinterpret_cast<glm::uvec4*>(parentObjects_.mapped());
    for (std::size_t o = 0; o < setRange_.size(); ++o)
      objects[o] = glm::uvec4(setRange_[o].first, setRange_[o].second, spheres_ + std::uint32_t(o), 0u);
    parentSetLayout_ = gpu::DescriptorSetLayout(ctx,
                                                {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                                 {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                                 {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                                                "sl.parents");
    parentLayout_ = gpu::PipelineLayout(ctx, {parentSetLayout_}, {}, "sl.parents");
    parentPipeline_ = gpu::createComputePipeline(ctx, parentLayout_, gpu::ShaderModule(ctx, "sl/parent_intensity.comp.spv"),
                                                 "sl.parents", nullptr, {std::uint32_t(order)});
    parentSet_ = descriptors_.allocate(parentSetLayout_);
    gpu::DescriptorWriter().buffer(0, intensity_).buffer(1, parentObjects_).buffer(2, parentChildren_).update(ctx, parentSet_);
  }
}

void IntensityPass::setBlockers(const ShadeData& blockers, VkSampler nearest, bool on, bool localLights) {
  gpu::DescriptorWriter w;
  blockers.write(w, kBlockerBinding, unreadIntensity_, nearest);
  w.update(ctx_, set_);
  // intensity.comp pc.blockers: bit 0 the indirect light, bit 1 the point and spot lights (§7.3).
  push_.blockers = (on && blockers.count() > 0 ? 1u : 0u) | (localLights && blockers.count() > 0 ? 2u : 0u);
}

void IntensityPass::setSpheres(std::span<const PosedSphere> posed, std::span<const incident::RadianceSH> indirect) {
  if (posed.size() != spheres_ || indirect.size() != spheres_)
    throw InternalError("sl::IntensityPass::setSpheres: one pose and one indirect SH per SL");
  auto* out = reinterpret_cast<SphereGpu*>(spheresBuf_.mapped());
  for (std::uint32_t i = 0; i < spheres_; ++i) {
    SphereGpu g{};
    g.rest = rest_[i];
    g.posed = glm::vec4(posed[i].centre, posed[i].radius);
    for (int c = 0; c < 3; ++c) g.rotation[c] = glm::vec4(posed[i].rotation[c], 0.0f);
    g.range[0] = range_[i].first;
    g.range[1] = range_[i].second;
    for (int k = 0; k < 9; ++k) g.indirect[k] = glm::vec4(indirect[i][std::size_t(k)], 0.0f);
    std::memcpy(out + i, &g, sizeof g);
  }
  if (setRange_.empty()) return;
  // §7.3 parents: their spheres (CPU, update.hpp) and per child parent_intensity.comp's weight
  // (r_j / r_P)² and SH rotation (sh::Rotation, hierarchy.hpp parentOf's).
  std::vector<std::uint32_t> objects(spheres_);
  for (std::size_t o = 0; o < setRange_.size(); ++o)
    for (std::uint32_t i = 0; i < setRange_[o].second; ++i) objects[setRange_[o].first + i] = std::uint32_t(o);
  parentPosed_ = parentSpheres(posed, objects);
  parentPosed_.resize(setRange_.size());  // a trailing set without SLs
  auto* child = reinterpret_cast<float*>(parentChildren_.mapped());
  for (std::uint32_t i = 0; i < spheres_; ++i) {
    float* rec = child + std::size_t(i) * kParentChildFloats;
    const float rp = parentPosed_[objects[i]].radius;
    rec[0] = rp > 0.0f ? (posed[i].radius / rp) * (posed[i].radius / rp) : 0.0f;
    // A mirroring pose (closestRotation of an improper transform, det −1) is −Q with Q proper:
    // band l of −Q's SH rotation is (−1)^l that of Q, as for a mirrored DNRT / RTF placement.
    const SignedRotation q = splitMirror(posed[i].rotation);
    const sh::Rotationf rot = sh::Rotationf::fromMatrix(q.rotation);
    std::size_t at = 1;
    for (int l = 1; l <= 3; ++l)
      for (float m : rot.band(l)) rec[at++] = bandSign(q.mirrored, l) * m;
  }
}

void IntensityPass::setLights(std::span<const render::LightGpu> lights, std::span<const glm::mat4> shadowMatrices) {
  if (lights.size() > render::kMaxLights || shadowMatrices.size() > render::kMaxShadowLayers)
    throw InternalError("sl::IntensityPass::setLights: more lights or shadow layers than the uniform blocks hold");
  if (!lights.empty()) std::memcpy(lights_.mapped(), lights.data(), lights.size_bytes());
  if (!shadowMatrices.empty()) std::memcpy(shadowMatrices_.mapped(), shadowMatrices.data(), shadowMatrices.size_bytes());
  bindLights(lights_, std::uint32_t(lights.size()), shadowMatrices_);
}

void IntensityPass::bindLights(const gpu::Buffer& lights, std::uint32_t count, const gpu::Buffer& shadowMatrices) {
  if (count > render::kMaxLights) throw InternalError("sl::IntensityPass::bindLights: more lights than the block holds");
  gpu::DescriptorWriter()
      .buffer(4, lights, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, render::kMaxLights * sizeof(render::LightGpu))
      .buffer(5, shadowMatrices, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, render::kMaxShadowLayers * sizeof(glm::mat4))
      .update(ctx_, set_);
  push_.lightCount = count;
}

void IntensityPass::setShadowAtlas(VkImageView atlas, VkSampler compareSampler, VkImageLayout layout, bool shadowsOn) {
  gpu::DescriptorWriter().sampledImage(6, atlas, compareSampler, layout).update(ctx_, set_);
  atlasBound_ = true;
  push_.shadowsOn = shadowsOn ? 1u : 0u;
}

void IntensityPass::record(VkCommandBuffer cmd) {
  if (!atlasBound_) throw InternalError("sl::IntensityPass::record: no shadow atlas bound (setShadowAtlas)");
  if (spheres_ == 0) return;
  pipeline_.bind(cmd);
  pipeline_.bindSet(cmd, 0, set_);
  pipeline_.push(cmd, push_);
  vkCmdDispatch(cmd, spheres_, 1, 1);
  if (!setRange_.empty()) {
    // The parents read every child's L^c: pass 1's writes first (§7.3, parent_intensity.comp).
    VkMemoryBarrier children{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &children, 0,
                         nullptr, 0, nullptr);
    parentPipeline_.bind(cmd);
    parentPipeline_.bindSet(cmd, 0, parentSet_);
    vkCmdDispatch(cmd, std::uint32_t(setRange_.size()), 1, 1);
  }
  VkMemoryBarrier done{VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, VK_ACCESS_SHADER_WRITE_BIT,
                       VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_UNIFORM_READ_BIT};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 1, &done, 0,
                       nullptr, 0, nullptr);
}

}  // namespace bounce::gi::sl
