#include "game/timing_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>
#include <nlohmann/json.hpp>

#include "engine/core/progress.hpp"
#include "game/session.hpp"

namespace bounce::game {

double percentile(std::vector<double> s, double q) {
  if (s.empty()) return 0.0;
  std::sort(s.begin(), s.end());
  // Nearest rank: the smallest value with at least q of the samples at or below it.
  std::size_t rank = static_cast<std::size_t>(std::ceil(q * double(s.size())));
  return s[std::clamp<std::size_t>(rank, 1, s.size()) - 1];
}

void TimingCollector::collect(gpu::FrameRing& frames, std::uint64_t warmupFrames) {
  for (const auto& resolved : frames.takeResolvedTimings()) {
    if (resolved.frame <= warmupFrames) continue;
    addFrame(resolved.timings);
  }
}

void TimingCollector::addFrame(const std::vector<gpu::TimingResult>& timings) {
  double total = 0.0;
  auto& frame = frameMs_.emplace_back();
  for (const auto& t : timings) {
    frame[t.name] = t.ms;
    if (!samples_.count(t.name)) order_.push_back(t.name);
    samples_[t.name].push_back(t.ms);
    depth_[t.name] = t.depth;
    if (t.depth == 0) total += t.ms;
  }
  if (!samples_.count("frame")) order_.push_back("frame");
  samples_["frame"].push_back(total);
  frame["frame"] = total;
  ++frames_;
}

double TimingCollector::pairedPercentileMs(const std::string& a, const std::string& b, double q,
                                           bool bMayBeMissing) const {
  std::vector<double> differences;
  for (const auto& frame : frameMs_) {
    const auto ia = frame.find(a), ib = frame.find(b);
    if (ia != frame.end() && ib != frame.end())
      differences.push_back(ia->second - ib->second);
    else if (ia != frame.end() && bMayBeMissing)
      differences.push_back(ia->second);
  }
  if (differences.empty()) return std::numeric_limits<double>::quiet_NaN();
  return percentile(std::move(differences), q);  // nearest rank, as stats()'s medians
}

std::vector<PassStats> TimingCollector::stats() const {
  std::vector<PassStats> rows;
  for (const auto& name : order_) {
    if (name == "frame") continue;
    const auto& s = samples_.at(name);
    // A per-object scope is named "<pass>/<object>" (e.g. "dnrt/prop-red-box"): its row names both.
    const auto slash = name.find('/');
    const std::string pass = slash == std::string::npos ? name : name.substr(0, slash);
    const std::string object = slash == std::string::npos ? std::string() : name.substr(slash + 1);
    rows.push_back({pass, object, s.size(), percentile(s, 0.5), percentile(s, 0.95), depth_.at(name)});
  }
  if (samples_.count("frame")) {
    const auto& s = samples_.at("frame");
    rows.push_back({"frame", "", s.size(), percentile(s, 0.5), percentile(s, 0.95)});
  }
  return rows;
}

std::string formatTable(const std::vector<PassStats>& rows) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-24s %-20s %7s %11s %11s\n", "pass", "object", "frames", "median ms", "p95 ms");
  out += line;
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line, "%-24s %-20s %7zu %11.3f %11.3f\n", r.pass.c_str(), r.object.c_str(), r.frames,
                  r.medianMs, r.p95Ms);
    out += line;
  }
  return out;
}

std::string formatCsv(const std::vector<PassStats>& rows) {
  std::string out = "pass,object,frames,median_ms,p95_ms\n";
  char line[256];
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line, "%s,%s,%zu,%.4f,%.4f\n", r.pass.c_str(), r.object.c_str(), r.frames, r.medianMs,
                  r.p95Ms);
    out += line;
  }
  return out;
}

std::string formatJson(const std::vector<PassStats>& rows) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& r : rows)
    passes.push_back({{"pass", r.pass}, {"object", r.object}, {"frames", r.frames}, {"median_ms", r.medianMs},
                      {"p95_ms", r.p95Ms}});
  return nlohmann::json{{"passes", passes}}.dump(2) + "\n";
}

void timeFrames(Session& session, gpu::Presenter& presenter, int frames, TimingCollector& timings, Progress* progress) {
  for (std::uint64_t f = 0; f < std::uint64_t(frames) + kWarmupFrames; ++f) {
    session.update(double(f) * kFrameDt);
    session.render(presenter, {});
    timings.collect(session.renderer().frames(), kWarmupFrames);
    if (progress) progress->advance();
  }
  session.renderer().frames().waitIdle();
  timings.collect(session.renderer().frames(), kWarmupFrames);
}

}  // namespace bounce::game
