#pragma once
// ONE entity's geometry in its own local frame, for its DNRT bake: the same expansion, materials
// and textures the reference tracer sees (ref::extractScene run on a registry holding only a copy of
// the entity at the identity transform), lights dropped, textures pruned to those it uses (so the
// bake's cache key depends on this object alone).
#include "engine/ecs/registry.hpp"
#include "engine/gi/dnrt/field.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/level.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace bounce::gi::dnrt {

// `entity` must have a MeshRef whose asset `assets` has loaded (ReferenceAssets::load). The result's
// sourceKey is objectSourceKey() of the entity (so cacheKey() of it needs no hashing of its texels).
ref::SceneDesc objectScene(ecs::Registry& registry, ecs::Entity entity, const ref::ReferenceAssets& assets);

// What objectScene() makes the entity's scene from, as a content key: the cooked asset's content key
// (asset::cacheKey: its source bytes, the files it references, the cook options — subdivision
// included), the node it instances and its material override. Computed without cooking or decoding
// anything (the asset's files are read and hashed), so planning a level's DNRT jobs stays cheap
// and a moved checkout keeps its keys. The first form is what objectScene() uses.
std::string objectSourceKey(const std::string& assetContentKey, const scene::MeshRef& mesh,
                            const scene::MaterialOverride* material);
std::string objectSourceKey(ecs::Registry& registry, ecs::Entity entity, const std::filesystem::path& cookCache);

// A level's entities that carry a DNRT field, with what objectScene() needs to describe them: the
// level instantiated at t = 0 (transforms resolved) and its reference assets. What bake-only tools
// (bounce bake, bounce bench dnrt) iterate; filled in place (the registry is not movable).
struct LevelObjects {
  ecs::Registry registry;
  ref::ReferenceAssets assets;
  std::vector<ecs::Entity> entities;  // with scene::Dnrt and scene::MeshRef, ascending
};
void loadLevelObjects(const scene::Level& level, const std::filesystem::path& cookCache, LevelObjects& out);

// The bake settings a level component asks for.
FieldSettings settingsFrom(const scene::Dnrt& component);

}  // namespace bounce::gi::dnrt
