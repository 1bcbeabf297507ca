#pragma once
// SL pass 2's screen tiles (issue 13: "tile-cull spheres by their influence bounds, as Unreal's
// capsule shadows do"): per frame, which SLs each 16×16-pixel tile's pixels may need. Receiver rule
// 0 (evaluate.hpp, influence F > 0) shrinks an SL to nothing at |c − p| ≥ F·r, and a culled SL
// neither lights nor blocks, so a receiver only needs the SLs whose ball of radius F·r contains it;
// the tile gets an SL when the screen hull of the cube around that ball meets it (the binning DNRT's
// clustered mode uses, engine/gi/screen_tiles.hpp) and the ball itself meets the tile's frustum
// (its four side planes; on the characters level at 1280×720 24.3 SLs per drawn tile in 2757 of 3600
// tiles, against 28.3 in every tile by the cube alone). Only tiles with any SL are drawn (one instance
// each, shaders/sl/tiles.vert). With F = 0 (no influence bound) every tile gets every SL.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/screen_tiles.hpp"
#include "engine/gi/sl/shade.hpp"

namespace bounce::gi::sl {

// One drawn tile as tiles.vert reads it (std430, 32 bytes).
struct ShadeTile {
  glm::uvec4 tile{0u};  // x, y: the tile's column and row (pixels [16x, 16x + 16) × [16y, 16y + 16))
  glm::uvec4 mask{0u};  // SL i at bit i % 32 of word i / 32
};
static_assert(sizeof(ShadeTile) == 32);
static_assert(kMaxShadedSpheres <= 4 * kTileMaskBits, "a tile's mask holds 4 words");

// tiles.vert's push constants (the passes that draw tiles: sl, sl.upsample, sl.shadow).
struct TilePush {
  glm::vec2 invExtent;     // 1 / the target's pixels
  std::uint32_t tileSize;  // gi::kScreenTile
  std::uint32_t pad = 0;
};

// The tiles of a `resolution` target (viewProj: the camera's, Vulkan clip space) with any SL, row by
// row; `spheres` as pass 2 reads them, `influence` rule 0's F (0: off).
std::vector<ShadeTile> binTiles(const glm::mat4& viewProj, glm::uvec2 resolution, std::span<const ShadedSphere> spheres,
                                float influence);

}  // namespace bounce::gi::sl
