#include "game/bench_sl.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "engine/core/error.hpp"
#include "engine/core/paths.hpp"
#include "engine/core/progress.hpp"
#include "engine/gi/resolution.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/gi/sl/sphere_set.hpp"
#include "engine/gi/sl/technique.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "game/bench_dnrt.hpp"
#include "game/session.hpp"
#include "game/timing_stats.hpp"

namespace bounce::game {
namespace {


}  // namespace

int runBenchSl(const cli::Args& args) {
  const std::filesystem::path path =
      args.has("--level") ? std::filesystem::path(args.str("--level")) : contentDir() / "levels" / "characters.json";
  if (!std::filesystem::exists(path))
    throwInputError("bounce bench", "--level", "no level " + path.string(), "a level .json with sl components");
  const scene::Level level = scene::loadLevel(path);
  int entities = 0;
  for (const auto& e : level.entities) entities += e.sl.has_value();
  if (entities == 0) throwInputError(path.string(), "/entities", "no entity has an sl component", "at least one sl component");
  std::vector<int> counts;
  for (const std::string& c : args.list("--counts").value_or(std::vector<std::string>{"8", "16", "32", "64", "128"})) {
    int n = 0;
    try {
      n = std::stoi(c);
    } catch (const std::exception&) {
      n = 0;
    }
    if (n < entities || n % entities != 0 || n / entities > gi::sl::kMaxSpheres)
      throwInputError("bounce bench", "--counts", "'" + c + "' does not split over the level's " + std::to_string(entities) +
                                                     " sl entities",
                      "multiples of " + std::to_string(entities) + " up to " + std::to_string(entities * gi::sl::kMaxSpheres));
    counts.push_back(n);
  }
  const auto res = args.resolution("--resolution").value_or(std::pair{1280, 720});
  const int frames = args.positiveInt("--frames", 3);
  std::optional<float> influence;
  if (args.has("--influence")) {
    double f = -1.0;
    try {
      f = std::stod(args.str("--influence"));
    } catch (const std::exception&) {
    }
    if (!(f == 0.0 || (f >= 3.0 && f <= 1000.0)))
      throwInputError("bounce bench", "--influence", "'" + args.str("--influence") + "' out of range", "0 (off) or 3..1000");
    influence = float(f);
  }

  std::vector<int> steps;  // pass 2's G-buffer pixels per sample per axis (engine/gi/resolution.hpp)
  for (const std::uint32_t step : gi::parseResolutionList(
           args.list("--sl-resolution").value_or(std::vector<std::string>{"full"}), "bounce bench", "--sl-resolution"))
    steps.push_back(int(step));

  const bool fused = args.has("--fused");
  gpu::Context ctx({args.str("--device")});
  gpu::OffscreenPresenter presenter(ctx, {std::uint32_t(res.first), std::uint32_t(res.second)});
  for (int n : counts)
    for (int step : steps)
      for (bool perObject : {false, true}) {
      scene::Level configured = level;
      // --fused: with the probes, "sl" is the shipped levels' one walk for both terms (sl_shadow.frag).
      scene::overrideEffects(configured, fused ? "direct,shadows,probes,sl" : "direct,shadows,sl");
      for (auto& e : configured.entities)
        if (e.sl) {
          e.sl->spheres = n / entities;
          e.sl->perObject = perObject;
          if (influence) e.sl->influence = *influence;
          e.sl->step = step;
          if (fused) e.sl->fused = true;
          // Where the direction maps' uniform block cannot hold n SLs (shade.hpp: kMaxMappedSpheres, and
          // the device's range), a level that reads them (characters.json) is benched with the SH; the
          // line says which it read.
          if (!gi::sl::mapsFitUniformRange(std::uint32_t(n), ctx.limits().maxUniformBufferRange)) e.sl->blockedMap = false;
        }
      TimingCollector timings;
      double updateMs = std::numeric_limits<double>::quiet_NaN();
      bool maps = false;
      {
        Session session(ctx, configured);
        timeFrames(session, presenter, frames, timings);
        if (const auto* rt = session.technique<gi::sl::SessionRuntime>("sl")) {
          updateMs = rt->medianUpdateMs();
          maps = rt->readsDirectionMaps();
        }
      }
      double slMs = 0.0;
      int found = 0;
      std::size_t timed = 0;
      for (const PassStats& s : timings.stats())
        if (s.depth == 0 && s.object.empty() && (s.pass == "sl" || s.pass == "sl.intensity" || s.pass == "sl.upsample")) {
          slMs += s.medianMs;
          ++found;
          timed = s.frames;
        }
      if (found != (step > 1 ? 3 : 2)) throw InternalError("bench sl: the session did not run every SL pass");
      float f = 0.0f;
      for (const auto& e : configured.entities)
        if (e.sl) f = e.sl->influence;
      std::printf("spheres=%d blocking=%s %dx%d sl_ms=%.3f sl_update_ms=%.3f frames=%zu influence=%g resolution=%s "
                  "blocked_read=%s%s\n",
                  n, perObject ? "per-object" : "per-sphere", res.first, res.second, slMs, updateMs, timed, double(f),
                  gi::resolutionName(std::uint32_t(step)), maps ? "map" : "sh", fused ? " fused" : "");
      std::fflush(stdout);
    }
  return 0;
}

}  // namespace bounce::game
