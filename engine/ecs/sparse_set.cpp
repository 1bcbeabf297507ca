#include "engine/ecs/sparse_set.hpp"

#include "engine/core/error.hpp"

namespace bounce::ecs {

std::size_t SparseSet::insert(Entity e) {
  if (e.isNull()) throw InternalError("ecs: cannot insert the null entity into a sparse set");
  if (contains(e)) throw InternalError("ecs: " + toString(e) + " is already in the sparse set");
  if (dense_.size() >= kNoPosition) throw InternalError("ecs: sparse set is full");
  const std::uint32_t i = e.index();
  if (i >= sparse_.size()) sparse_.resize(std::size_t(i) + 1, kNoPosition);
  sparse_[i] = std::uint32_t(dense_.size());
  dense_.push_back(e);
  return dense_.size() - 1;
}

bool SparseSet::erase(Entity e) {
  if (!contains(e)) return false;
  const std::size_t pos = sparse_[e.index()];
  sparse_[e.index()] = kNoPosition;
  if (deferred_) {
    dense_[pos] = Entity::null();
    ++tombstones_;
  } else {
    swapAndPop(pos);
  }
  return true;
}

void SparseSet::swapAndPop(std::size_t pos) {
  const std::size_t last = dense_.size() - 1;
  if (pos != last) {
    const Entity moved = dense_[last];
    dense_[pos] = moved;
    if (!moved.isNull()) sparse_[moved.index()] = std::uint32_t(pos);
    moveElement(last, pos);
  }
  dense_.pop_back();
  popElement();
}

void SparseSet::rollbackInsert() {
  sparse_[dense_.back().index()] = kNoPosition;
  dense_.pop_back();
}

void SparseSet::compact() {
  if (tombstones_ == 0) return;
  // Walking down from the back, every slot above `pos` is already live when we reach a
  // tombstone at `pos`, so the element swapped in is never itself a tombstone (except when
  // the tombstone is the last slot, which is simply popped).
  for (std::size_t pos = dense_.size(); pos-- > 0;) {
    if (dense_[pos].isNull()) swapAndPop(pos);
  }
  tombstones_ = 0;
}

}  // namespace bounce::ecs
