#include "engine/core/progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace bounce {

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total), start_(std::chrono::steady_clock::now()), lastDraw_(start_) {
  interactive_ = ::isatty(STDERR_FILENO) && std::getenv("CI") == nullptr;
}

Progress::~Progress() { finish(); }

void Progress::advance(std::size_t n) {
  done_ += n;
  if (interactive_) draw(false);
}

std::string Progress::render(std::size_t done, std::size_t total, double elapsed, int width) {
  const double frac = total ? std::min(1.0, double(done) / double(total)) : 1.0;
  const int filled = static_cast<int>(std::lround(frac * width));
  std::string s = "[";
  for (int i = 0; i < width; ++i) s += i < filled ? '#' : '.';
  char buf[96];
  if (done > 0 && done < total) {
    const double eta = elapsed / double(done) * double(total - done);
    std::snprintf(buf, sizeof buf, "] %3d%% %zu/%zu ETA %.0fs", int(frac * 100), done, total, std::ceil(eta));
  } else {
    std::snprintf(buf, sizeof buf, "] %3d%% %zu/%zu %.1fs", int(frac * 100), done, total, elapsed);
  }
  return s + buf;
}

void Progress::draw(bool force) {
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  auto now = std::chrono::steady_clock::now();
  if (!force && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  lastDraw_ = now;
  double elapsed = std::chrono::duration<double>(now - start_).count();
  std::fprintf(stderr, "\r%s %s", label_.c_str(), render(done_, total_, elapsed).c_str());
  std::fflush(stderr);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (interactive_) {
    draw(true);
    std::fprintf(stderr, "\n");
  } else if (elapsed > 1.0) {
    std::fprintf(stderr, "%s: %zu/%zu in %.1fs\n", label_.c_str(), done_.load(), total_, elapsed);
  }
}

}  // namespace bounce
