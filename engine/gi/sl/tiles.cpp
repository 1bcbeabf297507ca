#include "engine/gi/sl/tiles.hpp"

#include "engine/core/error.hpp"

namespace bounce::gi::sl {

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
