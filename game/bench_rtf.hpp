#pragma once
// `bounce bench rtf` (issue 14), CPU part: the RTF bake and CPCA of every dynamic object of a
// level (default cornell-5: its entities with a `dnrt` component, the level's dynamic props —
// there is no `rtf` level component yet), one line per object
//   object=ID proxies=M clusters=C components=P ratio=R frobenius=E bake_s=… bake_cpu_s=… raw_mb=… compressed_mb=…
// (bake_cpu_s: the process CPU time of the bake, all threads; bake_s is wall time)
// (bake_s=0 cached=1 when the field came from cache/rtf), then the bouncing step (§5, Algorithm 1)
// and the shading step on the CPU (engine/gi/rtf/evaluate.hpp, the test reference) for scenes of
// 1…N of those objects (--objects N: only the first N), one line per scene size:
//   objects=N bounces=B rtf_bounce_cpu_ms=… rtf_shade_cpu_us_per_receiver=… runs=…
// medians over --runs. There is no GPU pass yet, so no rtf_ms and no WxH. The light is a uniform
// environment of radiance 1 (the source's cost is not what is measured).
#include "game/cli.hpp"

namespace bounce::game {

int runBenchRtf(const cli::Args& args);

}  // namespace bounce::game
