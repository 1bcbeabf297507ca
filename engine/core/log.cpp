#include "engine/core/log.hpp"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace bounce::log {
namespace {
std::atomic<Level> g_level{Level::Info};
std::atomic<std::size_t> g_warnings{0};
std::mutex g_mutex;

void emit(Level lv, const char* tag, std::string_view msg) {
  if (lv < g_level.load()) return;
  std::lock_guard lock(g_mutex);
  std::fprintf(stderr, "%s%.*s\n", tag, static_cast<int>(msg.size()), msg.data());
}
}  // namespace

void setLevel(Level lv) { g_level = lv; }
Level level() { return g_level; }
void debug(std::string_view m) { emit(Level::Debug, "debug: ", m); }
void info(std::string_view m) { emit(Level::Info, "", m); }
void warn(std::string_view m) {
  ++g_warnings;
  emit(Level::Warn, "warning: ", m);
}
void error(std::string_view m) { emit(Level::Error, "error: ", m); }
std::size_t warningCount() { return g_warnings; }
void resetWarningCount() { g_warnings = 0; }

}  // namespace bounce::log
