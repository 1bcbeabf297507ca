// SparseSet and Storage<T>: the packed layout and its invariants under insert/erase/compact.
#include <gtest/gtest.h>

#include <vector>

#include "engine/core/error.hpp"
#include "engine/ecs/storage.hpp"

using namespace bounce;
using namespace bounce::ecs;

namespace {

// The two invariants of sparse_set.hpp, checked exhaustively.
void expectInvariants(const SparseSet& set, std::size_t maxIndex) {
  std::size_t tombstones = 0;
  for (std::size_t p = 0; p < set.size(); ++p) {
    const Entity e = set.dense()[p];
    if (e.isNull()) {
      ++tombstones;
      continue;
    }
    ASSERT_TRUE(set.contains(e));
    EXPECT_EQ(set.position(e), p);
  }
  EXPECT_EQ(tombstones, set.tombstones());
  EXPECT_EQ(set.count(), set.size() - tombstones);
  for (std::uint32_t i = 0; i <= maxIndex; ++i) {
    const Entity e(i, 0);
    if (set.contains(e)) {
      EXPECT_EQ(set.dense()[set.position(e)], e);
    }
  }
}

std::vector<std::uint32_t> indices(const SparseSet& set) {
  std::vector<std::uint32_t> out;
  for (Entity e : set.dense()) out.push_back(e.isNull() ? 999 : e.index());
  return out;
}

}  // namespace

TEST(SparseSet, InsertAppendsInOrder) {
  SparseSet set;
  for (std::uint32_t i : {5u, 1u, 9u}) set.insert(Entity(i, 0));
  EXPECT_EQ(indices(set), (std::vector<std::uint32_t>{5, 1, 9}));
  EXPECT_EQ(set.position(Entity(1, 0)), 1u);
  expectInvariants(set, 10);
}

TEST(SparseSet, ContainsChecksGeneration) {
  SparseSet set;
  set.insert(Entity(3, 1));
  EXPECT_TRUE(set.contains(Entity(3, 1)));
  EXPECT_FALSE(set.contains(Entity(3, 0)));
  EXPECT_FALSE(set.contains(Entity(3, 2)));
  EXPECT_FALSE(set.contains(Entity(4, 1)));
  EXPECT_FALSE(set.contains(Entity::null()));
}

TEST(SparseSet, EraseSwapsLastIntoHole) {
  SparseSet set;
  for (std::uint32_t i = 0; i < 5; ++i) set.insert(Entity(i, 0));
  EXPECT_TRUE(set.erase(Entity(1, 0)));
  // Last (4) moved into position 1.
  EXPECT_EQ(indices(set), (std::vector<std::uint32_t>{0, 4, 2, 3}));
  EXPECT_EQ(set.position(Entity(4, 0)), 1u);
  EXPECT_FALSE(set.contains(Entity(1, 0)));
  EXPECT_FALSE(set.erase(Entity(1, 0)));  // already gone
  EXPECT_TRUE(set.erase(Entity(3, 0)));   // erasing the last slot moves nothing
  EXPECT_EQ(indices(set), (std::vector<std::uint32_t>{0, 4, 2}));
  expectInvariants(set, 5);
}

TEST(SparseSet, DoubleInsertAndNullThrow) {
  SparseSet set;
  set.insert(Entity(2, 0));
  EXPECT_THROW(set.insert(Entity(2, 0)), InternalError);
  EXPECT_THROW(set.insert(Entity::null()), InternalError);
  EXPECT_EQ(set.size(), 1u);
}

TEST(SparseSet, DeferredEraseLeavesTombstonesThenCompacts) {
  SparseSet set;
  for (std::uint32_t i = 0; i < 6; ++i) set.insert(Entity(i, 0));
  set.setDeferred(true);
  set.erase(Entity(1, 0));
  set.erase(Entity(5, 0));
  set.erase(Entity(3, 0));
  EXPECT_EQ(indices(set), (std::vector<std::uint32_t>{0, 999, 2, 999, 4, 999}));
  EXPECT_EQ(set.tombstones(), 3u);
  EXPECT_EQ(set.count(), 3u);
  expectInvariants(set, 6);
  set.setDeferred(false);
  set.compact();
  // From the back: pos 5 is popped; pos 3 takes 4 (then last); pos 1 takes 4 again.
  EXPECT_EQ(indices(set), (std::vector<std::uint32_t>{0, 4, 2}));
  EXPECT_EQ(set.tombstones(), 0u);
  expectInvariants(set, 6);
}

TEST(Storage, PayloadFollowsSwapAndPop) {
  Storage<int> s;
  for (std::uint32_t i = 0; i < 4; ++i) s.emplace(Entity(i, 0), int(i * 10));
  s.erase(Entity(0, 0));
  EXPECT_EQ(s.get(Entity(3, 0)), 30);
  EXPECT_EQ(s.get(Entity(1, 0)), 10);
  EXPECT_EQ(s.position(Entity(3, 0)), 0u);
  EXPECT_EQ(s.at(0), 30);
  s.setDeferred(true);
  s.erase(Entity(1, 0));
  s.setDeferred(false);
  s.compact();
  EXPECT_EQ(s.get(Entity(2, 0)), 20);
  EXPECT_EQ(s.get(Entity(3, 0)), 30);
  EXPECT_EQ(s.size(), 2u);
}

TEST(Storage, ThrowingConstructorLeavesPoolUntouched) {
  struct Picky {
    explicit Picky(int v) {
      if (v < 0) throw std::invalid_argument("negative");
    }
  };
  Storage<Picky> s;
  s.emplace(Entity(0, 0), 1);
  EXPECT_THROW(s.emplace(Entity(1, 0), -1), std::invalid_argument);
  EXPECT_EQ(s.size(), 1u);
  EXPECT_FALSE(s.contains(Entity(1, 0)));
}

TEST(Storage, GrowthDoesNotMoveExistingComponents) {
  Storage<double> s;
  double& first = s.emplace(Entity(0, 0), 1.5);
  for (std::uint32_t i = 1; i < 10000; ++i) s.emplace(Entity(i, 0), double(i));
  EXPECT_EQ(&first, &s.get(Entity(0, 0)));
  EXPECT_EQ(first, 1.5);
}
