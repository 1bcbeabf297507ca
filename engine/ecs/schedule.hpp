#pragma once
// Schedule: named systems run in a fixed, reproducible order.
//
// Systems run by ascending stage, and within a stage in the order they were added (a stable
// order, never hash- or pointer-dependent), so the same schedule on the same registry state
// and the same FrameTime produces the same frame. Names must be unique: they label profiling
// scopes and error messages.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "engine/ecs/registry.hpp"

namespace bounce::ecs {

// Time of the frame being simulated. `time` is the simulation clock of the fixed step
// (seconds since start), `dt` the step (seconds), `frame` the frame index.
struct FrameTime {
  double time = 0.0;
  double dt = 0.0;
  std::uint64_t frame = 0;
};

using System = std::function<void(Registry&, const FrameTime&)>;

class Schedule {
 public:
  // Adds a system to `stage` (default 0). Throws InternalError on a duplicate or empty name.
  void add(std::string name, System system, int stage = 0);
  // Runs every system once, in order. An exception from a system propagates (later systems
  // do not run): a frame is all-or-nothing.
  void run(Registry& registry, const FrameTime& time) const;
  // System names in run order.
  std::vector<std::string> order() const;
  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::string name;
    System system;
    int stage;
  };
  std::vector<Entry> entries_;  // kept sorted by stage, insertion order within a stage
};

}  // namespace bounce::ecs
