// Schedule: deterministic system order.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/ecs/schedule.hpp"

using namespace bounce;
using namespace bounce::ecs;

TEST(Schedule, RunsByStageThenInsertionOrder) {
  Schedule s;
  std::vector<std::string> log;
  auto sys = [&](std::string name) { return [&log, name](Registry&, const FrameTime&) { log.push_back(name); }; };
  s.add("transforms", sys("transforms"), 20);
  s.add("motion", sys("motion"), 10);
  s.add("gi", sys("gi"), 30);
  s.add("animation", sys("animation"), 10);
  s.add("late", sys("late"), 20);
  const std::vector<std::string> expected{"motion", "animation", "transforms", "late", "gi"};
  EXPECT_EQ(s.order(), expected);
  Registry r;
  s.run(r, FrameTime{0.5, 0.1, 5});
  EXPECT_EQ(log, expected);
  log.clear();
  s.run(r, FrameTime{0.6, 0.1, 6});
  EXPECT_EQ(log, expected);
}

TEST(Schedule, SystemsSeeFrameTimeAndRegistry) {
  Schedule s;
  Registry r;
  struct Counter {
    double t = 0;
  };
  const Entity e = r.create();
  r.emplace<Counter>(e);
  s.add("advance", [](Registry& reg, const FrameTime& ft) {
    reg.view<Counter>().each([&](Counter& c) { c.t = ft.time + double(ft.frame); });
  });
  s.run(r, FrameTime{1.25, 0.25, 3});
  EXPECT_EQ(r.get<Counter>(e).t, 4.25);
}

TEST(Schedule, DuplicateOrEmptyNameThrows) {
  Schedule s;
  s.add("a", [](Registry&, const FrameTime&) {});
  EXPECT_THROW(s.add("a", [](Registry&, const FrameTime&) {}, 5), InternalError);
  EXPECT_THROW(s.add("", [](Registry&, const FrameTime&) {}), InternalError);
  EXPECT_THROW(s.add("b", System{}), InternalError);
  EXPECT_EQ(s.size(), 1u);
}
