#pragma once
// The configurations `bounce accuracy` measures: one row each in accuracy.csv. Every technique
// adds its rows to accuracyRows() (accuracy_rows.cpp); a row runs only when the renderer has the
// technique's passes (rowAvailable), so rows for techniques still being written are listed,
// skipped with a note, and start running the day their node lands.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/level.hpp"
#include "game/timing_stats.hpp"

namespace bounce::game {

struct AccuracyRow {
  std::string technique;  // CSV `technique`: the effect name (direct, probes, dnrt, vlm, ssao, hbao, sl, rtf)
  // CSV `setting`: key=value pairs joined by ';' (never a comma, so the CSV needs no quoting),
  // ending with the reference the row is compared with: "ref=direct" (bounces 0), "ref=1bounce"
  // (bounces 1) or "ref=all".
  std::string setting;
  std::vector<std::string> effects;               // the level's effects for this row
  std::optional<std::uint32_t> referenceBounces;  // empty: the full multi-bounce reference
  // The configuration's lighting passes (everything but the G-buffer and tonemap, which every
  // row shares): their summed median GPU time is the row's gpu_ms, and the row is available
  // only when the renderer executes all of them.
  std::vector<std::string> passes;
  // Passes that count towards gpu_ms when the renderer runs them but are not required for the row
  // to be available: DNRT's intrusion maps "dnrt.cube/<object>", present only on objects with
  // intrusion on (so the intrusion-off rows of the same technique still run).
  std::vector<std::string> optionalPasses;
  // Per-technique settings beyond the effect list (probe spacing, SH order, …), applied to the
  // level before it is rendered, with and without its dynamic entities alike. May be empty.
  std::function<void(scene::Level&)> configure;
};

// Every configuration of every technique, in CSV order.
std::vector<AccuracyRow> accuracyRows();
// Only the rows of the named techniques (the CLI's --rows); all of them when the list is empty.
std::vector<AccuracyRow> accuracyRows(const std::vector<std::string>& techniques);

// True when every pass the row names is among `executedPasses` (Renderer::executedPasses() of a
// frame rendered with the row's effects).
bool rowAvailable(const AccuracyRow& row, const std::vector<std::string>& executedPasses);

// The row's gpu_ms from one session's timings: the sum of the medians of every OUTERMOST scope
// (PassStats::depth 0) whose pass is in `passes` or `optionalPasses`. Per-object passes such as
// "dnrt.cube/<object>" are outermost and each counts; per-object scopes nested in a pass
// ("dnrt/<object>" inside "dnrt") are already part of that pass's time and are not added again.
double rowGpuMs(const AccuracyRow& row, const std::vector<PassStats>& stats);

}  // namespace bounce::game
