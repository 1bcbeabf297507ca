// Offscreen presenter: render through the frame ring, capture RGBA8 / RGBA16F / RGBA32F.
#include <gtest/gtest.h>

#include "draw_helpers.hpp"
#include "engine/core/error.hpp"
#include "engine/gpu/frames.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"

using namespace bounce::gpu;

namespace {
CpuImage renderAndCapture(Context& ctx, VkFormat format, const testkit::Color& color, int frameCount) {
  OffscreenPresenter presenter(ctx, {24, 16});
  VkExtent2D e = presenter.extent();
  Image target(ctx, {ImageType::Tex2D, format, e.width, e.height, 1, 1, 1,
                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_SAMPLE_COUNT_1_BIT,
                     "offscreen target"});
  testkit::SolidPipeline solid(ctx, format);
  FrameRing frames(ctx);
  for (int i = 0; i < frameCount; ++i) {
    Frame& f = frames.begin();
    testkit::beginColor(ctx, f.cmd, target, testkit::Color{0, 0, 0, 0});
    solid.draw(f.cmd, color);
    ctx.cmdEndRendering(f.cmd);
    if (i == frameCount - 1) presenter.requestCapture();
    EXPECT_TRUE(presenter.present(frames, target));
  }
  EXPECT_EQ(presenter.presentedFrames(), static_cast<std::uint64_t>(frameCount));
  return presenter.capture();
}
}  // namespace

TEST(OffscreenPresenter, CapturesRgba8) {
  CpuImage img = renderAndCapture(testkit::sharedContext(), VK_FORMAT_R8G8B8A8_UNORM, {1, 0, 1, 1}, 3);
  EXPECT_EQ(img.width, 24u);
  EXPECT_EQ(img.height, 16u);
  EXPECT_EQ(img.format, PixelFormat::RGBA8);
  std::vector<std::uint8_t> expected;
  for (int i = 0; i < 24 * 16; ++i) expected.insert(expected.end(), {255, 0, 255, 255});
  EXPECT_EQ(img.bytes, expected);
}

TEST(OffscreenPresenter, CapturesRgba16fAndRgba32fAsLinearFloats) {
  for (VkFormat format : {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT}) {
    CpuImage img = renderAndCapture(testkit::sharedContext(), format, {2.5f, 0.75f, 0.0f, 1.0f}, 2);
    EXPECT_EQ(img.format, format == VK_FORMAT_R16G16B16A16_SFLOAT ? PixelFormat::RGBA16F : PixelFormat::RGBA32F);
    std::vector<float> rgb = img.rgbFloat();
    ASSERT_EQ(rgb.size(), 24u * 16 * 3);
    for (std::size_t i = 0; i < rgb.size(); i += 3) {
      ASSERT_EQ(rgb[i], 2.5f);  // exact in half and float
      ASSERT_EQ(rgb[i + 1], 0.75f);
      ASSERT_EQ(rgb[i + 2], 0.0f);
    }
  }
}

TEST(OffscreenPresenter, UnsupportedCaptureFormatIsAnError) {
  Context& ctx = testkit::sharedContext();
  OffscreenPresenter presenter(ctx, {4, 4});
  Image target(ctx, {ImageType::Tex2D, VK_FORMAT_R32_SFLOAT, 4, 4, 1, 1, 1, VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                     VK_SAMPLE_COUNT_1_BIT, "r32f"});
  FrameRing frames(ctx);
  frames.begin();
  presenter.requestCapture();
  EXPECT_THROW(presenter.present(frames, target), bounce::InternalError);
  frames.submit();
}
