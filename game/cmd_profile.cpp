// bounce profile LEVEL: per-pass GPU milliseconds (median, p95) over many frames of the level's
// scripted motion, measured side by side in one run. The table ends with the running techniques'
// lines (gi::TechniqueRuntime::profileLines, e.g. VLM's grid overflow); the CSV keeps exactly its
// five timing columns.
#include <cstdio>

#include "engine/core/file.hpp"
#include "engine/core/progress.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"
#include "game/timing_stats.hpp"
#include "game/render_limits.hpp"

namespace bounce::game {

namespace {
}  // namespace

int runProfile(const cli::Args& args) {
  const int frames = args.positiveInt("--frames", 60);
  const auto res = args.resolution("--resolution").value_or(std::pair{1280, 720});
  scene::Level level = loadLevelWithEffects(args.positional[0], args.list("--effects"));
  gpu::Context ctx({args.str("--device")});
  checkRenderSize(ctx, {std::uint32_t(res.first), std::uint32_t(res.second)}, "bounce profile", "--resolution");
  Session session(ctx, level);
  gpu::OffscreenPresenter presenter(ctx, {std::uint32_t(res.first), std::uint32_t(res.second)});
  TimingCollector timings;
  Progress progress("profile", std::size_t(frames) + kWarmupFrames);
  timeFrames(session, presenter, frames, timings, &progress);
  progress.finish();
  const auto rows = timings.stats();
  std::string effects;
  for (const auto& e : session.level().effects.names()) effects += (effects.empty() ? "" : ",") + e;
  std::printf("level %s  effects %s  %dx%d  device %s  frames %zu\n", args.positional[0].c_str(), effects.c_str(),
              res.first, res.second, ctx.deviceName().c_str(), timings.framesCollected());
  std::printf("%s", formatTable(rows).c_str());
  for (const std::string& line : session.profileLines()) std::printf("%s\n", line.c_str());
  if (args.has("--csv")) writeFileAtomic(args.str("--csv"), formatCsv(rows));
  return 0;
}

}  // namespace bounce::game
