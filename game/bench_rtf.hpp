#pragma once
// `bounce bench rtf` (issue 14), CPU part: the RTF bake and CPCA of every dynamic object of a
// level (default cornell-5: its entities with a `dnrt` component, the level's dynamic props), one line per object
//   object=ID proxies=M clusters=C components=P ratio=R frobenius=E bake_s=… bake_cpu_s=… raw_mb=… compressed_mb=…
// (bake_cpu_s: the process CPU time of the bake, all threads; bake_s is wall time)
// (bake_s=0 cached=1 when the field came from cache/rtf; --radii INNER,OUTER sets the spheres' radii in η,
// as a level component's inner/outer), then the bouncing step (§5, Algorithm 1)
// and the shading step on the CPU (engine/gi/rtf/evaluate.hpp, the test reference) for scenes of
// 1…N of those objects (--objects N: only the first N; --object ID with --no-gpu: only that entity,
// any with a mesh, at the settings above), one line per scene size:
//   objects=N bounces=B rtf_bounce_cpu_ms=… rtf_shade_cpu_us_per_receiver=… runs=…
// medians over --runs (the light: a uniform environment of radiance 1; the source's cost is not what
// is measured). Then on the GPU (unless --no-gpu), the level rendered with direct,shadows,probes,rtf
// and the first 1…N of those objects carrying an `rtf` component at these settings, one line each:
//   objects=N bounces=B WxH rtf_bounce_ms=… rtf_ms=… rtf_per_object_ms=… frames=… resolution=full|half|quarter rtf_upsample_ms=…
// rtf_bounce_ms: the ξ pass ("rtf.bounce"); rtf_ms: the shading, pass "rtf" plus "rtf.upsample" below full
// resolution (--rtf-resolution, a list: one line per scene size and resolution; the level's "rtf":
// {"resolution"}); per object: the mean of the "rtf/<id>" scopes (the draws alone); rtf_upsample_ms: the
// upsample (0 at full); GPU medians over --frames (default 30) after 5 warm-up frames.
#include "game/cli.hpp"

namespace bounce::game {

int runBenchRtf(const cli::Args& args);

}  // namespace bounce::game
