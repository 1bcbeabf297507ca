// PNG and PFM writing and reading (no device).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/gpu/image_io.hpp"

using namespace bounce;
using namespace bounce::gpu;

namespace {
std::filesystem::path out(const std::string& name) { return std::filesystem::path(BOUNCE_TEST_OUT) / "gpu" / name; }

void writeRaw(const std::filesystem::path& path, const std::string& header, const std::vector<float>& values) {
  std::vector<std::uint8_t> bytes(header.begin(), header.end());
  const auto* raw = reinterpret_cast<const std::uint8_t*>(values.data());
  bytes.insert(bytes.end(), raw, raw + 4 * values.size());  // host is little-endian (x86)
  writeFileAtomic(path, bytes);
}

std::string errorOf(const std::filesystem::path& path) {
  try {
    readPfm(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(ImageIo, PngRoundTripIsExact) {
  const std::uint32_t w = 5, h = 3;
  std::vector<std::uint8_t> px(w * h * 4);
  // Captures are opaque: PNGs are written as RGB and read back with alpha 255.
  for (std::size_t i = 0; i < px.size(); ++i) px[i] = i % 4 == 3 ? 255 : static_cast<std::uint8_t>(i * 37 + 11);
  writePng(out("rt.png"), w, h, 4, px);
  CpuImage back = readPng(out("rt.png"));
  EXPECT_EQ(back.width, w);
  EXPECT_EQ(back.height, h);
  EXPECT_EQ(back.bytes, px);
  EXPECT_THROW(writePng(out("bad.png"), w, h, 4, std::span(px).first(7)), InternalError);
}

TEST(ImageIo, PfmRoundTripIsExactAndStoresBottomRowFirst) {
  FloatImage img{3, 2, {}};
  for (int i = 0; i < 18; ++i) img.rgb.push_back(i * 0.5f - 2.0f);
  img.rgb[4] = 1e30f;
  writePfm(out("rt.pfm"), img);
  FloatImage back = readPfm(out("rt.pfm"));
  EXPECT_EQ(back.width, 3u);
  EXPECT_EQ(back.height, 2u);
  EXPECT_EQ(back.rgb, img.rgb);

  auto bytes = readFileBytes(out("rt.pfm"));
  std::string header = "PF\n3 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 18 * 4);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + header.size()), header);
  float first;
  std::memcpy(&first, bytes.data() + header.size(), 4);
  EXPECT_EQ(first, img.rgb[9]);  // the file begins with the bottom row (row 1)
}

TEST(ImageIo, PfmReaderAcceptsGreyscaleAndBigEndian) {
  writeRaw(out("grey.pfm"), "Pf\n2 1\n-1.0\n", {0.25f, 4.0f});
  FloatImage g = readPfm(out("grey.pfm"));
  EXPECT_EQ(g.rgb, (std::vector<float>{0.25f, 0.25f, 0.25f, 4.0f, 4.0f, 4.0f}));

  // Scale +1: big-endian floats.
  std::string header = "PF\n1 1\n1\n";
  std::vector<std::uint8_t> bytes(header.begin(), header.end());
  for (float v : {1.0f, -2.0f, 0.5f}) {
    std::uint32_t b;
    std::memcpy(&b, &v, 4);
    for (int k = 3; k >= 0; --k) bytes.push_back(static_cast<std::uint8_t>(b >> (8 * k)));
  }
  writeFileAtomic(out("be.pfm"), bytes);
  EXPECT_EQ(readPfm(out("be.pfm")).rgb, (std::vector<float>{1.0f, -2.0f, 0.5f}));
}

// The PFM and PNG codecs themselves (hostile headers, truncation, NaN) are tested where they live:
// tests/unit/metrics/pfm_test.cpp and image_test.cpp. Here: the adapters keep a reader's error.
TEST(ImageIo, PfmReaderErrorsComeThroughTheAdapter) {
  EXPECT_NE(errorOf(out("does-not-exist.pfm")).find("does-not-exist.pfm"), std::string::npos);
}

TEST(ImageIo, CpuImageConversions) {
  CpuImage bgra{1, 1, PixelFormat::BGRA8, {10, 20, 30, 255}};
  EXPECT_EQ(bgra.rgba8(), (std::vector<std::uint8_t>{30, 20, 10, 255}));
  EXPECT_EQ(bgra.rgbFloat(), (std::vector<float>{30 / 255.0f, 20 / 255.0f, 10 / 255.0f}));
  CpuImage f32{1, 1, PixelFormat::RGBA32F, std::vector<std::uint8_t>(16)};
  float px[4] = {2.0f, 0.5f, -1.0f, 1.0f};
  std::memcpy(f32.bytes.data(), px, 16);
  EXPECT_EQ(f32.rgbFloat(), (std::vector<float>{2.0f, 0.5f, -1.0f}));
  EXPECT_EQ(f32.rgba8(), (std::vector<std::uint8_t>{255, 128, 0, 255}));  // clamped, 0.5·255 rounds up
}
