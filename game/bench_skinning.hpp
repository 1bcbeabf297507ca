#pragma once
// `bounce bench skinning`: vertices per millisecond of the skinning step, GPU compute pass vs the
// CPU evaluation (engine/anim/skinning.cpp, one core), for CesiumMan, Fox and BrainStem from
// ../shared/assets, and a synthetic cage of many CesiumMan instances (--instances, default 306:
// ~1M vertices). One line per model:
//   model=Fox vertices=1728 joints=24 instances=1 gpu_ms=… gpu_vertices_per_ms=… cpu_ms=… cpu_vertices_per_ms=…
// GPU: median over --frames frames (default 10, after 3 warm-up frames) of the `skinning` pass's
// timestamps; CPU: median over the same count of posing every skinned primitive once.
#include "game/cli.hpp"

namespace bounce::game {

int runBenchSkinning(const cli::Args& args);

}  // namespace bounce::game
