#pragma once
// What every baked technique's table entry asks of a level the same way (SL and RTF today): the
// entities that take part (a technique component beside a mesh), their cooked meshes alone; and
// (DNRT, SL, RTF) whether a bake job's cache entries can be used.
#include <algorithm>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/scene/components.hpp"

namespace bounce::gi {

// Entities with a `Component` and a mesh, sorted (deterministic job order); `part` = one entity's id only.
template <class Component>
std::vector<ecs::Entity> participantsOf(ecs::Registry& registry, std::string_view part = {}) {
  std::vector<ecs::Entity> out;
  registry.view<Component, scene::MeshRef>().each([&](ecs::Entity e, Component&, scene::MeshRef&) {
    const auto* name = registry.tryGet<scene::Name>(e);
    if (part.empty() || (name && name->id == part)) out.push_back(e);
  });
  std::sort(out.begin(), out.end());
  return out;
}

// Only the assets of `entities` (a bake job's process decodes its own mesh only).
inline void loadAssetsOf(ecs::Registry& registry, const std::vector<ecs::Entity>& entities,
                         const std::filesystem::path& cookCache, ref::ReferenceAssets& assets) {
  for (ecs::Entity e : entities) {
    ecs::Registry one;
    one.emplace<scene::MeshRef>(one.create(), registry.get<scene::MeshRef>(e));
    assets.load(one, cookCache);
  }
}

// A bake job's cache check (BakeJob::cached): true when every one of `paths` exists and `load(path)`
// reads it. A corrupt entry (load throws InputError) is false, so the job re-bakes it, after a
// warning "<technique>: re-baking a corrupt cache entry: …".
template <class Load>
bool cacheEntriesLoad(std::string_view technique, const std::vector<std::filesystem::path>& paths, Load load) {
  for (const std::filesystem::path& path : paths) {
    if (!std::filesystem::exists(path)) return false;
    try {
      load(path);
    } catch (const InputError& err) {
      log::warn(std::string(technique) + ": re-baking a corrupt cache entry: " + err.what());
      return false;
    }
  }
  return true;
}

}  // namespace bounce::gi
