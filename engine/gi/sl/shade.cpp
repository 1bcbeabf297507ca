#include "engine/gi/sl/shade.hpp"

#include <algorithm>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "engine/core/error.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/math/sh_exp.hpp"

namespace bounce::gi::sl {

namespace {
constexpr std::uint32_t kTableWidth = 256;  // θ entries (log and weight rows); the OL row uses 128
static_assert(sh::ExpTables::kThetaEntries == int(kTableWidth) && kAverageRadianceEntries == int(kTableWidth) &&
              sh::ExpTables::kMagEntries <= int(kTableWidth));
}  // namespace

ShadeData::ShadeData(gpu::Context& ctx, int order, std::uint32_t mappedSpheres)
    : order_(order), mappedSpheres_(mappedSpheres), indirectBytes_(indirectBlockBytes(mappedSpheres)) {
  if (order != 3 && order != 4) throw InternalError("sl::ShadeData: order must be 3 or 4");
  if (mappedSpheres > kMaxMappedSpheres) throw InternalError("sl::ShadeData: more mapped SLs than kMaxMappedSpheres");
  // Tables: sl.glsl's rows 0 (log ZH), 1 (weight ZH), 2 (OL a, b).
  const sh::ExpTables& t = sh::expTables(order, sh::LogKind::Windowed);
  const std::span<const double> w = averageRadianceTable(order);
  std::vector<float> texels(std::size_t(kTableWidth) * 3 * 4, 0.0f);
  for (std::uint32_t i = 0; i < kTableWidth; ++i)
    for (int l = 0; l < order; ++l) {
      texels[(0 * kTableWidth + i) * 4 + std::size_t(l)] = float(t.logTable()[std::size_t(i) * order + std::size_t(l)]);
      texels[(1 * kTableWidth + i) * 4 + std::size_t(l)] = float(w[std::size_t(i) * order + std::size_t(l)]);
    }
  for (int i = 0; i < sh::ExpTables::kMagEntries; ++i) {
    texels[(2 * kTableWidth + std::size_t(i)) * 4 + 0] = float(t.olTable()[2 * std::size_t(i)]);
    texels[(2 * kTableWidth + std::size_t(i)) * 4 + 1] = float(t.olTable()[2 * std::size_t(i) + 1]);
  }
  gpu::ImageDesc d;
  d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  d.width = kTableWidth;
  d.height = 3;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  d.name = "sl.tables";
  tables_ = gpu::Image(ctx, d);
  gpu::upload(ctx, tables_, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(texels.data()), texels.size() * sizeof(float)));

  spheres_ = gpu::Buffer(ctx, {(1 + 6 * std::size_t(kMaxShadedSpheres)) * sizeof(glm::vec4), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                               gpu::MemoryUsage::Upload, "sl.spheres"});
  std::memset(spheres_.mapped(), 0, spheres_.size());
  indirect_ = gpu::Buffer(ctx, {indirectBytes_, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::Upload, "sl.indirect"});
  std::memset(indirect_.mapped(), 0, indirect_.size());
}

void ShadeData::setSpheres(std::span<const ShadedSphere> spheres, std::span<const PosedSphere> parents,
                           std::span<const incident::RadianceSH> indirect, std::span<const incident::DirectionMap> maps) {
  if (spheres.size() + parents.size() > kMaxShadedSpheres)
    throw InternalError("sl::ShadeData: more SLs (and parents) than the uniform block holds");
  if (!indirect.empty() && indirect.size() != spheres.size())
    throw InternalError("sl::ShadeData: one indirect SH per SL or none");
  if (!maps.empty() && (maps.size() != spheres.size() || maps.size() > mappedSpheres_))
    throw InternalError("sl::ShadeData: one direction map per SL (at most the block's mappedSpheres) or none");
  if (!indirect.empty() && maps.empty() && indirect.size() * kIndirectWordsPerSl * 4 > indirectBytes_)
    throw InternalError("sl::ShadeData: more indirect SH than the SlIndirect block holds");
  if (!maps.empty()) {  // SlIndirect as maps (sl_data.glsl): SL i's texel t in word 256 i + t, RGB9E5
    std::vector<std::uint32_t> words(indirectBytes_ / 4, 0u);
    for (std::size_t i = 0; i < maps.size(); ++i)
      for (std::size_t t = 0; t < kMapWordsPerSl; ++t) words[kMapWordsPerSl * i + t] = glm::packF3x9_E1x5(maps[i][t]);
    std::memcpy(indirect_.mapped(), words.data(), indirectBytes_);
  } else {  // SlIndirect (sl_data.glsl): half h = 3k + c in word h / 2, low half first.
    std::vector<std::uint32_t> words(indirectBytes_ / 4, 0u);
    for (std::size_t i = 0; i < indirect.size(); ++i) {
      float halves[2 * kIndirectWordsPerSl] = {};
      for (std::size_t k = 0; k < 9; ++k)
        for (int c = 0; c < 3; ++c) halves[3 * k + std::size_t(c)] = std::clamp(indirect[i][k][c], -65504.0f, 65504.0f);
      for (std::size_t w = 0; w < kIndirectWordsPerSl; ++w)
        words[kIndirectWordsPerSl * i + w] = glm::packHalf2x16(glm::vec2(halves[2 * w], halves[2 * w + 1]));
    }
    std::memcpy(indirect_.mapped(), words.data(), indirectBytes_);
  }
  std::vector<glm::vec4> v(1 + 6 * std::size_t(kMaxShadedSpheres), glm::vec4(0.0f));
  count_ = std::uint32_t(spheres.size());
  std::uint32_t objects = 0;
  for (const ShadedSphere& s : spheres) objects = std::max(objects, s.object + 1);
  if (objects > kMaxShadedSpheres) throw InternalError("sl::ShadeData: object index beyond the uniform block");
  const std::uint32_t header[3] = {count_, objects, std::uint32_t(parents.size())};
  std::memcpy(&v[0], header, sizeof header);
  // Per-object blocking's order (evaluate.cpp: the mean of each object's sphere centres), in double
  // as the reference sums it.
  std::vector<glm::dvec4> mean(objects, glm::dvec4(0.0));
  for (const ShadedSphere& s : spheres) mean[s.object] += glm::dvec4(glm::dvec3(s.centre), 1.0);
  for (std::uint32_t o = 0; o < objects; ++o)
    if (mean[o].w > 0.0) v[1 + 4 * std::size_t(kMaxShadedSpheres) + o] = glm::vec4(glm::dvec3(mean[o]) / mean[o].w, mean[o].w);
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const ShadedSphere& s = spheres[i];
    v[1 + 4 * i] = glm::vec4(s.centre, s.radius);
    for (int c = 0; c < 3; ++c) v[2 + 4 * i + std::size_t(c)] = glm::vec4(s.rotation[c], 0.0f);
    v[2 + 4 * i].w = float(s.object);
    v[3 + 4 * i].w = s.share;
    v[4 + 4 * i].w = s.silhouette;
  }
  for (std::size_t o = 0; o < parents.size(); ++o) {
    const std::size_t i = spheres.size() + o;
    v[1 + 4 * i] = glm::vec4(parents[o].centre, parents[o].radius);
    for (int c = 0; c < 3; ++c) v[2 + 4 * i + std::size_t(c)] = glm::vec4(glm::mat3(1.0f)[c], 1.0f);
    v[2 + 4 * i].w = float(o);
    // The object's union share and shadow scale ("sl.shadow"), as probeShadow's settings give them.
    for (const ShadedSphere& s : spheres)
      if (s.object == o) {
        v[3 + 4 * i].w = s.share;
        v[4 + 4 * i].w = s.silhouette;
        break;
      }
  }
  // Pairs of one object that overlap (evaluate.cpp's intersects(), in double): pass 2 subtracts
  // them from the running blocker sum instead of testing every pair per pixel.
  std::vector<glm::uvec4> masks(kMaxShadedSpheres, glm::uvec4(0u));
  for (std::size_t i = 0; i < spheres.size(); ++i)
    for (std::size_t j = 0; j < spheres.size(); ++j) {
      const ShadedSphere &a = spheres[i], &b = spheres[j];
      if (i == j || a.object != b.object) continue;
      if (glm::length(glm::dvec3(a.centre) - glm::dvec3(b.centre)) < double(a.radius) + double(b.radius))
        masks[i][int(j / 32)] |= 1u << (j % 32);
    }
  std::memcpy(&v[1 + 5 * std::size_t(kMaxShadedSpheres)], masks.data(), masks.size() * sizeof(glm::uvec4));
  std::memcpy(spheres_.mapped(), v.data(), v.size() * sizeof(glm::vec4));
}

void ShadeData::write(gpu::DescriptorWriter& w, std::uint32_t first, const gpu::Buffer& intensity, VkSampler nearest) const {
  if (intensity.size() < kIntensityBlockBytes) throw InternalError("sl::ShadeData: intensity buffer smaller than its block");
  w.sampledImage(first, tables_.view(), nearest)
      .buffer(first + 1, spheres_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
      .buffer(first + 2, intensity, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, kIntensityBlockBytes);
}

void ShadeData::writeIndirect(gpu::DescriptorWriter& w, std::uint32_t binding) const {
  w.buffer(binding, indirect_, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0, indirectBytes_);
}

std::vector<gpu::Binding> ShadeData::bindings(std::uint32_t first) {
  return {{first, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
          {first + 1, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
          {first + 2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER}};
}

gpu::SpecConstants ShadeData::specialization(int order, Blocking blocking, std::uint32_t spheres, float influence) {
  const std::uint32_t size = specSpheres(spheres);
  std::uint32_t f = 0;
  std::memcpy(&f, &influence, sizeof f);
  return {std::uint32_t(order), blocking == Blocking::PerObject ? 1u : 0u, size, f};
}

}  // namespace bounce::gi::sl
