// View<Ts...>: matching, order, and the iteration rules written in view.hpp (one test each).
#include <gtest/gtest.h>

#include <map>
#include <vector>

#include "engine/ecs/registry.hpp"

using namespace bounce::ecs;

namespace {
struct A {
  int v = 0;
};
struct B {
  int v = 0;
};
struct C {
  int v = 0;
};

// n entities; entity i gets A always, B when i % 2 == 0, C when i % 3 == 0.
std::vector<Entity> populate(Registry& r, int n) {
  std::vector<Entity> es;
  for (int i = 0; i < n; ++i) {
    const Entity e = r.create();
    r.emplace<A>(e, i);
    if (i % 2 == 0) r.emplace<B>(e, 100 + i);
    if (i % 3 == 0) r.emplace<C>(e, 200 + i);
    es.push_back(e);
  }
  return es;
}
}  // namespace

TEST(View, OneComponentVisitsInInsertionOrder) {
  Registry r;
  auto es = populate(r, 5);
  std::vector<int> seen;
  r.view<A>().each([&](A& a) { seen.push_back(a.v); });
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(r.view<A>().entities(), es);
}

TEST(View, TwoComponentsVisitsIntersection) {
  Registry r;
  auto es = populate(r, 7);
  std::vector<std::pair<int, int>> seen;
  r.view<A, B>().each([&](Entity, A& a, B& b) { seen.emplace_back(a.v, b.v); });
  EXPECT_EQ(seen, (std::vector<std::pair<int, int>>{{0, 100}, {2, 102}, {4, 104}, {6, 106}}));
}

TEST(View, ThreeComponentsDrivenBySmallestPool) {
  Registry r;
  auto es = populate(r, 13);
  std::vector<Entity> seen;
  r.view<A, B, C>().each([&](Entity e, A& a, B& b, C& c) {
    EXPECT_EQ(b.v, 100 + a.v);
    EXPECT_EQ(c.v, 200 + a.v);
    seen.push_back(e);
  });
  EXPECT_EQ(seen, (std::vector<Entity>{es[0], es[6], es[12]}));
  EXPECT_EQ((r.view<C, B, A>().count()), 3u);
  EXPECT_EQ((r.view<A, B, C>().front()), es[0]);
}

TEST(View, UnusedComponentTypeGivesEmptyView) {
  Registry r;
  populate(r, 3);
  struct Never {};
  EXPECT_EQ((r.view<A, Never>().count()), 0u);
  EXPECT_EQ((r.view<Never>().front()), Entity::null());
}

TEST(ViewRules, RemovingCurrentEntityIsSafe) {
  Registry r;
  auto es = populate(r, 6);
  std::vector<int> seen;
  r.view<A>().each([&](Entity e, A& a) {
    seen.push_back(a.v);
    if (a.v % 2 == 1) r.destroy(e);
    EXPECT_EQ(a.v, seen.back());  // the reference outlives the removal for this callback
  });
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(r.alive(), 3u);
  EXPECT_EQ(r.storage<A>()->size(), 3u);  // compacted when the pass ended
  EXPECT_EQ(r.storage<A>()->tombstones(), 0u);
  std::vector<int> after;
  r.view<A>().each([&](A& a) { after.push_back(a.v); });
  EXPECT_EQ(after, (std::vector<int>{0, 4, 2}));  // swap-and-pop order after compaction
}

TEST(ViewRules, AddedComponentsAreNotVisitedThisPass) {
  Registry r;
  auto es = populate(r, 4);
  int visits = 0;
  r.view<A>().each([&](Entity, A&) {
    ++visits;
    const Entity fresh = r.create();
    r.emplace<A>(fresh, 1000);  // joins the iterated pool: not visited in this pass
  });
  EXPECT_EQ(visits, 4);
  EXPECT_EQ(r.view<A>().count(), 8u);
}

TEST(ViewRules, AddingAComponentTypeToOthersSkipsThemThisPass) {
  Registry r;
  auto es = populate(r, 6);  // B on 0, 2, 4
  std::vector<Entity> seen;
  r.view<A, B>().each([&](Entity e, A& a, B&) {
    seen.push_back(e);
    if (a.v == 0) r.emplace<B>(es[1]);  // es[1] gains B before... it is still not visited
  });
  // B is the driving pool (3 < 6); es[1] was appended past the recorded end.
  EXPECT_EQ(seen, (std::vector<Entity>{es[0], es[2], es[4]}));
  EXPECT_EQ((r.view<A, B>().count()), 4u);
}

TEST(ViewRules, RemovingOtherEntitiesComponentsIsSafe) {
  Registry r;
  auto es = populate(r, 10);
  std::vector<Entity> seen;
  r.view<A>().each([&](Entity e, A& a) {
    seen.push_back(e);
    // Remove A from the entity two ahead (not yet visited) and from one already visited.
    if (a.v + 2 < 10) r.remove<A>(es[a.v + 2]);
    if (a.v >= 1) r.destroy(es[a.v - 1]);
  });
  // Visit 0 removes 2; visit 1 removes 3 and destroys 0; 2, 3 are skipped; visit 4 removes 6 ...
  EXPECT_EQ(seen, (std::vector<Entity>{es[0], es[1], es[4], es[5], es[8], es[9]}));
}

TEST(ViewRules, ReferencesStayValidWhileOthersAreRemoved) {
  Registry r;
  auto es = populate(r, 5);
  r.view<A>().each([&](Entity e, A& a) {
    const int before = a.v;
    // The last entity's A would be swapped into a hole without deferral.
    for (Entity other : es)
      if (other != e && r.valid(other) && r.has<A>(other)) r.remove<A>(other);
    EXPECT_EQ(a.v, before);
    EXPECT_EQ(&a, &r.get<A>(e));
  });
  EXPECT_EQ(r.view<A>().count(), 1u);
}

TEST(ViewRules, IterationWithRemovalsVisitsEverySurvivorExactlyOnce) {
  // A deterministic pseudo-random mix of removals, destroys and additions during one pass.
  Registry r;
  auto es = populate(r, 200);
  std::map<std::uint64_t, int> visits;
  std::vector<bool> lostBeforeTurn(200, false), visited(200, false);
  std::uint32_t state = 12345;
  auto next = [&] { return state = state * 1664525u + 1013904223u; };
  r.view<A, B>().each([&](Entity e, A& a, B&) {
    ++visits[e.bits()];
    visited[a.v] = true;
    for (int k = 0; k < 3; ++k) {
      const int victim = int(next() % 200);
      if (!r.valid(es[victim])) continue;
      const std::uint32_t op = next() % 3;
      if (op == 2) {
        const Entity fresh = r.create();
        r.emplace<A>(fresh, 0);
        r.emplace<B>(fresh, 0);
        continue;
      }
      if (op == 0)
        r.remove<B>(es[victim]);
      else
        r.destroy(es[victim]);
      if (!visited[victim]) lostBeforeTurn[victim] = true;
    }
  });
  for (auto& [bits, n] : visits) EXPECT_EQ(n, 1) << toString(Entity::fromBits(bits));
  // Every original entity with B that was not touched before its turn was visited.
  // Nothing that lost B (or died) before its turn was visited.
  int survivors = 0;
  for (int i = 0; i < 200; i += 2) {
    EXPECT_EQ(visited[i], !lostBeforeTurn[i]) << i;
    survivors += !lostBeforeTurn[i];
  }
  EXPECT_EQ(int(visits.size()), survivors);  // and no fresh entity was visited
  // After the pass the pools are compact and consistent.
  EXPECT_EQ(r.storage<A>()->tombstones(), 0u);
  EXPECT_EQ(r.storage<B>()->tombstones(), 0u);
  for (Entity e : r.storage<B>()->dense()) EXPECT_TRUE(r.valid(e));
}

TEST(ViewRules, NestedViewsDeferUntilOutermostEnds) {
  Registry r;
  auto es = populate(r, 4);
  r.view<A>().each([&](Entity outer, A&) {
    r.view<B>().each([&](Entity inner, B&) {
      if (inner != outer && r.valid(inner)) r.remove<B>(inner);
    });
    EXPECT_TRUE(r.iterating());
    EXPECT_EQ(r.storage<B>()->size(), 2u);  // still tombstoned, not compacted
  });
  EXPECT_FALSE(r.iterating());
  EXPECT_EQ(r.storage<B>()->size(), r.storage<B>()->count());
}
