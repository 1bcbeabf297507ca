#pragma once
// Pass `probes.relight`'s device fixture (tests/unit/probes/relight_gpu_test.cpp, and the SLs' bounce
// in it, tests/unit/sl/relight_bounce_gpu_test.cpp): a closed white box (ρ = 0.5, 1 m) under a point
// light, surfels and probes baked as a level's would be, a 1-texel shadow atlas the tests bypass
// (V_now from the pass's test buffer, so the shadow is exactly the one a test sets).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "engine/gi/probes/node.hpp"
#include "engine/gi/probes/probe_volume.hpp"
#include "engine/gi/probes/relight.hpp"
#include "engine/gi/probes/relight_pass.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/testing.hpp"
#include "tests/unit/ref/test_scenes.hpp"

namespace bounce::gi::probes::relighttest {

constexpr float kRho = 0.5f;

struct Fixture {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  ProbeVolume volume;
  RelightData data;
  render::LightGpu light{};
  std::vector<float> vStatic;
  gpu::Buffer packed, lights, matrices;
  gpu::Image atlas;
  gpu::SamplerCache samplers{ctx};
  VkSampler compare = VK_NULL_HANDLE;
  gpu::DescriptorAllocator descriptors{ctx, "relight.test"};
  std::unique_ptr<ref::SceneBvh> bvh;

  Fixture() {
    ref::SceneDesc s;
    s.meshes = ref::test::insideOfCube(0.5f, 0);
    s.materials = {{glm::vec3(kRho), -1, glm::vec3(0.0f), -1}};
    bvh = std::make_unique<ref::SceneBvh>(std::move(s));
    const ProbeGrid grid = gridOverBounds(glm::vec3(-0.5f), glm::vec3(0.5f), 0.25f);
    ProbeSettings settings;
    settings.rays = 256;
    settings.bounces = 1;
    volume = bakeProbes(*bvh, grid, settings, nullptr, "");
    data = bakeRelight(*bvh, grid, settings, 1024, "");
    light.positionType = glm::vec4(0.0f, 0.4f, 0.0f, 1.0f);  // point
    light.radiance = glm::vec4(0.2f, 0.2f, 0.2f, 0.0f);
    light.shadow = glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f);
    vStatic = staticVisibility(*bvh, data.surfels, {&light, 1});
    const std::vector<std::uint32_t> words = packedShWords(volume);
    packed = gpu::Buffer(ctx, {64 * 1024, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                              VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               gpu::MemoryUsage::GpuOnly, "relight.test.packed"});
    gpu::upload(ctx, packed, {reinterpret_cast<const std::uint8_t*>(words.data()), words.size() * 4});
    lights = gpu::Buffer(ctx, {render::kMaxLights * sizeof(render::LightGpu), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                               gpu::MemoryUsage::Upload, "relight.test.lights"});
    std::memset(lights.mapped(), 0, lights.size());
    std::memcpy(lights.mapped(), &light, sizeof light);
    matrices = gpu::Buffer(ctx, {render::kMaxShadowLayers * sizeof(glm::mat4), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                 gpu::MemoryUsage::Upload, "relight.test.matrices"});
    std::memset(matrices.mapped(), 0, matrices.size());
    gpu::ImageDesc d;
    d.format = VK_FORMAT_D32_SFLOAT;
    d.layers = 2;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    d.name = "relight.test.atlas";
    atlas = gpu::Image(ctx, d);
    const float texels[2] = {1.0f, 1.0f};
    gpu::upload(ctx, atlas, {reinterpret_cast<const std::uint8_t*>(texels), sizeof texels});
    gpu::SamplerDesc sd;
    sd.compare = true;
    sd.mipmap = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    compare = samplers.get(sd);
  }

  void run(RelightPass& pass, int iterations, bool pack) {
    gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) {
      pass.record(cmd, descriptors, lights, 1, matrices, atlas.view(), compare, false, iterations, pack);
    });
  }
  std::vector<glm::vec3> delta(const RelightPass& pass) {
    const auto bytes = gpu::readback(ctx, pass.delta());
    std::vector<glm::vec3> out(volume.grid.probeCount() * 9);
    for (std::size_t i = 0; i < out.size(); ++i) {
      glm::vec4 v;
      std::memcpy(&v, bytes.data() + 16 * i, 16);
      out[i] = glm::vec3(v);
    }
    return out;
  }
  std::vector<glm::vec3> radiance(const RelightPass& pass) {
    const auto bytes = gpu::readback(ctx, pass.surfelRadiance());
    std::vector<glm::vec3> out(data.surfels.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
      glm::vec4 v;
      std::memcpy(&v, bytes.data() + 16 * i, 16);
      out[i] = glm::vec3(v);
    }
    return out;
  }
  // The lit floor surfel nearest below the light (V_static = 1, facing it).
  std::size_t floorSurfelUnderLight() const {
    std::size_t best = 0;
    float bestD = 1e9f;
    for (std::size_t s = 0; s < data.surfels.size(); ++s) {
      const Surfel& sf = data.surfels[s];
      if (sf.normal.y < 0.99f || vStatic[s] != 1.0f) continue;
      const float d = glm::length(glm::vec2(sf.position.x, sf.position.z));
      if (d < bestD) bestD = d, best = s;
    }
    return best;
  }
};

inline float maxAbs(const std::vector<glm::vec3>& v) {
  float m = 0.0f;
  for (const glm::vec3& x : v) m = std::max({m, std::abs(x.x), std::abs(x.y), std::abs(x.z)});
  return m;
}

}  // namespace bounce::gi::probes::relighttest
