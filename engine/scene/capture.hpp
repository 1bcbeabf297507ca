#pragma once
// Capture scripts (README "Capture scripts"): a headless, deterministic run of a level.
// Validated like levels (one-line InputError with a JSON pointer; nothing half-loaded).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/components.hpp"
#include "engine/scene/effects.hpp"

namespace bounce::scene {

struct CaptureScript {
  std::filesystem::path source;  // the script, absolute
  std::filesystem::path level;   // resolved relative to the script, absolute; existed at load
  glm::uvec2 resolution{0};      // each in [1, 16384]
  double dt = 0.0;               // fixed time step, seconds, in (0, 1]
  std::uint32_t frames = 0;      // frames simulated, >= 1
  std::vector<std::uint32_t> capture;  // strictly increasing frame indices, each < frames
  std::optional<Motion> camera;        // motion for the level's active camera (base: its transform)
  std::optional<EffectSet> effects;    // replaces the level's effects when present
};

inline constexpr std::uint32_t kMaxResolution = 16384;
inline constexpr std::uint32_t kMaxFrames = 1u << 24;  // ~3 days at 60 Hz

CaptureScript loadCaptureScript(const std::filesystem::path& path);
// loadCaptureScript on text already in memory (the level fuzz target, tests/fuzz): `path` names the
// file in messages and anchors the level path; it need not exist.
CaptureScript parseCaptureScript(std::string_view text, const std::filesystem::path& path);

}  // namespace bounce::scene
