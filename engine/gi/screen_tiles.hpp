#pragma once
// Screen tiles (16×16 pixels) and which of N world-space boxes may show in each: the CPU half of
// the tiled deferred passes, DNRT's clustered mode (engine/gi/dnrt/cluster.hpp) and SL's pass 2
// (engine/gi/sl/tiles.hpp), as Unreal's capsule shadows cull capsules per tile by their bounds.
// Conservative: a box reaching behind the eye covers every tile; the pixel shaders still test
// their own bound per pixel, so a tile's mask is a superset and decides what a pixel visits, never
// what it adds.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::gi {

constexpr std::uint32_t kScreenTile = 16;    // pixels per tile side
constexpr std::uint32_t kTileMaskBits = 32;  // boxes per mask word: one bit each

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

// Tile masks for `boxes` (each object's boxToWorld), batch b of kTileMaskBits objects after batch
// b − 1: mask[b·grid.count() + ty·tilesX + tx] has bit i set when object b·32 + i's screen hull
// meets tile (tx, ty).
std::vector<std::uint32_t> binObjects(const glm::mat4& viewProj, glm::uvec2 resolution,
                                      std::span<const glm::mat4> boxes);

}  // namespace bounce::gi
