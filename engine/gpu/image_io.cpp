#include "engine/gpu/image_io.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/image.hpp"
#include "engine/gpu/format.hpp"


namespace bounce::gpu {

std::uint32_t pixelBytes(PixelFormat f) {
  switch (f) {
    case PixelFormat::RGBA8:
    case PixelFormat::BGRA8: return 4;
    case PixelFormat::RGBA16F: return 8;
    case PixelFormat::RGBA32F: return 16;
  }
  return 0;
}

namespace {
// Channel c (0..3, RGBA order) of pixel i as a float.
float channel(const CpuImage& img, std::size_t i, int c) {
  const std::uint8_t* p = img.bytes.data() + i * pixelBytes(img.format);
  switch (img.format) {
    case PixelFormat::RGBA8: return p[c] / 255.0f;
    case PixelFormat::BGRA8: return p[c == 3 ? 3 : 2 - c] / 255.0f;
    case PixelFormat::RGBA16F: {
      std::uint16_t h;
      std::memcpy(&h, p + 2 * c, 2);
      return halfToFloat(h);
    }
    case PixelFormat::RGBA32F: {
      float f;
      std::memcpy(&f, p + 4 * c, 4);
      return f;
    }
  }
  return 0.0f;
}

void checkSize(const CpuImage& img) {
  if (img.bytes.size() != std::size_t(img.width) * img.height * pixelBytes(img.format))
    throw InternalError("CpuImage: " + std::to_string(img.bytes.size()) + " bytes for " + std::to_string(img.width) +
                        "x" + std::to_string(img.height));
}
}  // namespace

std::vector<float> CpuImage::rgbFloat() const {
  checkSize(*this);
  std::size_t n = std::size_t(width) * height;
  std::vector<float> out(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) out[3 * i + c] = channel(*this, i, c);
  return out;
}

std::vector<std::uint8_t> CpuImage::rgba8() const {
  checkSize(*this);
  std::size_t n = std::size_t(width) * height;
  std::vector<std::uint8_t> out(4 * n);
  if (format == PixelFormat::RGBA8) return bytes;
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) {
      float v = channel(*this, i, c);
      v = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
      out[4 * i + c] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
  return out;
}

// PNG and PFM go through the engine's one image codec (engine/core/image.hpp); these adapters only
// convert between the GPU readback layouts and its image types.

void writePng(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height, std::uint32_t channels,
              std::span<const std::uint8_t> pixels) {
  if (channels < 1 || channels > 4 || pixels.size() != std::size_t(width) * height * channels)
    throw InternalError("writePng: " + path.string() + ": pixel buffer does not match " + std::to_string(width) + "x" +
                        std::to_string(height) + "x" + std::to_string(channels));
  ImageSrgb8 img(width, height);
  for (std::size_t i = 0; i < std::size_t(width) * height; ++i)
    for (std::uint32_t c = 0; c < 3; ++c)  // grey (1–2 channels) is replicated; alpha is dropped
      img.rgb[i * 3 + c] = pixels[i * channels + (channels < 3 ? 0 : c)];
  bounce::writePng(path, img);
}

CpuImage readPng(const std::filesystem::path& path) {
  const ImageSrgb8 img = bounce::readPng(path);
  CpuImage out{std::uint32_t(img.width), std::uint32_t(img.height), PixelFormat::RGBA8, {}};
  out.bytes.resize(std::size_t(img.width) * img.height * 4);
  for (std::size_t i = 0; i < std::size_t(img.width) * img.height; ++i) {
    for (int c = 0; c < 3; ++c) out.bytes[i * 4 + c] = img.rgb[i * 3 + c];
    out.bytes[i * 4 + 3] = 255;
  }
  return out;
}

void writePfm(const std::filesystem::path& path, const FloatImage& image) {
  if (image.rgb.size() != std::size_t(image.width) * image.height * 3)
    throw InternalError("writePfm: " + path.string() + ": pixel buffer does not match the size");
  ImageRGB img(int(image.width), int(image.height));
  std::memcpy(img.pixels.data(), image.rgb.data(), image.rgb.size() * sizeof(float));
  bounce::writePfm(path, img);
}

FloatImage readPfm(const std::filesystem::path& path) {
  const ImageRGB img = bounce::readPfm(path);
  FloatImage out{std::uint32_t(img.width), std::uint32_t(img.height), {}};
  out.rgb.resize(img.pixels.size() * 3);
  std::memcpy(out.rgb.data(), img.pixels.data(), out.rgb.size() * sizeof(float));
  return out;
}

}  // namespace bounce::gpu
