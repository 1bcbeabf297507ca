#pragma once
// SparseSet: the set of entities that own one component type, as two arrays (EnTT's layout).
//
//   dense_  — the entities, packed: iteration walks it front to back, cache-friendly.
//   sparse_ — indexed by Entity::index(): the entity's position in dense_, or kNoPosition.
//
// Removal swaps the last dense element into the hole and pops ("swap-and-pop"), so the set stays
// packed in O(1); the moved element's sparse_ slot is updated. Invariants (checked by tests):
//   for every position p < size():  dense_[p] is a tombstone, or sparse_[dense_[p].index()] == p
//   for every entity e that contains(e): dense_[position(e)] == e (same generation)
//
// Deferred removal. While the set is *deferred* (Registry sets this while a view iterates),
// erase() does not move anything: it leaves a tombstone (the null entity) in the dense slot and
// forgets the entity. compact() later swap-and-pops every tombstone. This is what makes it safe to
// remove components of *other* entities while iterating: positions, and references to components
// in Storage<T>, do not move during the pass.
//
// Storage<T> derives from this class and keeps its components at the same positions, through
// the two hooks moveElement()/popElement().
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/ecs/entity.hpp"

namespace bounce::ecs {

class SparseSet {
 public:
  static constexpr std::uint32_t kNoPosition = 0xffffffffu;

  SparseSet() = default;
  virtual ~SparseSet() = default;
  SparseSet(const SparseSet&) = delete;
  SparseSet& operator=(const SparseSet&) = delete;

  bool contains(Entity e) const {
    const std::uint32_t i = e.index();
    return i < sparse_.size() && sparse_[i] != kNoPosition && dense_[sparse_[i]] == e;
  }
  // Position of e in dense(); precondition: contains(e).
  std::size_t position(Entity e) const { return sparse_[e.index()]; }

  // Dense slots, tombstones included (a tombstone is the null entity).
  std::size_t size() const { return dense_.size(); }
  // Entities actually contained (size() minus tombstones).
  std::size_t count() const { return dense_.size() - tombstones_; }
  std::size_t tombstones() const { return tombstones_; }
  std::span<const Entity> dense() const { return dense_; }

  // Appends e; returns its position. Throws InternalError when e is null or already present.
  std::size_t insert(Entity e);
  // Removes e (swap-and-pop, or a tombstone while deferred). Returns false if e was absent.
  bool erase(Entity e);

  // While deferred, erase() leaves tombstones. Turning deferral off does not compact by itself.
  void setDeferred(bool deferred) { deferred_ = deferred; }
  bool deferred() const { return deferred_; }
  // Swap-and-pops every tombstone, from the back to the front (deterministic order).
  void compact();

 protected:
  // Storage<T> keeps its payload aligned with dense(): move element `from` into `to`
  // (the old `to` is discarded), and drop the last element.
  virtual void moveElement(std::size_t /*from*/, std::size_t /*to*/) {}
  virtual void popElement() {}
  // Undoes the insert() of the last slot when the payload could not be appended.
  void rollbackInsert();

 private:
  void swapAndPop(std::size_t pos);

  std::vector<Entity> dense_;
  std::vector<std::uint32_t> sparse_;
  std::size_t tombstones_ = 0;
  bool deferred_ = false;
};

}  // namespace bounce::ecs
