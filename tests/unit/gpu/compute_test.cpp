// A compute shader fills a storage buffer with a formula; every value is checked.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "engine/core/error.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/pipeline_table.hpp"
#include "engine/gpu/testing.hpp"
#include "tests/unit/gpu/fill_shader.hpp"

using namespace bounce;
using namespace bounce::gpu;

using testkit::FillPush;
using testkit::kFillPush;

namespace {
constexpr float kSentinel = -7.0f;  // marks elements the shader must not touch
}  // namespace

TEST(Compute, FillsAStorageBufferWithAFormula) {
  Context& ctx = testkit::sharedContext();
  const std::uint32_t capacity = 1024, count = 1000;  // 1000 is not a multiple of 64: bounds check
  Buffer out(ctx, {capacity * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                   MemoryUsage::GpuOnly, "fill out"});
  upload(ctx, out, bytesOf(std::vector<float>(capacity, kSentinel)));

  DescriptorSetLayout setLayout(ctx, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}}, "fill");
  PipelineLayout layout(ctx, {setLayout}, {kFillPush}, "fill");
  ShaderModule shader(ctx, "test/fill.comp.spv");
  PipelineCache cache(ctx);
  Pipeline pipeline = createComputePipeline(ctx, layout, shader, "fill", &cache);
  DescriptorAllocator descriptors(ctx);
  VkDescriptorSet set = descriptors.allocate(setLayout);
  DescriptorWriter().buffer(0, out).update(ctx, set);

  const std::vector<float> v = testkit::dispatchFill(ctx, pipeline, set, out, FillPush{count, 0.5f, 3.0f});
  ASSERT_EQ(v.size(), capacity);
  for (std::uint32_t i = 0; i < capacity; ++i) {
    float expected = i < count ? 0.5f * float(i) * float(i) + 3.0f : kSentinel;  // exact in float32
    ASSERT_EQ(v[i], expected) << "element " << i;
  }
}

// constant_id i takes SpecConstants[i]; no constants keeps the shader's defaults; one module, two
// pipelines, two results (the mechanism technique variants use instead of runtime branches).
TEST(Compute, SpecializationConstantsSelectTheVariant) {
  Context& ctx = testkit::sharedContext();
  DescriptorSetLayout setLayout(ctx, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}}, "spec");
  PipelineLayout layout(ctx, {setLayout}, {}, "spec");
  ShaderModule shader(ctx, "test/spec.comp.spv");
  DescriptorAllocator descriptors(ctx);
  const auto run = [&](const SpecConstants& constants) {
    Buffer out(ctx, {64 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                     MemoryUsage::GpuOnly, "spec out"});
    Pipeline pipeline = createComputePipeline(ctx, layout, shader, "spec", nullptr, constants);
    VkDescriptorSet set = descriptors.allocate(setLayout);
    DescriptorWriter().buffer(0, out).update(ctx, set);
    submitAndWait(ctx, [&](VkCommandBuffer cmd) {
      pipeline.bind(cmd);
      pipeline.bindSet(cmd, 0, set);
      vkCmdDispatch(cmd, 1, 1, 1);
    });
    auto bytes = readback(ctx, out);
    std::vector<float> v(64);
    std::memcpy(v.data(), bytes.data(), bytes.size());
    return v;
  };
  const std::vector<float> plain = run({}), varied = run({5u, 1u}), addOnly = run({7u});
  for (std::uint32_t i = 0; i < 64; ++i) {
    ASSERT_EQ(plain[i], float(i)) << "element " << i;
    ASSERT_EQ(varied[i], -float(i + 5)) << "element " << i;
    ASSERT_EQ(addOnly[i], float(i + 7)) << "element " << i;
  }
}

TEST(Compute, MissingShaderFileIsNamed) {
  Context& ctx = testkit::sharedContext();
  try {
    ShaderModule m(ctx, "test/not-there.comp.spv");
    FAIL();
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("test/not-there.comp.spv not found"), std::string::npos) << e.what();
  }
}

TEST(Compute, PipelineCacheSavesAndReloads) {
  // Reuse off: with Context's pipeline table on, the second request would be served from the table
  // and the reloaded cache never consulted.
  ContextOptions noReuse;
  noReuse.reusePipelines = false;
  Context ctx(noReuse);
  ASSERT_FALSE(ctx.pipelines().reuses());
  auto file = std::filesystem::path(BOUNCE_TEST_OUT) / "gpu" / "pipeline.cache";
  std::filesystem::remove(file);
  DescriptorSetLayout setLayout(ctx, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}}, "fill");
  PipelineLayout layout(ctx, {setLayout}, {kFillPush}, "fill");
  ShaderModule shader(ctx, "test/fill.comp.spv");
  {
    PipelineCache cache(ctx, file);
    Pipeline p = createComputePipeline(ctx, layout, shader, "cached fill", &cache);
    cache.save();
  }
  // The Vulkan pipeline cache header alone is 16 + VK_UUID_SIZE bytes.
  ASSERT_TRUE(std::filesystem::exists(file));
  EXPECT_GE(std::filesystem::file_size(file), 16u + VK_UUID_SIZE);
  PipelineCache reloaded(ctx, file);
  Pipeline p = createComputePipeline(ctx, layout, shader, "cached fill again", &reloaded);
  EXPECT_NE(p.handle(), VK_NULL_HANDLE);
}
