#pragma once
// `bounce bench skinning`: vertices per millisecond of the skinning step, GPU compute pass vs the
// CPU evaluation (engine/anim/skinning.cpp, one core), for CesiumMan, Fox and BrainStem from
// ../shared/assets, and a synthetic cage of many CesiumMan instances (--instances, default 306:
// ~1M vertices). One line per model:
//   model=Fox vertices=1728 joints=24 instances=1 gpu_ms=… gpu_vertices_per_ms=… cpu_ms=… cpu_vertices_per_ms=…
// GPU: median over --frames frames (default 10, after 3 warm-up frames) of the `skinning` pass's
// timestamps; CPU: median over the same count of posing every skinned primitive once.
// The same four models subdivided ("+subdiv": catmull-clark, 1 level, the skinned cage refined
// every frame) add the subdivision step: refined vertices per ms of the `subdivision` pass vs the
// CPU face (LimitStencilJob on TBB's pool), its rate in M vertex·weights/s, and the same stencils
// on one thread (own loop, and OpenSubdiv's Osd::CpuEvaluator):
//   … refined_vertices=… stencil_weights=… subdiv_gpu_ms=… subdiv_gpu_vertices_per_ms=… subdiv_cpu_ms=…
//   subdiv_cpu_vertices_per_ms=… cpu_mweights_per_s=… subdiv_cpu1_ms=… cpu1_mweights_per_s=…
//   cpu1_mweights_per_cpu_s=… osd_cpu1_ms=…
// (cpu1_mweights_per_cpu_s: the one-thread loop per second of its thread's CPU time, which the
// host's other load does not stretch; wall-clock rates on a loaded host do.)
// --only TEXT runs the models whose name contains TEXT.
#include "game/cli.hpp"

namespace bounce::game {

int runBenchSkinning(const cli::Args& args);

}  // namespace bounce::game
