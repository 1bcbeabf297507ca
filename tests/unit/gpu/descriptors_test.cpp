// Descriptor pools grow and reset; samplers are cached.
#include <gtest/gtest.h>

#include "engine/core/error.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/testing.hpp"

using namespace bounce;
using namespace bounce::gpu;

TEST(Descriptors, PoolsGrowAndResetKeepsThem) {
  Context& ctx = testkit::sharedContext();
  DescriptorSetLayout layout(ctx,
                             {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                              {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT}},
                             "grow");
  DescriptorAllocator alloc(ctx, "test");
  const std::uint32_t n = DescriptorAllocator::kFirstPoolSets + 10;  // more than one pool holds
  std::vector<VkDescriptorSet> sets;
  for (std::uint32_t i = 0; i < n; ++i) sets.push_back(alloc.allocate(layout));
  EXPECT_EQ(alloc.poolCount(), 2u);
  std::sort(sets.begin(), sets.end());
  EXPECT_EQ(std::unique(sets.begin(), sets.end()), sets.end());  // all distinct
  alloc.reset();
  for (std::uint32_t i = 0; i < n; ++i) alloc.allocate(layout);
  EXPECT_EQ(alloc.poolCount(), 2u);  // reused, not grown
}

TEST(Descriptors, DuplicateBindingIsRejected) {
  Context& ctx = testkit::sharedContext();
  EXPECT_THROW(DescriptorSetLayout(ctx, {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}, {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}},
                                   "dup"),
               InternalError);
}

TEST(Descriptors, SamplerCacheReturnsOneSamplerPerDescription) {
  Context& ctx = testkit::sharedContext();
  SamplerCache cache(ctx);
  SamplerDesc linear;
  SamplerDesc nearest;
  nearest.filter = VK_FILTER_NEAREST;
  VkSampler a = cache.get(linear), b = cache.get(nearest), c = cache.get(linear);
  EXPECT_EQ(a, c);
  EXPECT_NE(a, b);
  EXPECT_EQ(cache.size(), 2u);
}
