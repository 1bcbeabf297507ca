#include "engine/gi/dnrt/object_scene.hpp"

#include "engine/asset/cook.hpp"
#include "engine/core/error.hpp"
#include "engine/core/hash.hpp"
#include "engine/scene/asset_instances.hpp"
#include "engine/scene/systems.hpp"

#include <algorithm>

namespace bounce::gi::dnrt {

void loadLevelObjects(const scene::Level& level, const std::filesystem::path& cookCache, LevelObjects& out) {
  scene::instantiate(level, out.registry);
  scene::transformSystem(out.registry);
  out.assets.load(out.registry, cookCache);
  out.entities.clear();
  out.registry.view<scene::Dnrt, scene::MeshRef>().each(
      [&](ecs::Entity e, scene::Dnrt&, scene::MeshRef&) { out.entities.push_back(e); });
  std::sort(out.entities.begin(), out.entities.end());
}

std::string objectSourceKey(const std::string& assetContentKey, const scene::MeshRef& mesh,
                            const scene::MaterialOverride* material) {
  Hasher h;
  h.str("dnrt-object-v1").str(assetContentKey);  // v1: objectScene() as below (identity frame, albedo only)
  if (!mesh.node) h.u64(0);
  else if (const auto* name = std::get_if<std::string>(&*mesh.node)) h.u64(1).str(*name);
  else h.u64(2).u64(std::get<std::uint32_t>(*mesh.node));
  h.u64(material && material->albedo ? 1 : 0);
  if (material && material->albedo) h.pod(*material->albedo);
  h.u64(material && material->emissive ? 1 : 0);  // emissive is dropped, but keep keys honest
  if (material && material->emissive) h.pod(*material->emissive);
  return h.hex();
}

std::string objectSourceKey(ecs::Registry& registry, ecs::Entity entity, const std::filesystem::path& cookCache) {
  const auto* mesh = registry.tryGet<scene::MeshRef>(entity);
  if (!mesh) throw InternalError("dnrt::objectSourceKey: entity has no mesh");
  return objectSourceKey(asset::cacheKey(mesh->asset, scene::cookOptionsForRef(*mesh, cookCache)), *mesh,
                         registry.tryGet<scene::MaterialOverride>(entity));
}

ref::SceneDesc objectScene(ecs::Registry& registry, ecs::Entity entity, const ref::ReferenceAssets& assets) {
  const auto* mesh = registry.tryGet<scene::MeshRef>(entity);
  if (!mesh) throw InternalError("dnrt::objectScene: entity has no mesh");
  ecs::Registry one;
  const ecs::Entity e = one.create();
  one.emplace<scene::MeshRef>(e, *mesh);
  one.emplace<scene::WorldTransform>(e);  // identity: the object's local frame
  if (const auto* over = registry.tryGet<scene::MaterialOverride>(entity)) one.emplace<scene::MaterialOverride>(e, *over);
  // Without textures: copying every decoded texture of every asset per object dominated planning
  // a level's bake jobs; the ones the object uses are copied below.
  ref::SceneDesc all = ref::extractScene(one, scene::Level{}, assets, false);
  const std::vector<ref::RefTexture>& textures = assets.textures();

  ref::SceneDesc out;
  out.meshes = std::move(all.meshes);
  out.materials = std::move(all.materials);
  std::vector<int> remap(textures.size(), -1);
  for (ref::RefMaterial& m : out.materials) {
    m.emissiveTexture = -1;  // DNRT reflects albedo only (Eq. 8)
    const int t = m.albedoTexture;
    if (t < 0 || std::size_t(t) >= textures.size()) {
      m.albedoTexture = -1;
      continue;
    }
    if (remap[std::size_t(t)] < 0) {
      remap[std::size_t(t)] = int(out.textures.size());
      out.textures.push_back(textures[std::size_t(t)]);
    }
    m.albedoTexture = remap[std::size_t(t)];
  }
  out.sourceKey = objectSourceKey(assets.get(*mesh).contentKey, *mesh, registry.tryGet<scene::MaterialOverride>(entity));
  return out;
}

FieldSettings settingsFrom(const scene::Dnrt& c) {
  FieldSettings s;
  s.shCount = c.shCount;
  s.grid = c.grid;
  s.innerExtent = c.innerExtent;
  s.outerExtent = c.outerExtent;
  s.samplesPerAxis = c.samplesPerAxis;
  s.antiRadiance = c.improvedAntiRadiance ? AntiRadiance::Improved : AntiRadiance::Paper;
  return s;
}

}  // namespace bounce::gi::dnrt
