#pragma once
// CPU images and the two capture formats:
//  - PNG (8-bit RGB/RGBA, via stb_image_write) for tonemapped sRGB frames;
//  - PFM (portable float map, "PF" = 3 channels float32) for linear radiance. The header is
//    "PF\n<width> <height>\n<scale>\n" with a negative scale meaning little-endian; rows are
//    stored bottom to top. We always write scale -1 (little-endian, unit scale).
// Every reader error is an InputError "file: where: what (expected …)".
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace bounce::gpu {

enum class PixelFormat { RGBA8, BGRA8, RGBA16F, RGBA32F };
std::uint32_t pixelBytes(PixelFormat format);

// Pixels as read back from the GPU: rows top to bottom, tightly packed.
struct CpuImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  PixelFormat format = PixelFormat::RGBA8;
  std::vector<std::uint8_t> bytes;

  // Linear float RGB, rows top to bottom (8-bit channels map to value/255, alpha dropped).
  std::vector<float> rgbFloat() const;
  // 8-bit RGBA (BGRA swizzled; float channels clamped to [0,1], ×255, rounded — no tonemapping).
  std::vector<std::uint8_t> rgba8() const;
};

// Float RGB image, rows top to bottom (PFM files store them the other way; the I/O flips).
struct FloatImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<float> rgb;  // 3 · width · height
};

// `channels` is 1..4; `pixels` holds width·height·channels bytes, rows top to bottom.
void writePng(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height, std::uint32_t channels,
              std::span<const std::uint8_t> pixels);
// Reads an 8-bit PNG as RGBA (tests; golden images).
CpuImage readPng(const std::filesystem::path& path);

void writePfm(const std::filesystem::path& path, const FloatImage& image);
// Accepts "PF" (RGB) and "Pf" (greyscale, expanded to RGB), either endianness; checks the
// header, the dimensions against the file size, and rejects NaN/Inf pixels.
FloatImage readPfm(const std::filesystem::path& path);

}  // namespace bounce::gpu
