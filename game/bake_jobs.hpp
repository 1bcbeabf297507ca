#pragma once
// A level's bakes as a job graph (DESIGN.md "Scale beyond one machine"): every technique of the
// table the level's effects name lists its jobs (gi::Technique::bakeJobs); `bounce bake` runs them
// in process, writes them as a Ninja file (one edge per job, `bounce bake LEVEL --job KEY` as the
// command, the cache entry as the target) or as JSON lines for any job-array scheduler.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/gi/technique.hpp"
#include "engine/scene/level.hpp"

namespace bounce::game {

// The cache kind, --only value and BakeJob::technique of the reference images: the path-traced
// references `bounce accuracy` compares with are bake jobs too (ref::planReference names their
// entries without tracing). A level names no accuracy run, so they are planned only when asked:
// `--only reference` (all of them) or `--only reference:PART` (accuracyReferences()' parts, e.g.
// "all", "all-static", "direct", "1bounce-half"), at `bounce accuracy`'s defaults (frame 0, 256x256,
// 64 spp).
inline constexpr std::string_view kReferenceKind = "reference";

// The reference jobs of `level` (`part` empty: all of them).
std::vector<gi::BakeJob> referenceJobs(const scene::Level& level, const std::filesystem::path& cookCache,
                                       std::string_view part = {});

struct LevelJobs {
  std::vector<gi::BakeJob> jobs;   // table order, then each technique's order; one per content key
  std::vector<std::string> notes;  // named effects that do not run (gi::effectNote)
};
// Every bake job of the level's named effects (instantiates the level, cooks its assets through the
// cache, hashes the inputs: no bake runs). `only` narrows it to one technique ("dnrt") or one part
// of it ("dnrt:prop-truck", BakeJob::part): what a job's own process plans (`bounce bake --only`);
// "reference[:PART]" plans the reference images instead (referenceJobs).
LevelJobs levelJobs(const scene::Level& level, const std::filesystem::path& cookCache, std::string_view only = {});

// "TECHNIQUE" or "TECHNIQUE:PART": the --only value that plans just `job`.
std::string onlyValue(const gi::BakeJob& job);

// The shell command that runs one job: `BOUNCE_CACHE=… BOUNCE_COOK_CACHE=… <bounce> bake <level>
// --effects <effects> --only <technique[:part]> --job <key>` (absolute paths, quoted for /bin/sh),
// so the job writes exactly the entry the plan names whatever the environment of the runner, and
// plans only itself.
std::string jobCommand(const scene::Level& level, const gi::BakeJob& job, const std::filesystem::path& cookCache);

// The Ninja file: one rule, one edge per job (target: the job's output; inputs: its files).
std::string ninjaPlan(const scene::Level& level, const std::vector<gi::BakeJob>& jobs,
                      const std::filesystem::path& cookCache);

// One JSON object per line: {"key", "technique", "what", "command", "inputs", "output", "extra_outputs"}
// (extra_outputs: BakeJob::extraOutputs, [] when none; the Ninja plan's implicit outputs).
std::string jobLines(const scene::Level& level, const std::vector<gi::BakeJob>& jobs,
                     const std::filesystem::path& cookCache);

}  // namespace bounce::game
