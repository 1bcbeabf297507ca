#pragma once
// Registry: creates and destroys entities and owns one Storage<T> per component type.
//
// Every operation that names an entity checks it first: a null or stale handle (destroyed, or
// its slot reused under a newer generation) throws InternalError naming the handle and the
// operation, e.g. "ecs: get<bounce::scene::Transform>: stale entity 3v0 (slot 3 is at
// generation 1)". valid(e) is the non-throwing test.
//
// Structural changes while a view iterates are allowed; the rules are in view.hpp. In short:
// while any view iterates, removals are deferred (tombstones), so nothing moves until the
// outermost iteration ends, when every pool is compacted.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/ecs/entity.hpp"
#include "engine/ecs/storage.hpp"

namespace bounce::ecs {

template <class... Ts>
class View;

namespace detail {
std::size_t nextComponentId();
std::string demangle(const char* mangled);

// One id per component type, assigned on first use (0, 1, 2, ...).
template <class T>
std::size_t componentId() {
  static const std::size_t id = nextComponentId();
  return id;
}
template <class T>
const std::string& componentName() {
  static const std::string name = demangle(typeid(T).name());
  return name;
}
}  // namespace detail

class Registry {
 public:
  Registry() = default;
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;
  Registry(Registry&&) = default;  // not while a view iterates it
  Registry& operator=(Registry&&) = default;

  // A new entity: the lowest-cost free slot (most recently freed first), else a new slot.
  Entity create();
  // Removes all of e's components and frees its slot (its generation is bumped).
  void destroy(Entity e);
  bool valid(Entity e) const;
  // Number of live entities.
  std::size_t alive() const { return alive_; }
  // Live entities in slot-index order (deterministic).
  std::vector<Entity> entities() const;
  // Destroys every entity; slots keep their generations, so old handles stay stale.
  void clear();

  template <class T, class... Args>
  T& emplace(Entity e, Args&&... args) {
    check(e, "emplace", detail::componentName<T>());
    auto& pool = assure<T>();
    if (pool.contains(e))
      throw InternalError("ecs: emplace<" + detail::componentName<T>() + ">: " + toString(e) + " already has one");
    return pool.emplace(e, std::forward<Args>(args)...);
  }
  template <class T, class... Args>
  T& replace(Entity e, Args&&... args) {
    T& slot = get<T>(e);
    slot = makeValue<T>(std::forward<Args>(args)...);
    return slot;
  }
  template <class T, class... Args>
  T& emplaceOrReplace(Entity e, Args&&... args) {
    check(e, "emplaceOrReplace", detail::componentName<T>());
    auto& pool = assure<T>();
    if (pool.contains(e)) return pool.get(e) = makeValue<T>(std::forward<Args>(args)...);
    return pool.emplace(e, std::forward<Args>(args)...);
  }
  // Removes e's T if it has one; returns whether it did.
  template <class T>
  bool remove(Entity e) {
    check(e, "remove", detail::componentName<T>());
    auto* pool = storage<T>();
    return pool && pool->erase(e);
  }
  template <class T>
  T& get(Entity e) {
    T* p = tryGet<T>(e);
    if (!p) throw InternalError("ecs: get<" + detail::componentName<T>() + ">: " + toString(e) + " has no such component");
    return *p;
  }
  template <class T>
  const T& get(Entity e) const {
    return const_cast<Registry*>(this)->get<T>(e);
  }
  // nullptr when e has no T (a stale e still throws).
  template <class T>
  T* tryGet(Entity e) {
    check(e, "get", detail::componentName<T>());
    auto* pool = storage<T>();
    return pool && pool->contains(e) ? &pool->get(e) : nullptr;
  }
  template <class T>
  const T* tryGet(Entity e) const {
    return const_cast<Registry*>(this)->tryGet<T>(e);
  }
  template <class T>
  bool has(Entity e) const {
    check(e, "has", detail::componentName<T>());
    const auto* pool = storage<T>();
    return pool && pool->contains(e);
  }
  template <class... Ts>
  bool allOf(Entity e) const {
    return (has<Ts>(e) && ...);
  }

  template <class... Ts>
  View<Ts...> view() {
    return View<Ts...>(*this);
  }

  // The pool for T, or nullptr if no T was ever emplaced.
  template <class T>
  Storage<T>* storage() {
    const std::size_t id = detail::componentId<T>();
    return id < pools_.size() ? static_cast<Storage<T>*>(pools_[id].get()) : nullptr;
  }
  template <class T>
  const Storage<T>* storage() const {
    return const_cast<Registry*>(this)->storage<T>();
  }
  template <class T>
  Storage<T>& assure() {
    const std::size_t id = detail::componentId<T>();
    if (id >= pools_.size()) pools_.resize(id + 1);
    if (!pools_[id]) {
      pools_[id] = std::make_unique<Storage<T>>();
      pools_[id]->setDeferred(iterationDepth_ > 0);
    }
    return *static_cast<Storage<T>*>(pools_[id].get());
  }

  // Iteration guard used by View: while held (nestable), removals are deferred.
  class IterationLock {
   public:
    explicit IterationLock(Registry& r) : r_(r) { r_.beginIteration(); }
    ~IterationLock() { r_.endIteration(); }
    IterationLock(const IterationLock&) = delete;
    IterationLock& operator=(const IterationLock&) = delete;

   private:
    Registry& r_;
  };
  bool iterating() const { return iterationDepth_ > 0; }

 private:
  template <class T, class... Args>
  static T makeValue(Args&&... args) {
    if constexpr (std::is_aggregate_v<T>)
      return T{std::forward<Args>(args)...};
    else
      return T(std::forward<Args>(args)...);
  }
  // Throws InternalError unless e is valid; `op` and `type` name the operation in the message.
  void check(Entity e, const char* op, const std::string& type) const;
  void beginIteration();
  void endIteration();

  std::vector<std::unique_ptr<SparseSet>> pools_;  // by detail::componentId<T>()
  std::vector<std::uint32_t> generations_;         // by slot index
  std::vector<std::uint8_t> live_;                 // by slot index: 1 while the slot's entity lives
  std::vector<std::uint32_t> free_;                // freed slots, reused last-in first-out
  std::size_t alive_ = 0;
  int iterationDepth_ = 0;
};

}  // namespace bounce::ecs

#include "engine/ecs/view.hpp"
