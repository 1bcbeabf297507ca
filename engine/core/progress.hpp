#pragma once
// A progress bar with ETA for long work (cooks, bakes, references). Drawn on stderr only when
// stderr is a terminal and CI is unset; otherwise silent except for one summary line at the
// end (so CI logs stay short). Thread-safe: workers call advance() concurrently.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace bounce {

class Progress {
 public:
  Progress(std::string label, std::size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(std::size_t n = 1);
  void finish();
  // True when a bar is drawn (terminal, not CI). Exposed for tests.
  bool interactive() const { return interactive_; }
  // "[#####.....] 50% 12/24 ETA 3s" for the given state; pure, unit-tested.
  static std::string render(std::size_t done, std::size_t total, double elapsedSeconds, int width = 30);

 private:
  void draw(bool force);
  std::string label_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point lastDraw_;
  std::mutex mutex_;
  bool interactive_ = false;
  bool finished_ = false;
};

}  // namespace bounce
