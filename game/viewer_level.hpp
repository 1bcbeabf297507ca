#pragma once
// A level made on the fly for one glTF file, so `bounce play|capture|profile|graph|bake|accuracy|
// reference|export FILE.glb` shows a model the way glTF viewers do (Filament's gltf_viewer, the
// Khronos Sample Viewer), and `bounce level FILE.glb --out L.json` writes the same level to edit:
//
//   - the asset at the origin, untransformed (its own units and pose);
//   - a camera on the bounds' bounding sphere (radius R, centre C) looking at C from the front,
//     a little above and to the right, far enough for the sphere to fit the vertical field of view;
//   - a sun (directional light, shadows on) from the upper front left, its shadow in view;
//   - a neutral grey background, which is also the environment the probes see;
//   - a ground plane (content/src/ground/ground.gltf) under the asset's lowest point, kViewerGroundHalf·R
//     each side of C, receiving the sun's shadow;
//   - effects direct, shadows, probes (the probe grid is over the ground: spacing 2·kViewerGroundHalf·R /
//     kViewerProbesPerAxis, 64 rays — a bake of well under a second for a sample model).
// `bounce play` turns the level's camera about C with the left mouse button (play_controls.hpp).
#include <filesystem>
#include <string>

#include <glm/glm.hpp>

namespace bounce::game {

inline constexpr float kViewerYfovDeg = 45.0f;
inline constexpr float kViewerGroundHalf = 3.0f;     // ground half-size in bounding radii
inline constexpr int kViewerProbesPerAxis = 12;      // across the ground
inline constexpr std::uint32_t kViewerProbeRays = 64;
inline constexpr float kViewerSunIrradiance = 2.5f;  // renderer units (a Cornell wall gets ~1)
inline constexpr float kViewerSky = 0.4f;            // background radiance, grey

// A .gltf or .glb path (extension compared without case).
bool isGltfFile(const std::filesystem::path& path);

// World-space bounds of what a level entity instancing `asset` (default scene, identity transform)
// draws; Virtual Light Mesh nodes are left out. InputError when the asset draws nothing.
struct AssetBounds {
  glm::vec3 min{0.0f}, max{0.0f};
  glm::vec3 centre() const { return 0.5f * (min + max); }
  // Bounding-sphere radius of the box (at least 1 mm, so a flat or point asset still frames).
  float radius() const;
};
AssetBounds assetBounds(const std::filesystem::path& asset, const std::filesystem::path& cookCache);

// The level's JSON text. Asset paths are written relative to `levelDir` (where the level will be
// saved), so the written level can be moved with its assets.
std::string viewerLevelText(const std::filesystem::path& asset, const AssetBounds& bounds,
                            const std::filesystem::path& levelDir);

// The path a level command should load for `input`: unchanged for a level; for a glTF file its
// viewer level, written to <cache>/levels/<stem>-<hash of the absolute path>.json (rewritten on
// every call, so a changed asset is re-framed).
std::filesystem::path levelPathFor(const std::filesystem::path& input);

// The same for `bounce capture`: a glTF file becomes a capture script of its viewer level
// (one captured frame, 640x480, dt 1/60) beside the level; a capture script is returned unchanged.
std::filesystem::path captureScriptPathFor(const std::filesystem::path& input);

}  // namespace bounce::game
