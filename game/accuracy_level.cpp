#include "game/accuracy_level.hpp"

#include <map>

#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"

namespace bounce::game {

std::set<std::string> dynamicEntityIds(const scene::Level& level) {
  std::map<std::string, std::string> parentOf;
  std::set<std::string> removed;
  for (const auto& e : level.entities) {
    if (e.parent) parentOf[e.id] = *e.parent;
    if ((e.dynamic || e.motion) && !e.camera) removed.insert(e.id);
  }
  // A child may come before its parent in the file: walk each entity's parent chain (loadLevel
  // rejected cycles, and the step bound keeps a hand-built Level with one from looping).
  for (const auto& e : level.entities) {
    std::string id = e.id;
    for (std::size_t step = 0; step <= level.entities.size(); ++step) {
      if (removed.count(id)) {
        if (e.camera)
          throwInputError(level.source.string(), e.pointer, "camera \"" + e.id + "\" moves with dynamic entity \"" + id + "\"",
                          "a camera that stays when dynamic entities are removed for the object-effect metric");
        removed.insert(e.id);
        break;
      }
      const auto p = parentOf.find(id);
      if (p == parentOf.end()) break;
      id = p->second;
    }
  }
  return removed;
}

scene::Level withoutDynamicEntities(const scene::Level& level) {
  const std::set<std::string> removed = dynamicEntityIds(level);
  scene::Level out = level;
  out.entities.clear();
  for (const auto& e : level.entities)
    if (!removed.count(e.id)) out.entities.push_back(e);
  return out;
}

std::string withoutDynamicEntitiesJson(const scene::Level& level) {
  const std::set<std::string> removed = dynamicEntityIds(level);
  nlohmann::json json = nlohmann::json::parse(readFileText(level.source), nullptr, /*allow_exceptions=*/false);
  // loadLevel read this same file a moment ago; a change in between is not bad user input.
  if (!json.is_object() || !json.contains("entities") || !json["entities"].is_array())
    throw InternalError(level.source.string() + ": level file changed while it was being read");
  const std::filesystem::path dir = level.source.parent_path();
  nlohmann::json kept = nlohmann::json::array();
  for (auto& e : json["entities"]) {
    if (!e.is_object() || !e.contains("id") || !e["id"].is_string())
      throw InternalError(level.source.string() + ": level file changed while it was being read");
    if (removed.count(e["id"].get<std::string>())) continue;
    if (e.contains("mesh") && e["mesh"].is_object() && e["mesh"].contains("asset") && e["mesh"]["asset"].is_string())
      e["mesh"]["asset"] = (dir / e["mesh"]["asset"].get<std::string>()).lexically_normal().string();
    kept.push_back(e);
  }
  json["entities"] = std::move(kept);
  return json.dump(2) + "\n";
}

}  // namespace bounce::game
