#include "engine/render/graph/resource.hpp"

#include <algorithm>
#include <bit>

#include "engine/core/error.hpp"

namespace bounce::rg {

bool isDepthFormat(Format format) { return format == Format::D16_UNORM || format == Format::D32F; }

const char* formatName(Format format) {
  switch (format) {
    case Format::R8_UNORM: return "R8_UNORM";
    case Format::RGBA8_UNORM: return "RGBA8_UNORM";
    case Format::RGBA8_SRGB: return "RGBA8_SRGB";
    case Format::BGRA8_UNORM: return "BGRA8_UNORM";
    case Format::BGRA8_SRGB: return "BGRA8_SRGB";
    case Format::R16F: return "R16F";
    case Format::RG16F: return "RG16F";
    case Format::RGBA16F: return "RGBA16F";
    case Format::R32F: return "R32F";
    case Format::RG32F: return "RG32F";
    case Format::RGBA32F: return "RGBA32F";
    case Format::R32_UINT: return "R32_UINT";
    case Format::D16_UNORM: return "D16_UNORM";
    case Format::D32F: return "D32F";
  }
  return "?";
}

void validate(const TextureDesc& d, const std::string& resource) {
  auto fail = [&](const std::string& what) {
    throw InternalError("render graph: texture '" + resource + "' (" + describe(d) + "): " + what);
  };
  if (d.width == 0 || d.height == 0 || d.depth == 0 || d.layers == 0 || d.mips == 0)
    fail("every extent, the layer count and the mip count must be at least 1");
  // A full mip chain of an n-texel edge has floor(log2 n) + 1 levels.
  std::uint32_t largest = std::max({d.width, d.height, d.depth});
  std::uint32_t maxMips = static_cast<std::uint32_t>(std::bit_width(largest));
  if (d.mips > maxMips) fail("has more mips than its largest edge allows (" + std::to_string(maxMips) + ")");
  if (d.depth > 1 && (d.layers > 1 || d.cube)) fail("a 3D texture cannot be an array or a cube");
  if (d.cube && (d.layers % 6 != 0 || d.width != d.height))
    fail("a cube needs square faces and a layer count that is a multiple of 6");
  if (isDepthFormat(d.format) && d.depth > 1) fail("a depth format cannot be 3D");
}

void validate(const BufferDesc& d, const std::string& resource) {
  if (d.size == 0) throw InternalError("render graph: buffer '" + resource + "' has size 0 bytes");
}

std::string describe(const TextureDesc& d) {
  std::string s = std::to_string(d.width) + "x" + std::to_string(d.height);
  if (d.depth > 1) s += "x" + std::to_string(d.depth);
  s += std::string(" ") + formatName(d.format);
  if (d.cube) s += " cube";
  if (d.layers > 1) s += " layers " + std::to_string(d.layers);
  if (d.mips > 1) s += " mips " + std::to_string(d.mips);
  return s;
}

std::string describe(const BufferDesc& d) { return std::to_string(d.size) + " bytes"; }

}  // namespace bounce::rg
