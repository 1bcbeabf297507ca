#pragma once
// DNRT's clustered mode (issue 15; level "mode": "clustered", NodeSettings::mode): instead of one
// draw per object, one full-screen draw per batch of up to 32 objects in which every pixel reads
// the G-buffer once and visits only the objects whose outer cube covers its screen tile
// (shaders/dnrt/clustered.frag). The CPU halves live here, pure and testable:
//
// - Tile lists: per frame, each object's outer cube is projected and the 16×16-pixel tiles its
//   screen rectangle touches get the object's bit (one uint per tile and batch). Conservative: a
//   cube reaching behind the eye covers every tile. The shader still tests s(r) > 0 per pixel, so a
//   tile list is only a superset; it decides what a pixel visits, never what it adds. On the GPU,
//   shaders/dnrt/tile_cull.comp then clears the objects whose outer cube misses the tile's depth
//   range (node.cpp, NodeSettings::tileCull), still a superset.
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
#include "engine/gi/screen_tiles.hpp"

namespace bounce::gi::dnrt {

constexpr std::uint32_t kClusterTile = kScreenTile;   // pixels per tile side (clustered.frag shifts by 4)
constexpr std::uint32_t kClusterBatch = kTileMaskBits;  // objects per clustered draw: one bit each of a tile's mask
// The screen-tile binning is shared with SL's tiled pass 2 (engine/gi/screen_tiles.hpp).
using gi::binObjects;
using gi::hullMeetsSquare;
using gi::PixelRect;
using gi::ScreenHull;
using gi::screenHull;
using gi::screenRect;
using gi::TileGrid;
using gi::tileGrid;


// Whether the probes pass may be drawn as an object's outer cube (the fused mode, probes::FusedDnrt::split;
// shaders/probes/outer_cube.vert): the eye is inside the cube, and every point of its faces that the view
// frustum holds lies between the near and far planes (no face is clipped where it is seen), so every
// pixel's view ray leaves the cube through exactly one face. `boxToWorld`: the unit cube [-1, 1]³ → the
// world-space outer cube (DnrtObjectGpu); `view`, `proj`: the frame's camera (render::CameraGpu, proj as
// perspectiveVk makes; false for any other projection).
bool eyeInsideOuterCube(const glm::mat4& boxToWorld, const glm::mat4& view, const glm::mat4& proj);

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
