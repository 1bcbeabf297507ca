#pragma once
// The cooked binary format (.bcook), little-endian:
//
//   offset 0   magic        8 bytes "BCOOKED\0"
//          8   u32          format version (kCookedFormatVersion)
//         12   u32          cooker version (kCookerVersion, engine/asset/cook.hpp)
//         16   u32          section count N
//         20   u32          reserved, 0
//         24   N × {u32 type, u32 reserved 0, u64 offset, u64 size}   section table
//              payload      sections, in table order, back to back
//   size-8     u64          checksum: Hasher digest (engine/core/hash.hpp) of every byte before it
//
// Every section type appears exactly once, in increasing type order, and must be consumed exactly
// by its parser. The reader checks magic, versions, sizes, offsets and the checksum before it
// parses anything, and validate()s the result: any mismatch is an InputError and no object.
#include "engine/asset/cooked_asset.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace bounce::asset {

// 2: nodes carry extras.bounce_vlm (NodeVlm).
// 3: Primitive::joints1/weights1. 4: Mesh::cage and Primitive::stencils (subdivided deformed meshes).
inline constexpr std::uint32_t kCookedFormatVersion = 4;

enum class SectionType : std::uint32_t {
  Info = 1,  // source name, root nodes
  Meshes = 2,
  Materials = 3,
  Textures = 4,
  Nodes = 5,
  Cameras = 6,
  Lights = 7,
  Skins = 8,
  Animations = 9,
};

std::vector<std::uint8_t> serializeCooked(const CookedAsset& asset);
// `name` is used in error messages (the cooked file's path).
CookedAsset parseCooked(std::span<const std::uint8_t> bytes, const std::string& name);

}  // namespace bounce::asset
