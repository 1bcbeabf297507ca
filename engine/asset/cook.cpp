// cook(): the import pipeline, step by step. Nothing is returned until every step and the final
// validate() succeeded, so a failed cook leaves nothing half-built.
#include "engine/asset/cook.hpp"

#include "engine/asset/cooked_format.hpp"
#include "engine/asset/gltf_import.hpp"
#include "engine/asset/gltf_json.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"

namespace bounce::asset {

CookedAsset cookFromMemory(std::span<const std::uint8_t> bytes, const std::string& name,
                           const std::filesystem::path& baseDir, const CookOptions& options) {
  const tinygltf::Model model = detail::loadModel(bytes, name, baseDir);
  const detail::ImportContext ctx{model, name};
  CookedAsset out;
  out.sourceName = name;
  out.materials = detail::importMaterials(ctx);
  out.textures = detail::importTextures(ctx, out.materials, options.decodeImages);
  out.meshes = detail::importMeshes(ctx);
  detail::importScene(ctx, out);
  detail::applySubdivision(ctx, options, out);
  validate(out, name);
  return out;
}

CookedAsset cook(const std::filesystem::path& source, const CookOptions& options) {
  const std::vector<std::uint8_t> bytes = readFileBytes(source);
  return cookFromMemory(bytes, source.filename().string(), source.parent_path().empty() ? "." : source.parent_path(),
                        options);
}

void writeCooked(const CookedAsset& asset, const std::filesystem::path& path) {
  writeFileAtomic(path, serializeCooked(asset));
}

CookedAsset readCooked(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = readFileBytes(path);
  return parseCooked(bytes, path.string());
}

std::vector<std::filesystem::path> referencedFiles(const std::filesystem::path& source) {
  const std::vector<std::uint8_t> bytes = readFileBytes(source);
  const std::string name = source.filename().string();
  const detail::GltfContainer c = detail::splitContainer(bytes, name);
  std::vector<std::filesystem::path> out;
  for (const std::string& uri : detail::externalUris(detail::parseJson(c.json, name)))
    out.push_back(source.parent_path() / uri);
  return out;
}

}  // namespace bounce::asset
