#pragma once
// Minimal leveled logging to stderr. Warnings are counted so tests can assert on them
// (e.g. "dropped 3 degenerate triangles" is a counted, documented repair).
#include <cstddef>
#include <string_view>

namespace bounce::log {

enum class Level { Debug = 0, Info = 1, Warn = 2, Error = 3, Quiet = 4 };

void setLevel(Level level);
Level level();

void debug(std::string_view msg);
void info(std::string_view msg);
void warn(std::string_view msg);
void error(std::string_view msg);

// Number of warnings emitted since start (or since resetWarningCount()).
std::size_t warningCount();
void resetWarningCount();

}  // namespace bounce::log
