#pragma once
// The "without" half of the object-effect metric (engine/ref/metrics.hpp, objectEffectError):
// the same level with every dynamic entity removed, so that (with − without) is the change the
// dynamic objects cause.
//
// An entity is dynamic when the level says "dynamic": true or gives it a "motion" (motion
// implies dynamic, README "Level format"). Its children go with it: a child's transform is
// relative to its parent, so it moves with it and belongs to the same object. Dynamic lights
// are objects too (a carried lamp) and go; cameras stay, being the viewpoint and not part of the
// scene: a dynamic camera entity is kept, and one riding on a removed object is an InputError
// (the two images would not show the same view).
#include <filesystem>
#include <set>
#include <string>

#include "engine/scene/level.hpp"

namespace bounce::game {

// Ids of the dynamic entities of `level` and of all their descendants.
std::set<std::string> dynamicEntityIds(const scene::Level& level);

// A copy of `level` without the entities dynamicEntityIds() names; everything else (effects,
// background, static entities in file order, source path) is unchanged.
scene::Level withoutDynamicEntities(const scene::Level& level);

// The same level as JSON text, for tools that read level files (the reference path tracer): the
// level file's JSON without those entities, with every mesh asset path made absolute so that the
// text can be saved anywhere. `level` must be the result of scene::loadLevel (it is validated;
// this only re-reads level.source).
std::string withoutDynamicEntitiesJson(const scene::Level& level);

}  // namespace bounce::game
