#include "engine/gi/sl/tiles.hpp"

#include <algorithm>

#include "engine/core/error.hpp"

namespace bounce::gi::sl {

namespace {
// The four side planes of a tile's frustum, (n, d) with n·x + d ≥ 0 inside, |n| = 1: clip-space
// x − a·w ≥ 0 and b·w − x ≥ 0 for the tile's NDC span [a, b] in x, likewise in y (Vulkan clip
// space, +Y down, so pixel rows map to NDC y directly). Their intersection is the forward cone
// only (behind the eye w < 0 and a < b leave no x), so a ball is kept when its centre lies no
// farther than its radius outside each plane: conservative (a ball beside a frustum edge can pass
// all four and miss the cone), never losing a receiver inside the ball.
glm::vec4 sidePlane(const glm::mat4& viewProj, int axis, float ndc, float sign) {
  const glm::vec4 rowAxis(viewProj[0][axis], viewProj[1][axis], viewProj[2][axis], viewProj[3][axis]);
  const glm::vec4 rowW(viewProj[0][3], viewProj[1][3], viewProj[2][3], viewProj[3][3]);
  const glm::vec4 plane = sign * (rowAxis - ndc * rowW);
  const float len = glm::length(glm::vec3(plane));
  return len > 0.0f ? plane / len : plane;
}
}  // namespace

std::vector<ShadeTile> binTiles(const glm::mat4& viewProj, glm::uvec2 resolution, std::span<const ShadedSphere> spheres,
                                float influence) {
  if (spheres.size() > kMaxShadedSpheres) throw InternalError("sl::binTiles: more SLs than a tile's mask holds");
  const TileGrid grid = tileGrid(resolution);
  std::vector<ShadeTile> tiles;
  if (spheres.empty()) return tiles;
  std::vector<std::uint32_t> masks;
  if (influence > 0.0f) {
    // The cube [c − F r, c + F r]³ bounds the ball rule 0 leaves the SL in.
    std::vector<glm::mat4> boxes;
    boxes.reserve(spheres.size());
    for (const ShadedSphere& s : spheres) {
      const float half = influence * std::max(0.0f, s.radius);
      boxes.push_back(glm::mat4(glm::vec4(half, 0, 0, 0), glm::vec4(0, half, 0, 0), glm::vec4(0, 0, half, 0),
                                glm::vec4(s.centre, 1.0f)));
    }
    masks = binObjects(viewProj, resolution, boxes);
    // Second test, per listed (tile, SL): the ball itself against the tile's frustum. The cube's
    // screen hull is up to √3 wider than the ball's silhouette, and every SL a tile lists costs each
    // of its pixels a candidate-walk body with a per-lane read of the sphere (README "SL cost,
    // session 8": the walk was about a third of the frame's CPU time there), so the ball's bound pays.
    std::vector<glm::vec4> columns(2 * std::size_t(grid.tilesX)), rows(2 * std::size_t(grid.tilesY));
    for (std::uint32_t tx = 0; tx < grid.tilesX; ++tx) {
      const float a = float(tx * kScreenTile) / float(resolution.x) * 2.0f - 1.0f;
      const float b = float(std::min((tx + 1) * kScreenTile, resolution.x)) / float(resolution.x) * 2.0f - 1.0f;
      columns[2 * tx] = sidePlane(viewProj, 0, a, 1.0f);
      columns[2 * tx + 1] = sidePlane(viewProj, 0, b, -1.0f);
    }
    for (std::uint32_t ty = 0; ty < grid.tilesY; ++ty) {
      const float a = float(ty * kScreenTile) / float(resolution.y) * 2.0f - 1.0f;
      const float b = float(std::min((ty + 1) * kScreenTile, resolution.y)) / float(resolution.y) * 2.0f - 1.0f;
      rows[2 * ty] = sidePlane(viewProj, 1, a, 1.0f);
      rows[2 * ty + 1] = sidePlane(viewProj, 1, b, -1.0f);
    }
    for (std::size_t i = 0; i < spheres.size(); ++i) {
      const glm::vec4 c(spheres[i].centre, 1.0f);
      // 1e-3 of slack for the planes' float rounding (rule 0 fades the SL to 0 at the ball's surface).
      const float ball = 1.001f * influence * std::max(0.0f, spheres[i].radius);
      std::uint32_t* word = masks.data() + (i / kTileMaskBits) * grid.count();
      const std::uint32_t bit = 1u << (i % kTileMaskBits);
      for (std::uint32_t ty = 0; ty < grid.tilesY; ++ty) {
        const bool rowMeets = glm::dot(rows[2 * ty], c) >= -ball && glm::dot(rows[2 * ty + 1], c) >= -ball;
        for (std::uint32_t tx = 0; tx < grid.tilesX; ++tx) {
          std::uint32_t& w = word[std::size_t(ty) * grid.tilesX + tx];
          if (!(w & bit)) continue;
          if (!rowMeets || glm::dot(columns[2 * tx], c) < -ball || glm::dot(columns[2 * tx + 1], c) < -ball) w &= ~bit;
        }
      }
    }
  } else {
    const std::size_t words = (spheres.size() + kTileMaskBits - 1) / kTileMaskBits;
    masks.assign(words * grid.count(), 0u);
    for (std::size_t i = 0; i < spheres.size(); ++i)
      for (std::size_t t = 0; t < grid.count(); ++t) masks[(i / kTileMaskBits) * grid.count() + t] |= 1u << (i % kTileMaskBits);
  }
  const std::size_t words = masks.size() / std::max<std::size_t>(grid.count(), 1);
  for (std::uint32_t ty = 0; ty < grid.tilesY; ++ty)
    for (std::uint32_t tx = 0; tx < grid.tilesX; ++tx) {
      ShadeTile t;
      t.tile = glm::uvec4(tx, ty, 0u, 0u);
      bool any = false;
      for (std::size_t w = 0; w < words; ++w) {
        t.mask[int(w)] = masks[w * grid.count() + std::size_t(ty) * grid.tilesX + tx];
        any = any || t.mask[int(w)] != 0u;
      }
      if (any) tiles.push_back(t);
    }
  return tiles;
}

}  // namespace bounce::gi::sl
