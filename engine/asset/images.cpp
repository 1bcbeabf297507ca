// Image decoding with stb_image (Debian's libstb provides the implementation).
#include "engine/asset/images.hpp"

#include "engine/core/error.hpp"

#include <stb_image.h>

#include <climits>
#include <cstring>

namespace bounce::asset::detail {

Texture decodeImage(std::span<const std::uint8_t> encoded, bool decode, const std::string& file, const std::string& where) {
  if (encoded.empty()) throwInputError(file, where, "image data is empty", "PNG or JPEG bytes");
  if (encoded.size() > std::size_t(INT_MAX)) throwInputError(file, where, "image data larger than 2 GiB", "a smaller image");
  int w = 0, h = 0, channels = 0;
  const auto* data = reinterpret_cast<const stbi_uc*>(encoded.data());
  const int size = int(encoded.size());
  if (!stbi_info_from_memory(data, size, &w, &h, &channels))
    throwInputError(file, where, std::string("cannot read image header: ") + stbi_failure_reason(), "a PNG or JPEG image");
  if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide)
    throwInputError(file, where, "image is " + std::to_string(w) + "x" + std::to_string(h) + " pixels",
                    "sides from 1 to " + std::to_string(kMaxImageSide));
  Texture t;
  t.width = std::uint32_t(w);
  t.height = std::uint32_t(h);
  if (!decode) return t;
  int dw = 0, dh = 0;
  stbi_uc* pixels = stbi_load_from_memory(data, size, &dw, &dh, &channels, 4);
  if (pixels == nullptr)
    throwInputError(file, where, std::string("cannot decode image: ") + stbi_failure_reason(), "a valid PNG or JPEG image");
  if (dw != w || dh != h) {
    stbi_image_free(pixels);
    throwInputError(file, where, "image size changed between header and decode", "a consistent image");
  }
  t.pixels.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4);
  stbi_image_free(pixels);
  return t;
}

}  // namespace bounce::asset::detail
