#pragma once
// The capture loop as a function, shared by `bounce capture`, `bounce demo` and the capture tests.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "game/timing_stats.hpp"

namespace bounce::game {

struct CaptureOverrides {
  std::string device;
  std::optional<std::vector<std::string>> effects;
  std::optional<std::pair<int, int>> resolution;
};

struct CapturedFrame {
  std::uint32_t index = 0;
  std::filesystem::path png, pfm;
};

struct CaptureResult {
  std::vector<CapturedFrame> frames;
  std::vector<PassStats> passes;
  std::vector<std::string> executedPasses;  // of the last frame
};

CaptureResult runCaptureScript(const std::filesystem::path& script, const std::filesystem::path& out,
                               const CaptureOverrides& overrides = {});

}  // namespace bounce::game
