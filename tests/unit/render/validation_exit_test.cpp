// `bounce` turns Vulkan validation errors into exit code 1 (main.cpp → exitCodeAfterCommand), so
// every test that runs `bounce` as a child process with BOUNCE_VALIDATION=1 (capture, profile,
// graph, demo, accuracy, play) fails on one. Here a deliberate validation error — the same wrong
// usage flag as tests/unit/gpu/validation_test.cpp — must flip a successful command's exit code.
#include <gtest/gtest.h>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/testing.hpp"
#include "game/commands.hpp"

using namespace bounce;

TEST(ValidationExit, NoErrorKeepsTheCommandsExitCode) {
  gpu::testkit::sharedContext();
  ASSERT_EQ(gpu::validationErrorsTotal(), 0u);
  EXPECT_EQ(game::exitCodeAfterCommand("capture", 0), 0);
  EXPECT_EQ(game::exitCodeAfterCommand("capture", 2), 2);
}

TEST(ValidationExit, AValidationErrorMakesSuccessExitOne) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  ASSERT_TRUE(ctx.validationEnabled()) << "GPU tests run with BOUNCE_VALIDATION=1";
  gpu::Buffer src(ctx, {256, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, gpu::MemoryUsage::Upload, "copy source"});
  // Deliberately missing VK_BUFFER_USAGE_TRANSFER_DST_BIT (VUID-vkCmdCopyBuffer-dstBuffer-00120).
  gpu::Buffer dst(ctx, {256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Readback, "copy destination"});
  std::fprintf(stderr, "(the next Vulkan validation error is expected)\n");
  gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, 256};
    vkCmdCopyBuffer(cmd, src.handle(), dst.handle(), 1, &region);
  });
  ASSERT_GE(gpu::validationErrorsTotal(), 1u);

  ::testing::internal::CaptureStderr();
  const int success = game::exitCodeAfterCommand("capture", 0);
  const int badInput = game::exitCodeAfterCommand("capture", 2);
  const std::string err = ::testing::internal::GetCapturedStderr();
  ::testing::internal::CaptureStderr();
  const int failed = game::exitCodeAfterCommand("play", 1);
  const std::string errFailed = ::testing::internal::GetCapturedStderr();

  EXPECT_EQ(success, 1);
  EXPECT_EQ(badInput, 1);
  EXPECT_EQ(failed, 1);
  // One line per call that did not already fail; none for the command that did (it said why).
  const std::string line = "bounce capture: " + std::to_string(gpu::validationErrorsTotal()) +
                           " Vulkan validation error(s), printed above\n";
  EXPECT_EQ(err, line + line);
  EXPECT_EQ(errFailed, "");
  // Expected: clear both counters so the listener does not fail this test.
  ctx.resetValidationErrorCount();
  gpu::resetValidationErrorsTotal();
}
