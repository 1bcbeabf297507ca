#pragma once
// Rolling per-pass GPU timings for the play overlay: the median over the last N completed frames
// (single frames jump by up to 2x on a shared host, DESIGN.md "Machine facts"), and the median
// CPU frame time over the same window.
#include <cstdint>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "engine/gpu/timestamps.hpp"

namespace bounce::game {

class RollingTimings {
 public:
  static constexpr std::size_t kDefaultWindow = 30;  // frames: half a second at 60 Hz
  explicit RollingTimings(std::size_t window = kDefaultWindow) : window_(window) {}

  // Records one completed frame's scopes (outermost scopes only) when `frameNumber` is new;
  // the same frame offered twice (the ring resolves a slot once) is ignored.
  void addGpuFrame(const std::vector<gpu::TimingResult>& timings, std::uint64_t frameNumber);
  void addCpuFrameMs(double ms);

  // The passes of the newest recorded frame, in its order, each with its median over the frames
  // of the window in which it ran (a pass toggled on a moment ago has few samples).
  std::vector<std::pair<std::string, double>> passMedians() const;
  // Median over the window of the sum of a frame's outermost scopes; 0 without samples.
  double gpuTotalMedianMs() const;
  double cpuFrameMedianMs() const;
  std::size_t gpuFrames() const { return gpu_.size(); }

 private:
  std::size_t window_;
  std::deque<std::vector<std::pair<std::string, double>>> gpu_;
  std::deque<double> cpu_;
  std::uint64_t lastFrame_ = 0;
};

}  // namespace bounce::game
