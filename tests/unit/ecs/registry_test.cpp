// Registry: entity generations, stale handles and component operations.
#include <gtest/gtest.h>

#include <string>

#include "engine/core/error.hpp"
#include "engine/ecs/registry.hpp"

using namespace bounce;
using namespace bounce::ecs;

namespace {
struct Position {
  float x = 0, y = 0;
};
struct Tag {};

std::string errorOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InternalError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(Entity, PacksIndexAndGeneration) {
  const Entity e(7, 3);
  EXPECT_EQ(e.index(), 7u);
  EXPECT_EQ(e.generation(), 3u);
  EXPECT_EQ(e.bits(), (std::uint64_t(3) << 32) | 7u);
  EXPECT_TRUE(Entity().isNull());
  EXPECT_FALSE(bool(Entity::null()));
  EXPECT_EQ(toString(e), "entity 7v3");
  EXPECT_EQ(toString(Entity::null()), "null entity");
}

TEST(Registry, DestroyBumpsGenerationAndReusesSlot) {
  Registry r;
  const Entity a = r.create();
  const Entity b = r.create();
  EXPECT_EQ(a, Entity(0, 0));
  EXPECT_EQ(b, Entity(1, 0));
  r.destroy(a);
  EXPECT_FALSE(r.valid(a));
  EXPECT_EQ(r.alive(), 1u);
  const Entity c = r.create();
  EXPECT_EQ(c, Entity(0, 1));  // same slot, next generation
  EXPECT_TRUE(r.valid(c));
  EXPECT_FALSE(r.valid(a));
  EXPECT_EQ(r.entities(), (std::vector<Entity>{c, b}));
}

TEST(Registry, StaleHandleAccessThrowsNamingIt) {
  Registry r;
  const Entity a = r.create();
  r.emplace<Position>(a, 1.f, 2.f);
  r.destroy(a);
  EXPECT_EQ(errorOf([&] { r.get<Position>(a); }),
            "ecs: get<(anonymous namespace)::Position>: stale entity 0v0 (destroyed; slot 0 is free)");
  const Entity reused = r.create();
  EXPECT_EQ(errorOf([&] { r.emplace<Tag>(a); }),
            "ecs: emplace<(anonymous namespace)::Tag>: stale entity 0v0 (destroyed; slot 0 now holds entity 0v1)");
  EXPECT_THROW(r.has<Position>(a), InternalError);
  EXPECT_THROW(r.remove<Position>(a), InternalError);
  EXPECT_THROW(r.tryGet<Position>(a), InternalError);
  EXPECT_THROW(r.destroy(a), InternalError);
  EXPECT_EQ(errorOf([&] { r.get<Position>(Entity::null()); }), "ecs: get<(anonymous namespace)::Position>: null entity");
  EXPECT_EQ(errorOf([&] { r.destroy(Entity(42, 0)); }), "ecs: destroy: unknown entity 42v0 (never created)");
  // The reused slot's new entity has no components from the old one.
  EXPECT_FALSE(r.has<Position>(reused));
}

TEST(Registry, EmplaceGetReplaceRemove) {
  Registry r;
  const Entity e = r.create();
  EXPECT_EQ(r.tryGet<Position>(e), nullptr);
  Position& p = r.emplace<Position>(e, 1.f, 2.f);
  EXPECT_EQ(&p, &r.get<Position>(e));
  EXPECT_EQ(r.get<Position>(e).y, 2.f);
  EXPECT_EQ(errorOf([&] { r.emplace<Position>(e); }),
            "ecs: emplace<(anonymous namespace)::Position>: entity 0v0 already has one");
  r.replace<Position>(e, 3.f, 4.f);
  EXPECT_EQ(r.get<Position>(e).x, 3.f);
  r.emplaceOrReplace<Position>(e, 5.f, 6.f);
  EXPECT_EQ(r.get<Position>(e).x, 5.f);
  EXPECT_TRUE(r.has<Position>(e));
  EXPECT_FALSE((r.allOf<Position, Tag>(e)));
  r.emplace<Tag>(e);
  EXPECT_TRUE((r.allOf<Position, Tag>(e)));
  EXPECT_TRUE(r.remove<Position>(e));
  EXPECT_FALSE(r.remove<Position>(e));
  EXPECT_FALSE(r.has<Position>(e));
  EXPECT_EQ(errorOf([&] { r.get<Position>(e); }),
            "ecs: get<(anonymous namespace)::Position>: entity 0v0 has no such component");
  EXPECT_THROW(r.replace<Position>(e, 1.f, 1.f), InternalError);
}

TEST(Registry, DestroyRemovesEveryComponent) {
  Registry r;
  const Entity a = r.create(), b = r.create();
  r.emplace<Position>(a);
  r.emplace<Tag>(a);
  r.emplace<Position>(b, 9.f, 9.f);
  r.destroy(a);
  EXPECT_EQ(r.storage<Position>()->count(), 1u);
  EXPECT_EQ(r.storage<Tag>()->count(), 0u);
  EXPECT_EQ(r.get<Position>(b).x, 9.f);
}

TEST(Registry, ClearKeepsOldHandlesStale) {
  Registry r;
  const Entity a = r.create();
  r.emplace<Tag>(a);
  r.clear();
  EXPECT_EQ(r.alive(), 0u);
  EXPECT_FALSE(r.valid(a));
  EXPECT_EQ(r.create(), Entity(0, 1));
}
