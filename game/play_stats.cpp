#include "game/play_stats.hpp"

#include "game/timing_stats.hpp"

namespace bounce::game {

void RollingTimings::addGpuFrame(const std::vector<gpu::TimingResult>& timings, std::uint64_t frameNumber) {
  if (frameNumber == 0 || frameNumber == lastFrame_ || timings.empty()) return;
  lastFrame_ = frameNumber;
  std::vector<std::pair<std::string, double>> frame;
  for (const auto& t : timings)
    if (t.depth == 0) frame.emplace_back(t.name, t.ms);
  gpu_.push_back(std::move(frame));
  while (gpu_.size() > window_) gpu_.pop_front();
}

void RollingTimings::addCpuFrameMs(double ms) {
  cpu_.push_back(ms);
  while (cpu_.size() > window_) cpu_.pop_front();
}

std::vector<std::pair<std::string, double>> RollingTimings::passMedians() const {
  std::vector<std::pair<std::string, double>> out;
  if (gpu_.empty()) return out;
  for (const auto& [name, ms] : gpu_.back()) {
    std::vector<double> samples;
    for (const auto& frame : gpu_)
      for (const auto& [n, v] : frame)
        if (n == name) samples.push_back(v);
    out.emplace_back(name, percentile(std::move(samples), 0.5));
  }
  return out;
}

double RollingTimings::gpuTotalMedianMs() const {
  std::vector<double> totals;
  for (const auto& frame : gpu_) {
    double sum = 0.0;
    for (const auto& p : frame) sum += p.second;
    totals.push_back(sum);
  }
  return percentile(std::move(totals), 0.5);
}

double RollingTimings::cpuFrameMedianMs() const { return percentile({cpu_.begin(), cpu_.end()}, 0.5); }

}  // namespace bounce::game
