// Upload → readback round trips for buffers and images (exact bytes).
#include <gtest/gtest.h>

#include <cstring>

#include "engine/core/error.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/format.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/testing.hpp"

using namespace bounce;
using namespace bounce::gpu;

namespace {
std::vector<std::uint8_t> pattern(std::size_t n, unsigned seed) {
  std::vector<std::uint8_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::uint8_t>((i * 131 + seed * 17 + (i >> 8)) & 0xFF);
  return v;
}
constexpr VkImageUsageFlags kCopyBoth = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
}  // namespace

TEST(BufferImage, DeviceLocalBufferRoundTripThroughStaging) {
  Context& ctx = testkit::sharedContext();
  Buffer b(ctx, {10000,
                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                     VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                 MemoryUsage::GpuOnly, "round trip"});
  auto data = pattern(10000, 1);
  upload(ctx, b, data);
  EXPECT_EQ(readback(ctx, b), data);
  // Partial update at an offset.
  auto patch = pattern(100, 2);
  upload(ctx, b, patch, 5000);
  std::copy(patch.begin(), patch.end(), data.begin() + 5000);
  EXPECT_EQ(readback(ctx, b), data);
  EXPECT_THROW(upload(ctx, b, patch, 9950), InternalError);  // overruns the end
}

TEST(BufferImage, MissingTransferUsageIsACleanError) {
  Context& ctx = testkit::sharedContext();
  Buffer b(ctx, {64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::GpuOnly, "no transfer"});
  try {
    upload(ctx, b, pattern(64, 3));
    FAIL();
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("'no transfer' needs TRANSFER_DST"), std::string::npos) << e.what();
  }
}

TEST(BufferImage, Rgba16fImageRoundTripIsExact) {
  Context& ctx = testkit::sharedContext();
  const std::uint32_t w = 17, h = 9;  // odd sizes catch row-pitch mistakes
  Image img(ctx, {ImageType::Tex2D, VK_FORMAT_R16G16B16A16_SFLOAT, w, h, 1, 1, 1,
                  kCopyBoth | VK_IMAGE_USAGE_SAMPLED_BIT, VK_SAMPLE_COUNT_1_BIT, "rgba16f"});
  std::vector<std::uint16_t> texels;
  for (std::uint32_t i = 0; i < w * h * 4; ++i) texels.push_back(floatToHalf(static_cast<float>(i) * 0.25f - 100.0f));
  upload(ctx, img, bytesOf(texels));
  EXPECT_EQ(img.layout(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  auto back = readback(ctx, img);
  ASSERT_EQ(back.size(), texels.size() * 2);
  EXPECT_EQ(back, std::vector<std::uint8_t>(bytesOf(texels).begin(), bytesOf(texels).end()));
  EXPECT_EQ(img.layout(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);  // restored
  std::uint16_t h0;
  std::memcpy(&h0, back.data() + 8 * (w + 1), 2);  // pixel (1,1), red
  EXPECT_EQ(halfToFloat(h0), static_cast<float>(4 * (w + 1)) * 0.25f - 100.0f);
}

TEST(BufferImage, CubeMipAnd3DRoundTrips) {
  Context& ctx = testkit::sharedContext();
  Image cube(ctx, {ImageType::Cube, VK_FORMAT_R8G8B8A8_UNORM, 8, 8, 1, 4, 6, kCopyBoth | VK_IMAGE_USAGE_SAMPLED_BIT,
                   VK_SAMPLE_COUNT_1_BIT, "cube"});
  auto faces = pattern(4 * 4 * 4 * 6, 4);  // mip 1 is 4×4, six faces
  upload(ctx, cube, faces, 1);
  EXPECT_EQ(readback(ctx, cube, 1), faces);
  ImageView face = cube.createView(VK_IMAGE_VIEW_TYPE_2D, 0, 1, 3, 1, "cube face 3");
  EXPECT_NE(face.handle(), VK_NULL_HANDLE);
  EXPECT_THROW(cube.createView(VK_IMAGE_VIEW_TYPE_2D, 0, 1, 6, 1, "no such face"), InternalError);

  Image vol(ctx, {ImageType::Tex3D, VK_FORMAT_R32_SFLOAT, 5, 4, 3, 1, 1, kCopyBoth | VK_IMAGE_USAGE_STORAGE_BIT,
                  VK_SAMPLE_COUNT_1_BIT, "volume"});
  std::vector<float> voxels(5 * 4 * 3);
  for (std::size_t i = 0; i < voxels.size(); ++i) voxels[i] = static_cast<float>(i) * 1.5f;
  upload(ctx, vol, bytesOf(voxels), 0, VK_IMAGE_LAYOUT_GENERAL);
  auto back = readback(ctx, vol);
  EXPECT_EQ(back, std::vector<std::uint8_t>(bytesOf(voxels).begin(), bytesOf(voxels).end()));
}

TEST(BufferImage, ImageDescriptionsAreChecked) {
  Context& ctx = testkit::sharedContext();
  ImageDesc d{ImageType::Cube, VK_FORMAT_R8G8B8A8_UNORM, 8, 8, 1, 1, 5, VK_IMAGE_USAGE_SAMPLED_BIT,
              VK_SAMPLE_COUNT_1_BIT, "bad cube"};
  EXPECT_THROW(Image(ctx, d), InternalError);
  d = {ImageType::Tex2D, VK_FORMAT_R8G8B8A8_UNORM, 8, 8, 1, 5, 1, VK_IMAGE_USAGE_SAMPLED_BIT, VK_SAMPLE_COUNT_1_BIT,
       "too many mips"};
  EXPECT_THROW(Image(ctx, d), InternalError);
  EXPECT_EQ(fullMipCount(8, 8), 4u);
  EXPECT_EQ(fullMipCount(1, 1), 1u);
  EXPECT_EQ(fullMipCount(640, 360), 10u);
  Image ok(ctx, {ImageType::Tex2D, VK_FORMAT_R8G8B8A8_UNORM, 4, 4, 1, 1, 1, kCopyBoth, VK_SAMPLE_COUNT_1_BIT, "ok"});
  try {
    upload(ctx, ok, pattern(10, 5));
    FAIL();
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("'ok' got 10 bytes (expected 64)"), std::string::npos) << e.what();
  }
}
