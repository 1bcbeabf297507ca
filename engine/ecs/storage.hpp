#pragma once
// Storage<T>: a component pool. A SparseSet plus the components, packed in the same order as
// dense(), so component p belongs to dense()[p].
//
// Components live in a std::deque: appending never moves existing elements, so references to
// components stay valid while other entities gain components (std::vector would reallocate).
// Only removal moves an element (swap-and-pop), and during a view's iteration removal is
// deferred (see sparse_set.hpp), so references handed to a view callback stay valid for the
// whole callback.
#include <deque>
#include <type_traits>
#include <utility>

#include "engine/ecs/sparse_set.hpp"

namespace bounce::ecs {

template <class T>
class Storage final : public SparseSet {
 public:
  template <class... Args>
  T& emplace(Entity e, Args&&... args) {
    // Build the value first: a throwing constructor leaves the pool untouched.
    T value = make(std::forward<Args>(args)...);
    insert(e);  // throws InternalError if e is null or already present
    try {
      return components_.emplace_back(std::move(value));
    } catch (...) {
      rollbackInsert();
      throw;
    }
  }
  // Precondition: contains(e).
  T& get(Entity e) { return components_[position(e)]; }
  const T& get(Entity e) const { return components_[position(e)]; }
  // By dense position (tombstones included; a tombstone's payload is a stale value).
  T& at(std::size_t pos) { return components_[pos]; }

 protected:
  void moveElement(std::size_t from, std::size_t to) override { components_[to] = std::move(components_[from]); }
  void popElement() override { components_.pop_back(); }

 private:
  template <class... Args>
  static T make(Args&&... args) {
    if constexpr (std::is_aggregate_v<T>)
      return T{std::forward<Args>(args)...};
    else
      return T(std::forward<Args>(args)...);
  }

  std::deque<T> components_;
};

}  // namespace bounce::ecs
