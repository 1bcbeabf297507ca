// ImageRGB / ImageSrgb8 helpers, the sRGB transfer function and PNG round trips.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/core/image.hpp"
#include "test_util.hpp"

namespace bounce::ref {
namespace {

TEST(Image, RowMajorTopRowFirst) {
  ImageRGB img(3, 2, glm::vec3(0.5f));
  EXPECT_EQ(img.pixelCount(), 6u);
  img.at(2, 1) = glm::vec3(1, 2, 3);
  EXPECT_EQ(img.pixels[5], glm::vec3(1, 2, 3));  // index y*width + x = 1*3 + 2
  EXPECT_EQ(img.pixels[0], glm::vec3(0.5f));
  EXPECT_THROW(ImageRGB(-1, 2), InternalError);
}

TEST(Image, DifferenceScaledMean) {
  ImageRGB a(2, 1), b(2, 1);
  a.pixels = {{1, 2, 3}, {4, 5, 6}};
  b.pixels = {{1, 1, 1}, {2, 2, 2}};
  const ImageRGB d = difference(a, b);
  EXPECT_EQ(d.pixels[0], glm::vec3(0, 1, 2));
  EXPECT_EQ(d.pixels[1], glm::vec3(2, 3, 4));
  EXPECT_EQ(scaled(a, 2.0f).pixels[1], glm::vec3(8, 10, 12));
  EXPECT_DOUBLE_EQ(meanValue(a), 21.0 / 6.0);
  EXPECT_EQ(meanValue(ImageRGB()), 0.0);
  EXPECT_THROW(difference(a, ImageRGB(1, 2)), InternalError);
}

TEST(Srgb, EncodeKnownValues) {
  EXPECT_EQ(encodeSrgb8(0.0f), 0);
  EXPECT_EQ(encodeSrgb8(1.0f), 255);
  EXPECT_EQ(encodeSrgb8(4.0f), 255);   // saturates
  EXPECT_EQ(encodeSrgb8(-1.0f), 0);    // clamps
  EXPECT_EQ(encodeSrgb8(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(encodeSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  // 1.055·0.5^(1/2.4) − 0.055 = 0.735357 → 187.52 → 188.
  EXPECT_EQ(encodeSrgb8(0.5f), 188);
  // The two segments meet at 0.0031308 ↔ 0.04045 (10.31 → 10).
  EXPECT_EQ(encodeSrgb8(0.0031308f), 10);
  EXPECT_NEAR(linearToSrgb(0.0031308f), 0.04045f, 1e-6f);
}

TEST(Srgb, EveryCodeRoundTrips) {
  for (int k = 0; k < 256; ++k) EXPECT_EQ(encodeSrgb8(srgbToLinear(k / 255.0f)), k) << "code " << k;
}

TEST(Srgb, ToSrgb8AppliesExposure) {
  ImageRGB img(1, 1, glm::vec3(0.25f, 0.5f, 2.0f));
  const ImageSrgb8 e = toSrgb8(img, 2.0f);
  EXPECT_EQ(e.at(0, 0), glm::u8vec3(188, 255, 255));
  const ImageRGB back = fromSrgb8(toSrgb8(ImageRGB(1, 1, glm::vec3(1.0f))));
  EXPECT_EQ(back.pixels[0], glm::vec3(1.0f));
}

TEST(Png, RoundTripIsExact) {
  const auto dir = test::testDir();
  ImageSrgb8 img(5, 3);
  for (std::size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = static_cast<std::uint8_t>(i * 37 + 11);
  writePng(dir / "a.png", img);
  const ImageSrgb8 back = readPng(dir / "a.png");
  EXPECT_EQ(back.width, 5);
  EXPECT_EQ(back.height, 3);
  EXPECT_EQ(back.rgb, img.rgb);
}

TEST(Png, GarbageIsInputError) {
  const auto dir = test::testDir();
  std::ofstream(dir / "bad.png", std::ios::binary) << "this is not a png";
  try {
    readPng(dir / "bad.png");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("bad.png: cannot decode image"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos);
  }
  EXPECT_THROW(readPng(dir / "missing.png"), InputError);
  EXPECT_THROW(writePng(dir / "empty.png", ImageSrgb8()), InternalError);
}

}  // namespace
}  // namespace bounce::ref
