#include "engine/ecs/schedule.hpp"

#include <algorithm>

#include "engine/core/error.hpp"

namespace bounce::ecs {

void Schedule::add(std::string name, System system, int stage) {
  if (name.empty()) throw InternalError("ecs: schedule: a system needs a name");
  if (!system) throw InternalError("ecs: schedule: system \"" + name + "\" is empty");
  for (const Entry& e : entries_)
    if (e.name == name) throw InternalError("ecs: schedule: duplicate system name \"" + name + "\"");
  // Insert after the last entry whose stage is <= `stage`: stable within a stage.
  auto at = std::upper_bound(entries_.begin(), entries_.end(), stage,
                             [](int s, const Entry& e) { return s < e.stage; });
  entries_.insert(at, Entry{std::move(name), std::move(system), stage});
}

void Schedule::run(Registry& registry, const FrameTime& time) const {
  for (const Entry& e : entries_) e.system(registry, time);
}

std::vector<std::string> Schedule::order() const {
  std::vector<std::string> names;
  names.reserve(entries_.size());
  for (const Entry& e : entries_) names.push_back(e.name);
  return names;
}

}  // namespace bounce::ecs
