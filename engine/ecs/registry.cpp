#include "engine/ecs/registry.hpp"

#include <cxxabi.h>

#include <atomic>
#include <cstdlib>

namespace bounce::ecs {

namespace detail {

std::size_t nextComponentId() {
  static std::atomic<std::size_t> next{0};
  return next.fetch_add(1);
}

std::string demangle(const char* mangled) {
  int status = 0;
  char* out = abi::__cxa_demangle(mangled, nullptr, nullptr, &status);
  std::string name = (status == 0 && out) ? out : mangled;
  std::free(out);
  return name;
}

}  // namespace detail

Entity Registry::create() {
  std::uint32_t index;
  if (!free_.empty()) {
    index = free_.back();
    free_.pop_back();
  } else {
    if (generations_.size() >= Entity::kNullIndex) throw InternalError("ecs: out of entity slots");
    index = std::uint32_t(generations_.size());
    generations_.push_back(0);
    live_.push_back(0);
  }
  live_[index] = 1;
  ++alive_;
  return Entity(index, generations_[index]);
}

void Registry::destroy(Entity e) {
  check(e, "destroy", "");
  for (auto& pool : pools_)
    if (pool) pool->erase(e);
  const std::uint32_t i = e.index();
  live_[i] = 0;
  --alive_;
  // Retire the slot when its generation would reach the all-ones value: reusing it would
  // eventually hand out a generation an old handle still carries.
  if (generations_[i] + 1 < 0xffffffffu) {
    ++generations_[i];
    free_.push_back(i);
  } else {
    generations_[i] = 0xffffffffu;
  }
}

bool Registry::valid(Entity e) const {
  const std::uint32_t i = e.index();
  return !e.isNull() && i < generations_.size() && live_[i] && generations_[i] == e.generation();
}

std::vector<Entity> Registry::entities() const {
  std::vector<Entity> out;
  out.reserve(alive_);
  for (std::uint32_t i = 0; i < generations_.size(); ++i)
    if (live_[i]) out.emplace_back(i, generations_[i]);
  return out;
}

void Registry::clear() {
  for (Entity e : entities()) destroy(e);
}

void Registry::check(Entity e, const char* op, const std::string& type) const {
  if (valid(e)) return;
  std::string what = std::string("ecs: ") + op + (type.empty() ? "" : "<" + type + ">") + ": ";
  const std::uint32_t i = e.index();
  if (e.isNull())
    what += "null entity";
  else if (i >= generations_.size())
    what += "unknown " + toString(e) + " (never created)";
  else if (!live_[i])
    what += "stale " + toString(e) + " (destroyed; slot " + std::to_string(i) + " is free)";
  else
    what += "stale " + toString(e) + " (destroyed; slot " + std::to_string(i) + " now holds " +
            toString(Entity(i, generations_[i])) + ")";
  throw InternalError(what);
}

void Registry::beginIteration() {
  if (iterationDepth_++ == 0)
    for (auto& pool : pools_)
      if (pool) pool->setDeferred(true);
}

void Registry::endIteration() {
  if (--iterationDepth_ > 0) return;
  for (auto& pool : pools_) {
    if (!pool) continue;
    pool->setDeferred(false);
    pool->compact();
  }
}

}  // namespace bounce::ecs
