#pragma once
// Images for accuracy work: linear float RGB (what the renderer and the path tracer produce,
// stored as PFM, compared by metrics.hpp) and 8-bit sRGB (what people look at: PNG captures,
// heat maps, side-by-side panels).
//
// PFM ("portable float map", Debevec's HDRShop format; netpbm documents it as "PFM"):
//   "PF\n<width> <height>\n<scale>\n" then width·height·3 IEEE-754 binary32 values,
//   rows from the BOTTOM of the image to the top, pixels left to right, RGB interleaved.
//   A negative scale means little-endian floats, a positive one big-endian; its magnitude is a
//   conventional "scale factor" that readers (netpbm, OpenImageIO, ours) do not apply.
//   "Pf" is the one-channel variant; we read it (grey replicated to RGB) and never write it.
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

// Linear RGB radiance (renderer units), row-major, row 0 is the TOP row (as on screen).
struct ImageRGB {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;

  ImageRGB() = default;
  // Throws InternalError for negative sizes (a caller bug, not bad input).
  ImageRGB(int w, int h, glm::vec3 fill = glm::vec3(0.0f));

  std::size_t pixelCount() const { return pixels.size(); }
  bool empty() const { return pixels.empty(); }
  bool sameSize(const ImageRGB& o) const { return width == o.width && height == o.height; }
  // Bounds are asserted in debug builds only: callers loop over [0,width)×[0,height).
  glm::vec3& at(int x, int y) { return pixels[index(x, y)]; }
  const glm::vec3& at(int x, int y) const { return pixels[index(x, y)]; }

 private:
  std::size_t index(int x, int y) const {
    assert(x >= 0 && x < width && y >= 0 && y < height);
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
  }
};

// a − b, pixel by pixel (InternalError when sizes differ). Used for "with minus without".
ImageRGB difference(const ImageRGB& a, const ImageRGB& b);
// Every channel multiplied by s.
ImageRGB scaled(const ImageRGB& img, float s);
// Mean over pixels and channels (double accumulation); 0 for an empty image.
double meanValue(const ImageRGB& img);

// 8-bit sRGB-encoded RGB, row-major, top row first, 3 bytes per pixel.
struct ImageSrgb8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;

  ImageSrgb8() = default;
  ImageSrgb8(int w, int h, glm::u8vec3 fill = glm::u8vec3(0));

  std::size_t pixelCount() const { return rgb.size() / 3; }
  glm::u8vec3 at(int x, int y) const;
  void set(int x, int y, glm::u8vec3 c);
};

// sRGB transfer function (IEC 61966-2-1): linear [0,1] ↔ encoded [0,1].
float linearToSrgb(float linear);
float srgbToLinear(float encoded);
// Linear value → 8-bit sRGB code: clamps to [0,1] (values above 1 saturate, +inf gives 255),
// rounds to nearest; NaN gives 0 so one bad pixel cannot poison a whole capture's encode.
std::uint8_t encodeSrgb8(float linear);

// Multiplies by `exposure`, then encodeSrgb8 per channel. No tone curve: the panels that use
// it (reference vs. technique) must be compared under the same simple, invertible mapping.
ImageSrgb8 toSrgb8(const ImageRGB& img, float exposure = 1.0f);
// Decodes 8-bit sRGB back to linear floats.
ImageRGB fromSrgb8(const ImageSrgb8& img);

struct PfmReadOptions {
  // Reject NaN and ±inf (the default): a reference with one NaN makes every metric NaN.
  bool requireFinite = true;
};

// Largest accepted width or height. 16384 is Vulkan's common maxImageDimension2D; it also
// caps a hostile header's payload at 16384²·12 bytes before anything is allocated.
inline constexpr int kMaxImageDimension = 16384;

// Writes little-endian PFM (scale -1.0) atomically. Throws InternalError for an empty image.
void writePfm(const std::filesystem::path& path, const ImageRGB& img);
// Encodes PFM into bytes (what writePfm writes).
std::vector<std::uint8_t> encodePfm(const ImageRGB& img);

// Reads a PFM file. Every field is validated (magic, dimensions within 1..kMaxImageDimension,
// scale a finite non-zero number, payload exactly width·height·channels·4 bytes, values finite
// unless allowed); any violation throws InputError "file: where: what (expected …)".
ImageRGB readPfm(const std::filesystem::path& path, const PfmReadOptions& options = {});
// The same from bytes already in memory; `name` is the file name used in errors.
ImageRGB parsePfm(std::span<const std::uint8_t> bytes, const std::string& name,
                  const PfmReadOptions& options = {});

// PNG through stb_image_write / stb_image (Debian's libstb). Writes atomically; throws
// InternalError on encode failure (an empty image) and InputError for an unreadable PNG.
void writePng(const std::filesystem::path& path, const ImageSrgb8& img);
// Any PNG stb_image can decode, converted to 8-bit RGB (alpha dropped, grey replicated).
ImageSrgb8 readPng(const std::filesystem::path& path);

}  // namespace bounce
