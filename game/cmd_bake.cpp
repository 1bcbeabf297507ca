// bounce bake LEVEL [--effects LIST] [--force] [--plan FILE.ninja | --list-jobs | --job KEY]:
// everything the level's effects precompute, as jobs of the table's techniques
// (gi::Technique::bakeJobs), through the same caches play/capture/profile use, with one line per
// job (what, how long, where). Needs no Vulkan device: the bakes run on the CPU with Embree.
//   (no option)  run every job in this process, one after the other; cached entries are skipped
//   --plan F     write a Ninja file, one edge per job: `ninja -f F -j N` bakes them in parallel
//   --list-jobs  the same jobs as JSON lines (key, technique, what, command, inputs, output,
//                extra_outputs) for a job-array scheduler
//   --job KEY    run the one job with content key KEY (the plan's command)
//   --only T[:P] plan only technique T's jobs (or only its part P, e.g. dnrt:prop-truck): the plan's
//                commands pass it so each job's process gathers only its own inputs
// --force re-bakes even when the cache holds a valid entry (to time a bake). A cache entry is only
// trusted after it is read in full and validated (version, sizes, checksum); a corrupt one is
// re-baked.
#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "game/bake_jobs.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"

namespace bounce::game {
namespace {

void runJob(const gi::BakeJob& job, bool force) {
  if (!force)
    if (const auto line = job.cached()) {
      std::printf("%s\n", line->c_str());
      std::fflush(stdout);
      return;
    }
  const std::string line = job.run();
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

}  // namespace

int runBake(const cli::Args& args) {
  const scene::Level level = loadLevelWithEffects(args.positional[0], args.list("--effects"));
  const bool force = args.has("--force");
  const int modes = int(args.has("--plan")) + int(args.has("--list-jobs")) + int(args.has("--job"));
  if (modes > 1) throwInputError("bounce bake", "--plan/--list-jobs/--job", "more than one given", "at most one of them");
  const LevelJobs planned = levelJobs(level, cookCacheDir(), args.str("--only"));

  if (args.has("--job")) {
    const std::string key = args.str("--job");
    for (const auto& job : planned.jobs)
      if (job.key == key) {
        runJob(job, force);
        return 0;
      }
    std::string keys;
    for (const auto& job : planned.jobs) keys += (keys.empty() ? "" : ", ") + job.key;
    throwInputError(level.source.string(), "--job", "no bake job has key " + key,
                    keys.empty() ? "no key: the level's effects bake nothing" : "one of: " + keys);
  }
  for (const auto& note : planned.notes) gi::printNoteOnce(note);
  if (args.has("--plan")) {
    writeFileAtomic(std::filesystem::path(args.str("--plan")), ninjaPlan(level, planned.jobs, cookCacheDir()));
    std::printf("%zu bake job(s) -> %s\n", planned.jobs.size(), args.str("--plan").c_str());
    return 0;
  }
  if (args.has("--list-jobs")) {
    std::fputs(jobLines(level, planned.jobs, cookCacheDir()).c_str(), stdout);
    return 0;
  }
  for (const auto& job : planned.jobs) runJob(job, force);
  if (planned.jobs.empty()) {
    // The techniques that bake, from the table: "neither probes nor dnrt" today.
    std::vector<std::string> baking;
    bool named = false;
    for (const gi::Technique* t : gi::techniques())
      if (!t->cacheKind().empty()) baking.emplace_back(t->name()), named = named || level.effects.has(t->effect());
    std::string list;
    for (std::size_t i = 0; i < baking.size(); ++i)
      list += (i == 0 ? "" : i + 1 == baking.size() ? (baking.size() == 2 ? " nor " : ", nor ") : ", ") + baking[i];
    if (named)
      std::printf("nothing to bake: no entity takes part in the effects that bake\n");
    else
      std::printf("nothing to bake: the effects name %s%s\n", baking.size() == 2 ? "neither " : "none of ", list.c_str());
  }
  return 0;
}

}  // namespace bounce::game
