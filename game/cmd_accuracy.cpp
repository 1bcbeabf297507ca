// bounce accuracy LEVEL: every available technique configuration against the path-traced
// reference; accuracy.csv, an error-vs-GPU-ms chart and per-row heat maps (game/accuracy.hpp).
#include <charconv>
#include <cstdio>
#include <map>

#include "engine/core/error.hpp"
#include "engine/core/paths.hpp"
#include "game/accuracy.hpp"
#include "game/accuracy_rows.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"
#include "game/viewer_level.hpp"

namespace bounce::game {

int runAccuracy(const cli::Args& args) {
  AccuracyOptions o;
  o.level = levelPathFor(args.positional[0]);
  o.out = args.str("--out", "accuracy");
  o.spp = std::uint32_t(args.positiveInt("--spp", int(o.spp)));
  o.measuredFrames = std::uint32_t(args.positiveInt("--frames", int(o.measuredFrames)));
  if (auto res = args.resolution("--resolution")) {
    o.width = std::uint32_t(res->first);
    o.height = std::uint32_t(res->second);
  }
  if (args.has("--frame")) {  // 0 is a valid frame, which Args::positiveInt rejects
    const std::string v = args.str("--frame");
    const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), o.frame);
    if (v.empty() || ec != std::errc() || end != v.data() + v.size())
      throwInputError("bounce accuracy", "--frame", "'" + v + "' is not a valid frame", "a non-negative integer");
  }
  o.device = args.str("--device");
  o.effectImages = args.has("--effect-images");
  if (const auto techniques = args.list("--rows")) {
    for (const auto& t : *techniques)
      if (!scene::effectFromName(t))
        throwInputError("bounce accuracy", "--rows", "unknown technique '" + t + "'", "effect names: " + scene::knownEffectNames());
    o.rows = accuracyRows(*techniques);
  }
  o.referenceCache = cacheDir("reference");
  o.cookCache = cookCacheDir();

  const AccuracyReport report = game::runAccuracy(o);
  std::printf("accuracy %s frame %u: %ux%u, reference %u spp\n", o.level.filename().c_str(), o.frame, o.width, o.height,
              o.spp);
  std::printf("%s", formatAccuracyTable(report.rows).c_str());
  // Skipped rows: one note per technique (a level without VLMs skips all 16 vlm rows for one reason).
  std::map<std::string, std::pair<int, std::string>> skipped;  // technique → count, first reason
  for (const auto& note : report.notes) {
    if (note.rfind("skipped ", 0) == 0) {
      const std::string technique = note.substr(8, note.find(' ', 8) - 8);
      auto& [count, reason] = skipped[technique];
      if (count++ == 0) reason = note.substr(note.find(':') == std::string::npos ? note.size() : note.find(':'));
      continue;
    }
    std::printf("note: %s\n", note.c_str());
  }
  for (const auto& [technique, what] : skipped)
    std::printf("note: skipped %d %s row%s%s\n", what.first, technique.c_str(), what.first == 1 ? "" : "s", what.second.c_str());
  for (const auto& [kind, noise] : report.referenceNoise)
    std::printf("reference ref=%s: estimated noise (rel. RMSE) %.4f\n", kind.c_str(), noise);
  for (const auto& f : report.effectFloors)
    std::printf("reference ref=%s (%u spp): noise floor (what a technique equal to the converged effect scores) "
                "%.4f for the object effect, %.4f for the indirect-only effect\n",
                f.kind.c_str(), f.spp, f.effect, f.indirect);
  for (const auto& warning : report.warnings) std::printf("warning: %s\n", warning.c_str());
  std::printf("wrote %s\n", report.csv.c_str());
  if (report.chart) std::printf("wrote %s\n", report.chart->c_str());
  return 0;
}

}  // namespace bounce::game
