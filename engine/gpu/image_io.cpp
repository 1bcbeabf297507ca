#include "engine/gpu/image_io.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/gpu/format.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

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

void writePng(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height, std::uint32_t channels,
              std::span<const std::uint8_t> pixels) {
  if (channels < 1 || channels > 4 || width == 0 || height == 0 ||
      pixels.size() != std::size_t(width) * height * channels)
    throw InternalError("writePng " + path.string() + ": " + std::to_string(pixels.size()) + " bytes for " +
                        std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(channels));
  // Encode in memory, then write atomically (a capture is never left half-written).
  std::vector<std::uint8_t> encoded;
  auto sink = [](void* ctx, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(ctx);
    out->insert(out->end(), static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
  };
  int ok = stbi_write_png_to_func(sink, &encoded, static_cast<int>(width), static_cast<int>(height),
                                  static_cast<int>(channels), pixels.data(), static_cast<int>(width * channels));
  if (!ok) throw InternalError("writePng " + path.string() + ": encoding failed");
  writeFileAtomic(path, encoded);
}

CpuImage readPng(const std::filesystem::path& path) {
  std::vector<std::uint8_t> file = readFileBytes(path);
  int w = 0, h = 0, n = 0;
  stbi_uc* data = stbi_load_from_memory(file.data(), static_cast<int>(file.size()), &w, &h, &n, 4);
  if (!data) throwInputError(path.string(), "", std::string("not a readable image: ") + stbi_failure_reason(), "PNG");
  CpuImage img{static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h), PixelFormat::RGBA8, {}};
  img.bytes.assign(data, data + std::size_t(w) * h * 4);
  stbi_image_free(data);
  return img;
}

void writePfm(const std::filesystem::path& path, const FloatImage& image) {
  std::size_t n = std::size_t(image.width) * image.height;
  if (image.width == 0 || image.height == 0 || image.rgb.size() != 3 * n)
    throw InternalError("writePfm " + path.string() + ": " + std::to_string(image.rgb.size()) + " floats for " +
                        std::to_string(image.width) + "x" + std::to_string(image.height));
  std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1\n";
  std::vector<std::uint8_t> out(header.begin(), header.end());
  out.reserve(header.size() + 12 * n);
  for (std::uint32_t row = image.height; row-- > 0;) {  // bottom row first
    const float* src = image.rgb.data() + std::size_t(row) * image.width * 3;
    for (std::size_t k = 0; k < std::size_t(image.width) * 3; ++k) {
      std::uint32_t bits = std::bit_cast<std::uint32_t>(src[k]);
      if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
      for (int b = 0; b < 4; ++b) out.push_back(static_cast<std::uint8_t>(bits >> (8 * b)));
    }
  }
  writeFileAtomic(path, out);
}

FloatImage readPfm(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::vector<std::uint8_t> bytes = readFileBytes(path);
  std::size_t pos = 0;
  // Header tokens are separated by whitespace; exactly one whitespace byte precedes the data.
  auto token = [&](const char* what) {
    while (pos < bytes.size() && std::isspace(bytes[pos])) ++pos;
    std::size_t start = pos;
    while (pos < bytes.size() && !std::isspace(bytes[pos])) ++pos;
    if (start == pos || pos - start > 32)
      throwInputError(file, "header byte " + std::to_string(start), std::string("missing ") + what, "a PFM header");
    return std::string(bytes.begin() + start, bytes.begin() + pos);
  };
  std::string magic = token("magic");
  if (magic != "PF" && magic != "Pf") throwInputError(file, "header", "magic is '" + magic + "'", "PF or Pf");
  int channels = magic == "PF" ? 3 : 1;
  auto number = [&](const char* what, std::uint32_t max) {
    std::string t = token(what);
    std::size_t used = 0;
    unsigned long v = 0;
    try {
      v = std::stoul(t, &used);
    } catch (...) {
      used = 0;
    }
    if (used != t.size() || v == 0 || v > max)
      throwInputError(file, "header", std::string(what) + " is '" + t + "'", "1.." + std::to_string(max));
    return static_cast<std::uint32_t>(v);
  };
  constexpr std::uint32_t kMaxSide = 1u << 15;  // 32768 px: far beyond any capture
  std::uint32_t w = number("width", kMaxSide), h = number("height", kMaxSide);
  std::string scaleText = token("scale");
  double scale = 0.0;
  try {
    std::size_t used = 0;
    scale = std::stod(scaleText, &used);
    if (used != scaleText.size()) scale = 0.0;
  } catch (...) {
    scale = 0.0;
  }
  if (scale == 0.0 || !std::isfinite(scale))
    throwInputError(file, "header", "scale is '" + scaleText + "'", "a non-zero number (negative = little-endian)");
  bool little = scale < 0.0;
  if (pos >= bytes.size() || !std::isspace(bytes[pos]))
    throwInputError(file, "header", "no whitespace after the scale", "one byte before the pixels");
  ++pos;
  std::size_t count = std::size_t(w) * h * channels;
  if (bytes.size() - pos != 4 * count)
    throwInputError(file, "byte " + std::to_string(pos),
                    std::to_string(bytes.size() - pos) + " bytes of pixels for " + std::to_string(w) + "x" +
                        std::to_string(h),
                    std::to_string(4 * count) + " bytes");
  FloatImage img{w, h, std::vector<float>(std::size_t(w) * h * 3)};
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* p = bytes.data() + pos + 4 * i;
    std::uint32_t bits = little ? (p[0] | p[1] << 8 | p[2] << 16 | std::uint32_t(p[3]) << 24)
                                : (std::uint32_t(p[0]) << 24 | p[1] << 16 | p[2] << 8 | p[3]);
    float v = std::bit_cast<float>(bits);
    if (!std::isfinite(v))
      throwInputError(file, "pixel " + std::to_string(i / channels), "value is not finite", "finite floats");
    std::size_t pixel = i / channels;
    std::uint32_t fileRow = static_cast<std::uint32_t>(pixel / w), col = static_cast<std::uint32_t>(pixel % w);
    std::size_t dst = (std::size_t(h - 1 - fileRow) * w + col) * 3;
    if (channels == 3)
      img.rgb[dst + i % 3] = v;
    else
      img.rgb[dst] = img.rgb[dst + 1] = img.rgb[dst + 2] = v;
  }
  return img;
}

}  // namespace bounce::gpu
