#pragma once
// From a level's ECS state to the tracer's SceneDesc, seeing exactly what the rasteriser draws:
// the same cooked assets (same CookOptions as GpuScene::upload, so subdivided meshes match), the
// same node-subtree expansion and world matrices as GpuScene::extract, the same material rules
// (level overrides replace the factors; textures still multiply), the same lights (entity lights
// and KHR_lights_punctual lights inside assets) and the same active camera.
//
//   ReferenceAssets assets;  assets.load(registry, cookCache);   // once per level
//   motionSystem(registry, t); transformSystem(registry);         // pose at time t
//   SceneDesc scene = extractScene(registry, level, assets);
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/asset/cook.hpp"
#include "engine/asset/cooked_asset.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/ref/scene_bvh.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/level.hpp"

namespace bounce::ref {

// The cooked assets of every MeshRef in a registry, keyed as GpuScene keys them.
class ReferenceAssets {
 public:
  // Cooks (through the cache) every asset the registry's MeshRef components name. InputError
  // when an asset is broken or a MeshRef names a node the asset does not have.
  void load(ecs::Registry& registry, const std::filesystem::path& cookCache);

  struct Entry {
    asset::CookedAsset cpu;
    asset::CookOptions options;
    std::string contentKey;         // asset::cacheKey(source, options): source bytes, referenced files, options
    std::uint32_t firstTexture = 0;  // this asset's texture 0 in textures()
  };
  const Entry& get(const scene::MeshRef& ref) const;
  const std::map<std::string, Entry>& entries() const { return entries_; }

  // The decoded textures of every asset, in entries() order (SceneDesc::textures).
  const std::vector<RefTexture>& textures() const { return textures_; }

  // GpuScene's key: asset path, plus subdivision settings when present.
  static std::string key(const scene::MeshRef& ref);

 private:
  std::map<std::string, Entry> entries_;
  std::vector<RefTexture> textures_;
};

// The scene at the registry's current WorldTransforms (run the transform system first): meshes in
// world space, materials with the level's overrides, lights, active camera and background.
// `withTextures` false leaves SceneDesc::textures empty (texture indices still index
// assets.textures()): for callers that keep only a few of them (DNRT's per-object scenes).
SceneDesc extractScene(ecs::Registry& registry, const scene::Level& level, const ReferenceAssets& assets,
                       bool withTextures = true);

}  // namespace bounce::ref
