// MemoryAllocator on a real device: block sharing, dedicated allocations, granularity.
#include <gtest/gtest.h>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/testing.hpp"

using namespace bounce::gpu;

TEST(Memory, SmallResourcesShareOneBlockAndLargeOnesAreDedicated) {
  Context& ctx = testkit::sharedContext();
  MemoryAllocator& mem = ctx.allocator();
  auto before = mem.stats();
  {
    std::vector<Buffer> small;
    for (int i = 0; i < 20; ++i)
      small.emplace_back(ctx, BufferDesc{4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "small"});
    auto s = mem.stats();
    EXPECT_EQ(s.suballocations, before.suballocations + 20);
    EXPECT_LE(s.blocks, before.blocks + 1);  // one new 64 MiB block at most
    for (std::size_t i = 1; i < small.size(); ++i) {
      EXPECT_EQ(small[i].allocation().memory, small[0].allocation().memory);
      EXPECT_EQ(small[i].allocation().offset % ctx.limits().minStorageBufferOffsetAlignment, 0u);
    }
    Buffer big(ctx, {MemoryAllocator::kDefaultBlockSize / 2 + 1, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     MemoryUsage::GpuOnly, "big"});
    EXPECT_EQ(big.allocation().block, -1);
    EXPECT_EQ(big.allocation().offset, 0u);
    EXPECT_EQ(mem.stats().dedicated, before.dedicated + 1);
  }
  auto after = mem.stats();
  EXPECT_EQ(after.suballocations, before.suballocations);
  EXPECT_EQ(after.dedicated, before.dedicated);
  EXPECT_EQ(after.usedBytes, before.usedBytes);
}

TEST(Memory, FreedRangeIsReused) {
  Context& ctx = testkit::sharedContext();
  BufferDesc d{1 << 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "reuse"};
  Buffer a(ctx, d);
  VkDeviceSize offset = a.allocation().offset;
  VkDeviceMemory memory = a.allocation().memory;
  a.reset();
  Buffer b(ctx, d);
  EXPECT_EQ(b.allocation().memory, memory);
  EXPECT_EQ(b.allocation().offset, offset);
}

TEST(Memory, BuffersAndImagesInOneBlockRespectGranularity) {
  Context& ctx = testkit::sharedContext();
  VkDeviceSize g = ctx.limits().bufferImageGranularity;
  Buffer buf(ctx, {100, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "linear"});
  Image img(ctx, {ImageType::Tex2D, VK_FORMAT_R8G8B8A8_UNORM, 8, 8, 1, 1, 1, VK_IMAGE_USAGE_SAMPLED_BIT,
                  VK_SAMPLE_COUNT_1_BIT, "optimal"});
  const Allocation& a = buf.allocation();
  const Allocation& b = img.allocation();
  if (a.memory == b.memory) {  // same block: pages must differ
    VkDeviceSize aFirst = a.offset / g, aLast = (a.offset + a.size - 1) / g;
    VkDeviceSize bFirst = b.offset / g, bLast = (b.offset + b.size - 1) / g;
    EXPECT_TRUE(aLast < bFirst || bLast < aFirst);
  }
  EXPECT_EQ(b.offset % 16, 0u);
}

TEST(Memory, HostVisibleBuffersAreMapped) {
  Context& ctx = testkit::sharedContext();
  Buffer up(ctx, {256, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "upload"});
  Buffer down(ctx, {256, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "readback"});
  EXPECT_NE(up.mapped(), nullptr);
  EXPECT_NE(down.mapped(), nullptr);
}
