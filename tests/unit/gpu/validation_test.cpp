// The validation counter sees a deliberate error (so "zero errors" in every other test means
// something).
#include <gtest/gtest.h>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/testing.hpp"

using namespace bounce::gpu;

TEST(Validation, WrongUsageFlagIsCounted) {
  Context& ctx = testkit::sharedContext();
  if (!ctx.validationEnabled()) {
    ASSERT_FALSE(testkit::runningAsGpuTest()) << "GPU tests must run with validation";
    GTEST_SKIP() << "validation is off (set BOUNCE_VALIDATION=1)";
  }
  Buffer src(ctx, {256, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "copy source"});
  // Deliberately missing VK_BUFFER_USAGE_TRANSFER_DST_BIT (VUID-vkCmdCopyBuffer-dstBuffer-00120).
  Buffer dst(ctx, {256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Readback, "copy destination"});
  std::uint64_t before = ctx.validationErrorCount();
  ASSERT_EQ(validationErrorsTotal(), 0u);
  std::fprintf(stderr, "(the next Vulkan validation error is expected)\n");
  submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, 256};
    vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &region);
  });
  EXPECT_GE(ctx.validationErrorCount(), before + 1);
  EXPECT_GE(validationErrorsTotal(), 1u);
  // Expected: clear both counters so the listener does not fail this test.
  ctx.resetValidationErrorCount();
  resetValidationErrorsTotal();
}
