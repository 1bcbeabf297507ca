// OffsetAllocator: pure offset arithmetic, no device.
#include <gtest/gtest.h>

#include "engine/core/error.hpp"
#include "engine/gpu/offset_allocator.hpp"

using namespace bounce;
using namespace bounce::gpu;
using Kind = OffsetAllocator::Kind;

TEST(OffsetAllocator, OffsetsHonourAlignment) {
  OffsetAllocator a(1 << 20);
  EXPECT_EQ(a.allocate(3, 1), 0u);
  EXPECT_EQ(a.allocate(10, 256), 256u);  // 3 rounded up to the next multiple of 256
  EXPECT_EQ(a.allocate(1, 4), 4u);       // best fit: the 253-byte hole before 256 is the smallest
  auto big = a.allocate(100, 4096);
  ASSERT_TRUE(big);
  EXPECT_EQ(*big % 4096, 0u);
  EXPECT_EQ(a.usedBytes(), 3u + 10u + 1u + 100u);
}

TEST(OffsetAllocator, FreedRangeIsReusedAndCoalesced) {
  OffsetAllocator a(1000);
  auto x = a.allocate(100, 1), y = a.allocate(200, 1), z = a.allocate(300, 1);
  ASSERT_TRUE(x && y && z);
  EXPECT_EQ(*y, 100u);
  a.free(*y);
  EXPECT_EQ(a.allocate(200, 1), 100u);  // exactly the freed range
  a.free(100);
  a.free(*x);
  a.free(*z);
  EXPECT_TRUE(a.empty());
  EXPECT_EQ(a.freeRangeCount(), 1u);  // everything merged back into one range
  EXPECT_EQ(a.largestFreeRange(), 1000u);
  EXPECT_EQ(a.allocate(1000, 1), 0u);
}

TEST(OffsetAllocator, BestFitKeepsTheLargeHole) {
  // Layout: [A 100][hole 50][B 100][hole 400][C 100][tail 250]
  OffsetAllocator a(1000);
  auto A = a.allocate(100, 1), h1 = a.allocate(50, 1), B = a.allocate(100, 1), h2 = a.allocate(400, 1),
       C = a.allocate(100, 1);
  ASSERT_TRUE(A && h1 && B && h2 && C);
  a.free(*h1);
  a.free(*h2);
  EXPECT_EQ(a.freeRangeCount(), 3u);
  EXPECT_EQ(a.allocate(40, 1), 100u);   // the 50-byte hole, not the 400-byte one
  EXPECT_EQ(a.allocate(260, 1), 250u);  // 250-byte tail too small → the 400-byte hole
  EXPECT_EQ(a.allocate(200, 1), 750u);  // tail
}

TEST(OffsetAllocator, FragmentationFailsThenRecoversAfterFree) {
  OffsetAllocator a(400);
  std::optional<std::uint64_t> blocks[4];
  for (auto& b : blocks) b = a.allocate(100, 1);
  a.free(*blocks[0]);
  a.free(*blocks[2]);
  // 200 bytes free in total but no 200-byte range.
  EXPECT_EQ(a.largestFreeRange(), 100u);
  EXPECT_FALSE(a.allocate(200, 1));
  a.free(*blocks[1]);  // merges [0,300)
  EXPECT_EQ(a.allocate(300, 1), 0u);
}

TEST(OffsetAllocator, GranularitySeparatesLinearAndOptimal) {
  constexpr std::uint64_t kPage = 1024;  // bufferImageGranularity of the imagined device
  OffsetAllocator a(8 * kPage, kPage);
  EXPECT_EQ(a.allocate(100, 16, Kind::Linear), 0u);
  EXPECT_EQ(a.allocate(100, 16, Kind::Linear), 112u);  // same kind shares the page
  EXPECT_EQ(a.allocate(100, 16, Kind::Optimal), kPage);  // different kind: next page
  EXPECT_EQ(a.allocate(100, 16, Kind::Optimal), kPage + 112);
  // Linear again: best fit is the 12-byte alignment gap [100, 112) on page 0 ...
  EXPECT_EQ(a.allocate(10, 1, Kind::Linear), 100u);
  // ... but a larger one cannot go there, nor on page 1 (images): page 2.
  EXPECT_EQ(a.allocate(1000, 1, Kind::Linear), 2 * kPage);
}

TEST(OffsetAllocator, GranularityChecksTheNextNeighbourToo) {
  constexpr std::uint64_t kPage = 1024;
  OffsetAllocator a(4 * kPage, kPage);
  auto first = a.allocate(kPage, 1, Kind::Linear);             // [0, 1024)
  auto image = a.allocate(kPage / 2, 1, Kind::Optimal);        // [1024, 1536)
  ASSERT_TRUE(first && image);
  a.free(*first);
  // Linear ranges in [0, 1024) end on page 0, before the image's page 1: allowed.
  EXPECT_EQ(a.allocate(kPage / 2, 1, Kind::Linear), 0u);
  // The rest of page 0 fits exactly; the tail of the image's page, [1536, 2048), is off
  // limits to linear resources, so the next one goes to page 2.
  EXPECT_EQ(a.allocate(kPage / 2, 1, Kind::Linear), kPage / 2);
  EXPECT_EQ(a.allocate(16, 1, Kind::Linear), 2 * kPage);
}

TEST(OffsetAllocator, OutOfSpaceAndMisuse) {
  OffsetAllocator a(256);
  EXPECT_FALSE(a.allocate(257, 1));
  EXPECT_EQ(a.allocate(256, 1), 0u);
  EXPECT_FALSE(a.allocate(1, 1));
  EXPECT_THROW(a.allocate(0, 1), InternalError);
  EXPECT_THROW(a.allocate(1, 3), InternalError);
  EXPECT_THROW(a.free(5), InternalError);  // not an allocation
  a.free(0);
  EXPECT_THROW(a.free(0), InternalError);  // double free
}
