#pragma once
// Internal: image decoding (PNG, JPEG and the other formats stb_image reads) to RGBA8.
#include "engine/asset/cooked_asset.hpp"

#include <cstdint>
#include <span>
#include <string>

namespace bounce::asset::detail {

// Largest accepted image side, pixels. Bigger declared sizes are refused before decoding so a
// corrupt header cannot ask for gigabytes.
inline constexpr int kMaxImageSide = 16384;

// Decodes `encoded` (reads only its header when !decode). Errors name `file` and `where`.
Texture decodeImage(std::span<const std::uint8_t> encoded, bool decode, const std::string& file, const std::string& where);

}  // namespace bounce::asset::detail
