#pragma once
// What rtf_cpca and rtf_cpca_time both take first: LEVEL OBJECT PROXIES SPHERES FACE RAYS — one of the
// level's dynamic objects (cooked meshes from the cache) and the RTF field's sampling settings.
#include <cstdio>
#include <cstdlib>

#include "engine/core/paths.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/rtf/bake.hpp"
#include "engine/scene/level.hpp"

namespace bounce::tools {

// args[0..5] = LEVEL OBJECT PROXIES SPHERES FACE RAYS. False (after a one-line message naming `tool`)
// when OBJECT is past the level's objects.
inline bool loadToolObject(const char* tool, char** args, gi::dnrt::LevelObjects& objects, std::size_t& index,
                           gi::rtf::FieldSettings& s) {
  const scene::Level level = scene::loadLevel(args[0]);
  index = std::size_t(std::atoi(args[1]));
  gi::dnrt::loadLevelObjects(level, cacheDir("cooked"), objects);
  if (index >= objects.entities.size()) {
    std::fprintf(stderr, "%s: object %zu of %zu\n", tool, index, objects.entities.size());
    return false;
  }
  s.proxies = std::atoi(args[2]), s.spheres = std::atoi(args[3]), s.faceSize = std::atoi(args[4]);
  s.raysPerAxis = std::atoi(args[5]);
  return true;
}

}  // namespace bounce::tools
