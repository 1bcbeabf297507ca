#include "engine/core/image.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <memory>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"

namespace bounce {

ImageRGB::ImageRGB(int w, int h, glm::vec3 fill) : width(w), height(h) {
  if (w < 0 || h < 0)
    throw InternalError("ImageRGB: negative size " + std::to_string(w) + "x" + std::to_string(h));
  pixels.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill);
}

ImageRGB difference(const ImageRGB& a, const ImageRGB& b) {
  if (!a.sameSize(b))
    throw InternalError("difference: image sizes differ (" + std::to_string(a.width) + "x" + std::to_string(a.height) +
                        " vs " + std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
  ImageRGB out(a.width, a.height);
  for (std::size_t i = 0; i < a.pixels.size(); ++i) out.pixels[i] = a.pixels[i] - b.pixels[i];
  return out;
}

ImageRGB scaled(const ImageRGB& img, float s) {
  ImageRGB out = img;
  for (auto& p : out.pixels) p *= s;
  return out;
}

double meanValue(const ImageRGB& img) {
  if (img.empty()) return 0.0;
  double sum = 0.0;
  for (const auto& p : img.pixels) sum += double(p.r) + double(p.g) + double(p.b);
  return sum / (3.0 * static_cast<double>(img.pixels.size()));
}

ImageSrgb8::ImageSrgb8(int w, int h, glm::u8vec3 fill) : width(w), height(h) {
  if (w < 0 || h < 0)
    throw InternalError("ImageSrgb8: negative size " + std::to_string(w) + "x" + std::to_string(h));
  rgb.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = fill.r;
    rgb[i + 1] = fill.g;
    rgb[i + 2] = fill.b;
  }
}

glm::u8vec3 ImageSrgb8::at(int x, int y) const {
  assert(x >= 0 && x < width && y >= 0 && y < height);
  const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

void ImageSrgb8::set(int x, int y, glm::u8vec3 c) {
  assert(x >= 0 && x < width && y >= 0 && y < height);
  const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
  rgb[i] = c.r;
  rgb[i + 1] = c.g;
  rgb[i + 2] = c.b;
}

float linearToSrgb(float c) {
  // IEC 61966-2-1: linear segment below 0.0031308 avoids the infinite slope of the power curve.
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float srgbToLinear(float e) { return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f); }

std::uint8_t encodeSrgb8(float linear) {
  if (std::isnan(linear)) return 0;
  const float e = linearToSrgb(std::clamp(linear, 0.0f, 1.0f));
  return static_cast<std::uint8_t>(std::lround(e * 255.0f));
}

ImageSrgb8 toSrgb8(const ImageRGB& img, float exposure) {
  ImageSrgb8 out(img.width, img.height);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    const glm::vec3 c = img.pixels[i] * exposure;
    out.rgb[3 * i] = encodeSrgb8(c.r);
    out.rgb[3 * i + 1] = encodeSrgb8(c.g);
    out.rgb[3 * i + 2] = encodeSrgb8(c.b);
  }
  return out;
}

ImageRGB fromSrgb8(const ImageSrgb8& img) {
  ImageRGB out(img.width, img.height);
  for (std::size_t i = 0; i < out.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) out.pixels[i][c] = srgbToLinear(img.rgb[3 * i + c] / 255.0f);
  return out;
}

// ---------------------------------------------------------------------------------------------
// PFM

namespace {

std::uint32_t byteSwap(std::uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

// Stores a float's bits as little-endian bytes whatever the host order.
void putFloatLE(std::uint8_t* dst, float f) {
  std::uint32_t bits = std::bit_cast<std::uint32_t>(f);
  if constexpr (std::endian::native == std::endian::big) bits = byteSwap(bits);
  std::memcpy(dst, &bits, 4);
}

float getFloat(const std::uint8_t* src, bool littleEndian) {
  std::uint32_t bits;
  std::memcpy(&bits, src, 4);
  const bool hostLittle = std::endian::native == std::endian::little;
  if (littleEndian != hostLittle) bits = byteSwap(bits);
  return std::bit_cast<float>(bits);
}

bool isPfmSpace(std::uint8_t c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Reads the header tokens one by one, remembering byte offsets for error messages.
class HeaderReader {
 public:
  HeaderReader(std::span<const std::uint8_t> bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  // The next whitespace-separated token. Tokens are short; a long run of non-space bytes is
  // binary garbage, reported as such rather than scanned to the end of a large file.
  std::string token(const char* what, const char* expected) {
    while (pos_ < bytes_.size() && isPfmSpace(bytes_[pos_])) ++pos_;
    start_ = pos_;
    std::string tok;
    while (pos_ < bytes_.size() && !isPfmSpace(bytes_[pos_])) {
      if (tok.size() >= kMaxToken) fail(std::string(what) + " is not a short text token", expected);
      tok.push_back(static_cast<char>(bytes_[pos_++]));
    }
    if (tok.empty()) fail(std::string("file ends before the ") + what, expected);
    return tok;
  }

  // The single whitespace byte between the scale token and the payload.
  void endOfHeader() {
    if (pos_ >= bytes_.size() || !isPfmSpace(bytes_[pos_]))
      fail("no whitespace after the scale", "one newline, then the float payload");
    ++pos_;
  }

  [[noreturn]] void fail(const std::string& what, const std::string& expected) const {
    throwInputError(name_, "byte " + std::to_string(start_), what, expected);
  }

  std::size_t pos() const { return pos_; }

 private:
  static constexpr std::size_t kMaxToken = 32;
  std::span<const std::uint8_t> bytes_;
  const std::string& name_;
  std::size_t pos_ = 0;
  std::size_t start_ = 0;
};

// A dimension: decimal digits only (no sign), value in 1..kMaxImageDimension.
int parseDimension(HeaderReader& r, const char* what) {
  const std::string expected = std::string(what) + " as an integer in 1.." + std::to_string(kMaxImageDimension);
  const std::string tok = r.token(what, expected.c_str());
  long long v = 0;
  for (char c : tok) {
    if (c < '0' || c > '9') r.fail(std::string(what) + " '" + tok + "' is not a positive integer", expected);
    v = v * 10 + (c - '0');
    if (v > kMaxImageDimension) r.fail(std::string(what) + " " + tok + " is too large", expected);
  }
  if (v < 1) r.fail(std::string(what) + " is 0", expected);
  return static_cast<int>(v);
}

}  // namespace

std::vector<std::uint8_t> encodePfm(const ImageRGB& img) {
  if (img.empty()) throw InternalError("writePfm: empty image");
  const std::string header = "PF\n" + std::to_string(img.width) + " " + std::to_string(img.height) + "\n-1.0\n";
  std::vector<std::uint8_t> bytes(header.size() + img.pixels.size() * 12);
  std::memcpy(bytes.data(), header.data(), header.size());
  std::uint8_t* dst = bytes.data() + header.size();
  for (int row = 0; row < img.height; ++row) {
    const int y = img.height - 1 - row;  // PFM stores the bottom row first
    for (int x = 0; x < img.width; ++x, dst += 12) {
      const glm::vec3& p = img.at(x, y);
      putFloatLE(dst, p.r);
      putFloatLE(dst + 4, p.g);
      putFloatLE(dst + 8, p.b);
    }
  }
  return bytes;
}

void writePfm(const std::filesystem::path& path, const ImageRGB& img) { writeFileAtomic(path, encodePfm(img)); }

ImageRGB parsePfm(std::span<const std::uint8_t> bytes, const std::string& name, const PfmReadOptions& options) {
  HeaderReader r(bytes, name);
  const std::string magic = r.token("magic", "'PF' (RGB) or 'Pf' (grey)");
  if (magic != "PF" && magic != "Pf")
    r.fail("not a PFM file (magic '" + magic.substr(0, 8) + "')", "'PF' (RGB) or 'Pf' (grey)");
  const int channels = magic == "PF" ? 3 : 1;
  const int width = parseDimension(r, "width");
  const int height = parseDimension(r, "height");

  const std::string scaleTok = r.token("scale", "a non-zero number, negative for little-endian");
  // from_chars: locale-independent ("-1.0" must parse the same under a German locale).
  double scale = 0.0;
  const auto [end, ec] = std::from_chars(scaleTok.data(), scaleTok.data() + scaleTok.size(), scale);
  if (ec != std::errc() || end != scaleTok.data() + scaleTok.size())
    r.fail("scale '" + scaleTok + "' is not a number", "a non-zero number, negative for little-endian");
  if (!std::isfinite(scale) || scale == 0.0)
    r.fail("scale '" + scaleTok + "' is zero or not finite", "a non-zero number, negative for little-endian");
  r.endOfHeader();
  const bool littleEndian = scale < 0.0;

  // Both dimensions are ≤ 16384, so this product fits easily in 64 bits.
  const std::uint64_t payload = std::uint64_t(width) * std::uint64_t(height) * std::uint64_t(channels) * 4u;
  const std::uint64_t available = bytes.size() - r.pos();
  if (available != payload) {
    throwInputError(name, "byte " + std::to_string(r.pos()),
                    std::string(available < payload ? "payload truncated" : "extra bytes after payload") + ": " +
                        std::to_string(available) + " bytes",
                    std::to_string(payload) + " bytes for " + std::to_string(width) + "x" + std::to_string(height) +
                        "x" + std::to_string(channels) + " floats");
  }

  ImageRGB img(width, height);
  const std::uint8_t* src = bytes.data() + r.pos();
  static const char* kChannelNames[] = {"R", "G", "B"};
  for (int row = 0; row < height; ++row) {
    const int y = height - 1 - row;
    for (int x = 0; x < width; ++x) {
      glm::vec3& p = img.at(x, y);
      for (int c = 0; c < channels; ++c, src += 4) {
        const float v = getFloat(src, littleEndian);
        if (options.requireFinite && !std::isfinite(v))
          throwInputError(name, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")" +
                                    (channels == 3 ? std::string(" channel ") + kChannelNames[c] : std::string()),
                          std::string("value is ") + (std::isnan(v) ? "NaN" : "infinite"), "finite floats");
        p[c] = v;
      }
      if (channels == 1) p = glm::vec3(p.r);
    }
  }
  return img;
}

ImageRGB readPfm(const std::filesystem::path& path, const PfmReadOptions& options) {
  const auto bytes = readFileBytes(path);
  return parsePfm(bytes, path.string(), options);
}

// ---------------------------------------------------------------------------------------------
// PNG

void writePng(const std::filesystem::path& path, const ImageSrgb8& img) {
  if (img.width <= 0 || img.height <= 0 || img.rgb.size() != std::size_t(img.width) * img.height * 3)
    throw InternalError(path.string() + ": writePng: empty or inconsistent image");
  std::vector<std::uint8_t> encoded;
  auto append = [](void* ctx, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(ctx);
    const auto* p = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), p, p + size);
  };
  // Encoding to memory, then writeFileAtomic, so a crash never leaves half a PNG behind.
  if (!stbi_write_png_to_func(append, &encoded, img.width, img.height, 3, img.rgb.data(), img.width * 3))
    throw InternalError(path.string() + ": PNG encoding failed");
  writeFileAtomic(path, encoded);
}

ImageSrgb8 readPng(const std::filesystem::path& path) {
  const auto bytes = readFileBytes(path);
  if (bytes.size() > std::size_t(INT32_MAX)) throwInputError(path.string(), "", "file too large", "< 2 GiB");
  int w = 0, h = 0, comp = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> data(
      stbi_load_from_memory(bytes.data(), static_cast<int>(bytes.size()), &w, &h, &comp, 3), stbi_image_free);
  if (!data) {
    const char* why = stbi_failure_reason();
    throwInputError(path.string(), "", std::string("cannot decode image: ") + (why ? why : "unknown reason"),
                    "a PNG file");
  }
  if (w < 1 || h < 1 || w > kMaxImageDimension || h > kMaxImageDimension)
    throwInputError(path.string(), "header", "size " + std::to_string(w) + "x" + std::to_string(h),
                    "dimensions in 1.." + std::to_string(kMaxImageDimension));
  ImageSrgb8 img(w, h);
  std::memcpy(img.rgb.data(), data.get(), img.rgb.size());
  return img;
}

}  // namespace bounce
