// rtf.glsl's Eq. 10 lookup (what the shading step will run per pixel) = lookup() /
// interreflection() / occlusion() of engine/gi/rtf/evaluate.cpp, on receivers inside the innermost
// sphere, between spheres, on samples, beyond the outermost sphere and far away. The GPU reads the
// ξ the xi pass wrote (equal to the CPU caches to 1e-5, xi_gpu_test.cpp); weights are computed in
// float by the same formulas on both sides: tolerance 1e-5 absolute + 1e-4 relative.
#include <gtest/gtest.h>

#include <cstring>

#include "engine/gi/rtf/evaluate.hpp"
#include "engine/gi/rtf/xi_pass.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"
#include "tests/unit/rtf/small_field.hpp"

namespace bounce::gi::rtf {
namespace {

struct Output {
  float xi[16][4];
  float v[16];
};
static_assert(sizeof(Output) == 320);
struct Push {
  std::uint32_t count;
  std::int32_t spheres, faceSize;
  float innerRadius, outerRadius;
};

TEST(RtfLookupGpu, GlslLookupEqualsTheCpuEvaluation) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const BakeResult b = bake(testing::unitSphere(glm::vec3(0.8f, 0.6f, 0.4f), 8), testing::smallSettings());
  const Field& f = b.field;
  const FieldSettings& s = f.settings;
  math::Pcg32 rng(3);
  std::vector<glm::vec3> L(std::size_t(s.proxies) * kShCount);
  for (auto& l : L) l = rng.nextFloat3();
  const std::vector<glm::vec3> xi = xiCache(f, L);

  std::vector<glm::vec4> points;
  const float rN = sphereRadius(s, s.spheres - 1), dr = sphereRadius(s, 1) - sphereRadius(s, 0);
  for (float r : {0.0f, 0.2f, sphereRadius(s, 0), 1.1f, 2.0f, 3.3f, rN, rN + 0.3f * dr, rN + 0.9f * dr, rN + 2.0f * dr})
    for (int k = 0; k < 12; ++k) points.emplace_back(r * glm::vec3(math::uniformSphere(rng.next2D())), 0.0f);
  for (int face = 0; face < 6; ++face)  // exactly on samples, and on the face axes (ties)
    points.emplace_back(sphereRadius(s, 1) * glm::vec3(sh::cubeTexelDirection(face, 1, 0, s.faceSize)), 0.0f);
  for (const glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 1), glm::vec3(1, 1, 0), glm::vec3(1, 1, 1)})
    points.emplace_back(2.5f * glm::normalize(d), 0.0f);
  const std::uint32_t n = std::uint32_t(points.size());

  XiPass pass(ctx, f, {.keepXi = true});
  pass.setProxyLight(L);
  gpu::Buffer in(ctx, {points.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, "rtf.points"});
  gpu::Buffer out(ctx, {n * sizeof(Output), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Readback, "rtf.out"});
  gpu::upload(ctx, in, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(points.data()), points.size() * sizeof(glm::vec4)));
  gpu::DescriptorSetLayout layout(ctx,
                                  {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                   {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
                                   {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                   {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER}},
                                  "rtf.lookup");
  gpu::PipelineLayout pipelineLayout(ctx, {layout}, {{VK_SHADER_STAGE_ALL, 0, sizeof(Push)}}, "rtf.lookup");
  gpu::Pipeline pipeline = gpu::createComputePipeline(ctx, pipelineLayout, gpu::ShaderModule(ctx, "rtf/lookup_selftest.comp.spv"), "rtf.lookup");
  gpu::SamplerCache samplers(ctx);
  // Linear: the bilinear part of Eq. 10 is the sampler's (rtf.glsl rtfTaps).
  const VkSampler linear = samplers.get({VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST});
  gpu::DescriptorAllocator descriptors(ctx);
  VkDescriptorSet set = descriptors.allocate(layout);
  gpu::DescriptorWriter()
      .buffer(0, in)
      .buffer(1, out)
      .sampledImage(2, pass.xi().view(), linear, VK_IMAGE_LAYOUT_GENERAL)
      .sampledImage(3, pass.oof().view(), linear)
      .update(ctx, set);
  const Push push{n, s.spheres, s.faceSize, s.innerRadius, s.outerRadius};
  gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    pass.record(cmd);
    pipeline.bind(cmd);
    pipeline.bindSet(cmd, 0, set);
    pipeline.push(cmd, push);
    vkCmdDispatch(cmd, (n + 63) / 64, 1, 1);
  });
  const auto bytes = gpu::readback(ctx, out);
  std::vector<Output> got(n);
  std::memcpy(got.data(), bytes.data(), n * sizeof(Output));
  int nonZero = 0;
  for (std::uint32_t p = 0; p < n; ++p) {
    const glm::vec3 q(points[p]);
    const ShRgb want = interreflection(f, xi, q);
    const ShScalar v = occlusion(f, q);
    for (int i = 0; i < kShCount; ++i) {
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[p].xi[i][c], want[std::size_t(i)][c], 1e-5f + 1e-4f * std::abs(want[std::size_t(i)][c])) << p << " " << i;
      ASSERT_NEAR(got[p].v[i], v[std::size_t(i)], 1e-5f + 1e-4f * std::abs(v[std::size_t(i)])) << p << " " << i;
      nonZero += want[std::size_t(i)].r != 0.0f;
    }
  }
  EXPECT_GT(nonZero, 100);  // the comparison is not between zeros
}

}  // namespace
}  // namespace bounce::gi::rtf
