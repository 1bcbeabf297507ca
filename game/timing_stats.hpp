#pragma once
// Per-pass GPU timings gathered over many frames, reduced to median and 95th percentile (this
// host's timings vary up to 2× between runs, so single frames mean little: DESIGN.md).
#include <map>
#include <string>
#include <vector>

#include "engine/gpu/frames.hpp"

namespace bounce {
class Progress;
namespace gpu {
class Presenter;
}
}  // namespace bounce

namespace bounce::game {

class Session;

struct PassStats {
  std::string pass;
  std::string object;  // empty for whole-pass rows; the entity id for a per-object scope "<pass>/<object>"
  std::size_t frames = 0;
  double medianMs = 0.0;
  double p95Ms = 0.0;
  // Nesting depth of the scope: 0 for an outermost one (the "frame" row sums those). A nested
  // scope (DNRT's "dnrt/<object>" inside "dnrt") is already part of its parent's time, while a
  // per-object pass such as "dnrt.cube/<object>" is outermost.
  std::uint32_t depth = 0;
};

// Nearest-rank percentile (q in [0, 1]) of unsorted samples; 0 for none.
double percentile(std::vector<double> samples, double q);

class TimingCollector {
 public:
  // Records every frame the ring resolved since the last call, except warm-up frames.
  void collect(gpu::FrameRing& frames, std::uint64_t warmupFrames);
  // Records one frame's scopes (what collect does per frame; tests feed frames through it).
  void addFrame(const std::vector<gpu::TimingResult>& timings);
  // One row per pass in first-seen order, then a "frame" row: the sum of the outermost scopes.
  // A scope named "<pass>/<object>" becomes a row with that pass and object. A per-object row
  // counts only the frames that drew the object.
  std::vector<PassStats> stats() const;
  std::size_t framesCollected() const { return frames_; }
  // The q-th percentile (nearest rank, q in [0, 1]; 0.5 the median) over the frames that timed both scopes
  // of `a` − `b` (ms; NaN when no frame did): a paired difference, so the host's speed drifting between
  // frames cancels, where the difference of the two medians keeps it (`bounce bench dnrt`'s fused rows:
  // "probes" − "probes.baseline").
  // `bMayBeMissing`: a frame without `b` counts with b = 0 instead of being left out. A scope timed twice in
  // one frame counts with its last time here (stats() keeps both).
  double pairedPercentileMs(const std::string& a, const std::string& b, double q, bool bMayBeMissing = false) const;

 private:
  std::vector<std::string> order_;
  std::map<std::string, std::vector<double>> samples_;
  std::map<std::string, std::uint32_t> depth_;  // of each scope name (the same every frame)
  std::vector<std::map<std::string, double>> frameMs_;  // each collected frame's scopes (pairedPercentileMs)
  std::size_t frames_ = 0;
};

// The frames `bounce profile` and the benches time: kWarmupFrames first (their draws compile
// pipelines: DESIGN.md machine facts), then `frames`, the level's motion advanced kFrameDt (s) each;
// every frame but the warm-up ones lands in `timings` (the last after waiting for the device).
// `progress`, when set, advances once a frame.
inline constexpr std::uint64_t kWarmupFrames = 5;
inline constexpr double kFrameDt = 1.0 / 60.0;
void timeFrames(Session& session, gpu::Presenter& presenter, int frames, TimingCollector& timings,
                Progress* progress = nullptr);

std::string formatTable(const std::vector<PassStats>& rows);
// CSV with the header exactly "pass,object,frames,median_ms,p95_ms".
std::string formatCsv(const std::vector<PassStats>& rows);
// {"passes": [{"pass": …, "object": …, "frames": …, "median_ms": …, "p95_ms": …}, …]}
std::string formatJson(const std::vector<PassStats>& rows);

}  // namespace bounce::game
