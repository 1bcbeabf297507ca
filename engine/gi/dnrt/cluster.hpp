#pragma once
// DNRT's clustered mode (issue 15; level "mode": "clustered", NodeSettings::mode): instead of one
// draw per object, one full-screen draw per batch of up to 32 objects in which every pixel reads
// the G-buffer once and visits only the objects whose outer cube covers its screen tile
// (shaders/dnrt/clustered.frag). The CPU halves live here, pure and testable:
//
// - Tile lists: per frame, each object's outer cube is projected and the 16×16-pixel tiles its
//   screen rectangle touches get the object's bit (one uint per tile and batch). Conservative: a
//   cube reaching behind the eye covers every tile. The shader still tests s(r) > 0 per pixel, so a
//   tile list is only a superset; it decides what a pixel visits, never what it adds.
// - The field atlas: lavapipe (Mesa 22.3) has no descriptor indexing — not even
//   shaderSampledImageArrayDynamicIndexing (vulkaninfo) — so a shader cannot pick one of N field
//   textures by a per-pixel index. All fields therefore share one RGBA8 3D texture per slot
//   (Table 2's 3 or 7), bricks stacked along z. Each brick is padded by one texel that copies its
//   edge, so trilinear filtering at a brick's face reads what CLAMP_TO_EDGE reads on a texture of
//   its own, never the next brick.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/dnrt/field.hpp"

namespace bounce::gi::dnrt {

constexpr std::uint32_t kClusterTile = 16;   // pixels per tile side (clustered.frag shifts by 4)
constexpr std::uint32_t kClusterBatch = 32;  // objects per clustered draw: one bit each of a tile's mask

struct TileGrid {
  std::uint32_t tilesX = 0, tilesY = 0;
  std::size_t count() const { return std::size_t(tilesX) * tilesY; }
};
TileGrid tileGrid(glm::uvec2 resolution);

// Pixels [x0, x1) × [y0, y1) that may show the outer cube boxToWorld·[−1, 1]³ through viewProj
// (Vulkan clip space, +Y down, depth 0..1). A cube with a corner at or behind the eye plane
// (w ≤ 0) gets the whole screen; one wholly beyond the far plane or beside the frustum none.
struct PixelRect {
  std::uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
  friend bool operator==(const PixelRect&, const PixelRect&) = default;
};
PixelRect screenRect(const glm::mat4& viewProj, const glm::mat4& boxToWorld, glm::uvec2 resolution);

// The screen footprint of the outer cube: the convex hull of its projected corners, in pixels
// (counter-clockwise in y-down pixel space as Andrew's monotone chain emits it), or empty with
// `all` set when a corner lies at or behind the eye plane (then every tile), or empty when
// screenRect is. A tile is visited when its square meets the hull (separating axes: the square's
// two and the hull's edge normals), which for a cube seen corner-on leaves out the rectangle's
// corners — up to half its area.
struct ScreenHull {
  bool all = false;
  std::vector<glm::vec2> points;
};
ScreenHull screenHull(const glm::mat4& viewProj, const glm::mat4& boxToWorld, glm::uvec2 resolution);
bool hullMeetsSquare(const ScreenHull& hull, glm::vec2 lo, glm::vec2 hi);

// Tile masks for `boxes` (each object's boxToWorld), batch b of kClusterBatch objects after batch
// b − 1: mask[b·grid.count() + ty·tilesX + tx] has bit i set when object b·32 + i's screen hull
// meets tile (tx, ty).
std::vector<std::uint32_t> binObjects(const glm::mat4& viewProj, glm::uvec2 resolution,
                                      std::span<const glm::mat4> boxes);

// Where each field's brick sits in the atlas. Brick i occupies z ∈ [z0[i], z0[i] + N_i + 2) and
// x, y ∈ [0, N_i + 2); its grid vertex (0, 0, 0) is texel (1, 1, z0[i] + 1).
struct AtlasLayout {
  glm::uvec3 size{0u};              // texels of every slot's 3D texture
  std::vector<std::uint32_t> z0;    // per field
  int slots = 0;                    // RGBA8 textures: 3 when every field has 4 SH, else 7
};
// `maxDepth`: the device's maxImageDimension3D; fields that no longer fit are left out (z0 has one
// entry per field that fits, in order), so the caller draws the rest on their own.
AtlasLayout atlasLayout(std::span<const Field* const> fields, std::uint32_t maxDepth);
// Slot `slot`'s texels (RGBA8, x fastest). Zero where a field lacks the slot (a 4-SH field in a
// 7-slot atlas, whose k for those slots is 0) and outside the bricks.
std::vector<std::uint8_t> atlasTexels(const AtlasLayout& layout, std::span<const Field* const> fields, int slot);

}  // namespace bounce::gi::dnrt
