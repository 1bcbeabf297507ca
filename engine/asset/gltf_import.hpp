#pragma once
// Internal: the import steps of cook(), in the order cook() runs them.
#include "engine/asset/cook.hpp"
#include "engine/asset/import_context.hpp"

#include <filesystem>
#include <span>

namespace bounce::asset::detail {

// Validates the container and JSON, then parses with tinygltf (buffers loaded, images kept
// encoded in Image::image for decodeTextures()).
tinygltf::Model loadModel(std::span<const std::uint8_t> bytes, const std::string& file,
                          const std::filesystem::path& baseDir);

std::vector<Material> importMaterials(const ImportContext& ctx);
// One texture per glTF image; srgb set from the materials that use it.
std::vector<Texture> importTextures(const ImportContext& ctx, const std::vector<Material>& materials, bool decode);
std::vector<Mesh> importMeshes(const ImportContext& ctx);

// gltf_scene.cpp: nodes (with cycle and multiple-parent checks), cameras, lights, skins,
// animations and the default scene's roots.
void importScene(const ImportContext& ctx, CookedAsset& out);

// subdivision.cpp: replaces the mesh of every node with a subdivision request by a refined copy.
void applySubdivision(const ImportContext& ctx, const CookOptions& options, CookedAsset& out);

}  // namespace bounce::asset::detail
