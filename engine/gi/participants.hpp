#pragma once
// What every baked technique's table entry asks of a level the same way (SL and RTF today): the
// entities that take part (a technique component beside a mesh), their cooked meshes alone; and
// (DNRT, SL, RTF) whether a bake job's cache entries can be used; (DNRT, RTF) whether a field can be
// placed at the level's start.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/gi/placement.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/json_reader.hpp"
#include "engine/scene/level.hpp"

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

// At the session's start (the level's transforms, t = 0) a participant's field must be placeable: a
// world scale so small that place() refuses it (placement.hpp: an entry of the unit-frame map above
// kMaxToUnit, i.e. a smallest axis scale × the field's radius under ~1e-30) is the level's bad input,
// one line at the entity's transform (its own or a parent's scale). A motion that reaches such a
// scale later is no error: the techniques skip the object's GI for those frames (tryPlace).
// Callers link bounce_gi_placement (DNRT, RTF).
inline void checkPlaceable(const scene::Level& level, const ecs::Registry& registry, ecs::Entity e,
                           std::string_view technique, glm::vec3 centreLocal, float radiusLocal) {
  const auto* placed = registry.tryGet<scene::WorldTransform>(e);
  if (!placed || tryPlace(centreLocal, radiusLocal, placed->matrix)) return;
  const auto* name = registry.tryGet<scene::Name>(e);
  const auto desc = std::find_if(level.entities.begin(), level.entities.end(),
                                 [&](const scene::EntityDesc& d) { return name && d.id == name->id; });
  if (desc == level.entities.end())
    throw InternalError(std::string(technique) + ": an object's world transform cannot be placed");
  const glm::dmat3 m{glm::dmat4(placed->matrix)};
  const double scale = std::min({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
  auto num = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return std::string(text);
  };
  throwInputError(level.source.string(), desc->pointer + "/transform",
                  std::string(technique) + " cannot place " + scene::json::inQuotes(desc->id) + ": smallest world axis scale " +
                      num(scale) + " × field radius " + num(radiusLocal),
                  "a finite transform whose smallest axis scale × the field radius is at least ~1e-30");
}

}  // namespace bounce::gi
