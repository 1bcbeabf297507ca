#pragma once
// Content cooking: glTF 2.0 (.gltf, .glb, embedded data: URIs, KHR_draco_mesh_compression,
// KHR_lights_punctual) → CookedAsset, plus the content-hash cache of cooked files.
//
//   CookedAsset a = loadOrCook("content/src/Duck/Duck.glb", "build/cooked", {});
//
// Every error in a user's file is an InputError with one line "file: where: what (expected …)",
// where `where` is a JSON pointer ("/meshes/2/primitives/0/attributes/POSITION") or "accessor 5".
// Nothing is returned half-built. Repairs made on the way are counted warnings (log::warn); see
// the header comment of engine/asset/mesh_repair.cpp.
#include "engine/asset/cooked_asset.hpp"

#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace bounce::asset {

// Bump when cook() output changes for the same input (it is part of every cache key and stored in
// every cooked file, so old cache entries are re-cooked, never trusted).
// 2: reads extras.bounce_vlm into Node::vlm.
// 3: JOINTS_1/WEIGHTS_1, skin weights checked and renormalised, skins and animations validated.
// 4: a subdivided skinned or morphed mesh keeps its cage and gets limit stencils (Mesh::cage).
inline constexpr std::uint32_t kCookerVersion = 4;

struct CookOptions {
  // false: images are checked (header read) but not decoded; Texture::pixels stays empty.
  // For tools and tests that only need geometry.
  bool decodeImages = true;
  // Subdivision requested by the caller, keyed by node name or by the node index in decimal.
  // Overrides the node's extras.subdivision. A key that names no node is an InputError.
  std::map<std::string, Subdivision> subdivision;
};

// Imports and cooks one .gltf/.glb file.
CookedAsset cook(const std::filesystem::path& source, const CookOptions& options = {});

// Cooks from memory: `bytes` are a .glb when they start with "glTF", else glTF JSON. External
// files (buffers, images) are looked up in `baseDir`. `name` is used in error messages.
CookedAsset cookFromMemory(std::span<const std::uint8_t> bytes, const std::string& name,
                           const std::filesystem::path& baseDir, const CookOptions& options = {});

// Cooked binary files (engine/asset/cooked_format.hpp describes the layout).
void writeCooked(const CookedAsset& asset, const std::filesystem::path& path);
CookedAsset readCooked(const std::filesystem::path& path);

// The cache: key = hash(source bytes, every external file it references, options, cooker and
// format versions); entry `cacheDir/<key>.bcook`, written atomically. A corrupt or stale entry is
// reported with a warning and re-cooked.
std::string cacheKey(const std::filesystem::path& source, const CookOptions& options);
CookedAsset loadOrCook(const std::filesystem::path& source, const std::filesystem::path& cacheDir,
                       const CookOptions& options = {});
// loadOrCook for many files, with a progress bar.
std::vector<CookedAsset> loadOrCookAll(const std::vector<std::filesystem::path>& sources,
                                       const std::filesystem::path& cacheDir, const CookOptions& options = {});

// Files a glTF references by relative URI (buffers and images, data: URIs excluded), resolved
// against its folder, in the order they appear. Throws InputError when the glTF cannot be parsed.
std::vector<std::filesystem::path> referencedFiles(const std::filesystem::path& source);

}  // namespace bounce::asset
