// Half-float conversion and format facts (no device).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/gpu/format.hpp"

using namespace bounce::gpu;

TEST(Format, HalfConversionIsExactForRepresentableValues) {
  for (float v : {0.0f, 1.0f, -2.5f, 0.25f, 1024.0f, 65504.0f, 6.103515625e-05f /* 2^-14 */,
                  5.9604644775390625e-08f /* 2^-24, smallest subnormal */}) {
    EXPECT_EQ(halfToFloat(floatToHalf(v)), v) << v;
  }
  EXPECT_EQ(floatToHalf(1.0f), 0x3C00);
  EXPECT_EQ(floatToHalf(-2.0f), 0xC000);
  EXPECT_EQ(halfToFloat(0x0001), std::ldexp(1.0f, -24));
  EXPECT_EQ(halfToFloat(0x03FF), std::ldexp(1023.0f, -24));  // largest subnormal
}

TEST(Format, HalfRoundsToNearestEvenAndSaturatesToInf) {
  // 1 + 2^-11 lies exactly between 1 and 1 + 2^-10: ties go to the even mantissa (1.0).
  EXPECT_EQ(floatToHalf(1.0f + std::ldexp(1.0f, -11)), 0x3C00);
  // 1 + 3·2^-11 lies between 1 + 2^-10 (odd) and 1 + 2^-9 (even): goes up.
  EXPECT_EQ(floatToHalf(1.0f + 3 * std::ldexp(1.0f, -11)), 0x3C02);
  EXPECT_EQ(floatToHalf(65520.0f), 0x7C00);  // rounds past the largest half
  EXPECT_EQ(floatToHalf(std::numeric_limits<float>::infinity()), 0x7C00);
  EXPECT_TRUE(std::isnan(halfToFloat(floatToHalf(std::numeric_limits<float>::quiet_NaN()))));
  EXPECT_EQ(floatToHalf(1e-10f), 0x0000);
}

TEST(Format, TexelSizesAndAspects) {
  EXPECT_EQ(texelBytes(VK_FORMAT_R8G8B8A8_UNORM), 4u);
  EXPECT_EQ(texelBytes(VK_FORMAT_R16G16B16A16_SFLOAT), 8u);
  EXPECT_EQ(texelBytes(VK_FORMAT_R32G32B32A32_SFLOAT), 16u);
  EXPECT_EQ(aspectOf(VK_FORMAT_D32_SFLOAT), VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT));
  EXPECT_EQ(aspectOf(VK_FORMAT_R32_SFLOAT), VkImageAspectFlags(VK_IMAGE_ASPECT_COLOR_BIT));
}
