#pragma once
// The configurations `bounce accuracy` measures: one row each in accuracy.csv. The direct-light
// rows are here; every technique of the table adds its own (gi::Technique::accuracyRows). A row runs
// only when the renderer has the technique's passes (rowAvailable), so rows for techniques still
// being written are listed, skipped with a note, and start running the day their node lands.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/gi/technique.hpp"
#include "engine/scene/level.hpp"
#include "game/timing_stats.hpp"

namespace bounce::game {

// One configuration (engine/gi/technique.hpp): the techniques' rows come from the table.
using AccuracyRow = gi::AccuracyRow;

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
