#pragma once
// `bounce bench sl` (issue 13, the paper's §8.3–8.4 analogue): SL's GPU cost against the sphere
// count for per-sphere and per-object blocking. For every N of --counts (default 8,16,32,64,128)
// and both blockings, the level (default content/levels/characters.json) runs with effects
// direct,shadows,sl and N/E spheres on each of its E entities with an `sl` component (N must divide
// evenly and N/E ≤ 64), one session per configuration (the sphere sets bake through the cache on
// first use), and prints one line per configuration:
//   spheres=N blocking=per-sphere|per-object WxH sl_ms=… sl_update_ms=… frames=… influence=F
// (--influence F overrides the level's sl influence, 0 = off: the cost of culling by influence.)
// --fused: effects direct,shadows,probes,sl, so pass 2 is the shipped levels' one walk for the SLs'
// bounce and their shadow on the probes' light (shaders/sl/sl_shadow.frag); the line ends " fused".
// sl_ms: the median GPU ms of pass 1 ("sl.intensity") plus pass 2 ("sl") over the timed frames
// (after 5 warm-up frames); sl_update_ms: the median CPU ms of the §7.1 poses.
#include "game/cli.hpp"

namespace bounce::game {

int runBenchSl(const cli::Args& args);

}  // namespace bounce::game
