#include "game/bake_jobs.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>

#include "engine/core/error.hpp"
#include "engine/core/paths.hpp"
#include "engine/ref/reference.hpp"
#include "engine/scene/systems.hpp"
#include "game/accuracy.hpp"

namespace bounce::game {
namespace {

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Ninja paths: '$', ' ', ':' and newlines are escaped with '$' (ninja_syntax.py's escape_path).
std::string ninjaPath(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '$' || c == ' ' || c == ':' || c == '\n') out += '$';
    out += c;
  }
  return out;
}

// A value in a Ninja variable binding: only '$' and newlines are special there.
std::string ninjaValue(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '$' || c == '\n') out += '$';
    out += c;
  }
  return out;
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += char(c);
        }
    }
  }
  return out + "\"";
}

std::string effectList(const scene::Level& level) {
  std::string list;
  for (const auto& e : level.effects.names()) list += (list.empty() ? "" : ",") + e;
  return list;
}

}  // namespace

std::vector<gi::BakeJob> referenceJobs(const scene::Level& level, const std::filesystem::path& cookCache,
                                       std::string_view part) {
  AccuracyOptions options;  // `bounce accuracy`'s defaults: frame 0, 256x256, 64 spp
  options.level = level.source;
  options.referenceCache = cacheDir(kReferenceKind);
  options.cookCache = cookCache;
  options.progress = false;  // a job's own progress would interleave under ninja; its line says enough
  std::vector<gi::BakeJob> jobs;
  for (AccuracyReference& r : accuracyReferences(options)) {
    if (!part.empty() && r.part != part) continue;
    r.request.progress = false;
    const ref::ReferencePlan plan = ref::planReference(r.request);
    gi::BakeJob job;
    job.technique = std::string(kReferenceKind);
    job.what = "reference " + r.part;
    job.key = plan.key;
    job.part = r.part;
    job.output = plan.cachePath;
    job.inputs = {level.source};
    for (const auto& e : level.entities)
      if (e.mesh && std::find(job.inputs.begin(), job.inputs.end(), e.mesh->asset) == job.inputs.end())
        job.inputs.push_back(e.mesh->asset);
    const auto request = std::make_shared<const ref::ReferenceRequest>(r.request);
    const std::string what = job.what;
    job.cached = [plan, what]() -> std::optional<std::string> {
      if (!ref::loadCachedReference(plan.cachePath, plan.width, plan.height)) return std::nullopt;
      return what + ": cached " + plan.cachePath.string();
    };
    job.run = [request, what] {
      const ref::ReferenceResult res = ref::renderReference(*request);
      char text[256];
      std::snprintf(text, sizeof text, ": %ux%u, %u spp, %.2f s, %.2f M rays/s -> ", res.image.width, res.image.height,
                    request->spp.value_or(ref::kDefaultSpp), res.stats.seconds, res.stats.raysPerSecond() * 1e-6);
      return what + text + res.cachePath.string();
    };
    jobs.push_back(std::move(job));
  }
  return jobs;
}

std::string onlyValue(const gi::BakeJob& job) { return job.part.empty() ? job.technique : job.technique + ":" + job.part; }

LevelJobs levelJobs(const scene::Level& level, const std::filesystem::path& cookCache, std::string_view only) {
  const std::size_t colon = only.find(':');
  const std::string_view onlyTechnique = only.substr(0, colon);
  const std::string_view onlyPart = colon == std::string_view::npos ? std::string_view{} : only.substr(colon + 1);
  LevelJobs out;
  if (onlyTechnique == kReferenceKind) {  // the references `bounce accuracy` compares with
    out.jobs = referenceJobs(level, cookCache, onlyPart);
    return out;
  }
  if (!only.empty()) {
    const auto e = scene::effectFromName(onlyTechnique);
    if (!e || !gi::findTechnique(*e))
      throwInputError(level.source.string(), "--only", "no technique " + std::string(onlyTechnique),
                      "TECHNIQUE or TECHNIQUE:PART, TECHNIQUE one of the table's (probes, dnrt, ...) or reference");
  }
  ecs::Registry registry;
  scene::instantiate(level, registry);
  scene::transformSystem(registry);
  const gi::LevelContext lc{level, registry, cookCache};
  for (const gi::Technique* t : gi::techniques()) {
    if (!level.effects.has(t->effect())) continue;
    if (!only.empty() && t->name() != onlyTechnique) continue;
    if (const auto note = gi::effectNote(*t, lc)) {
      out.notes.push_back(*note);
      continue;
    }
    for (auto& job : t->bakeJobs(lc, onlyPart)) {
      // Content keys name outputs: two entities with the same object and settings (cornell-10's two
      // trucks) share one entry, so one job bakes it.
      auto same = std::find_if(out.jobs.begin(), out.jobs.end(), [&](const gi::BakeJob& j) { return j.key == job.key; });
      if (same == out.jobs.end())
        out.jobs.push_back(std::move(job));
      else
        same->what += " (also " + job.what + ")";
    }
  }
  return out;
}

std::string jobCommand(const scene::Level& level, const gi::BakeJob& job, const std::filesystem::path& cookCache) {
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe");
  return "BOUNCE_CACHE=" + shellQuote(cacheRoot().string()) + " BOUNCE_COOK_CACHE=" + shellQuote(cookCache.string()) +
         " " + shellQuote(exe.string()) + " bake " + shellQuote(level.source.string()) + " --effects " +
         shellQuote(effectList(level)) + " --only " + shellQuote(onlyValue(job)) + " --job " + job.key;
}

std::string ninjaPlan(const scene::Level& level, const std::vector<gi::BakeJob>& jobs,
                      const std::filesystem::path& cookCache) {
  std::string out = "# bounce bake " + level.source.string() + " --plan: one edge per bake job (" +
                    std::to_string(jobs.size()) + "), run with `ninja -f FILE -j N`.\n"
                    "ninja_required_version = 1.3\n\n"
                    "rule bake\n"
                    "  command = $cmd\n"
                    "  description = bake $what\n\n";
  for (const auto& job : jobs) {
    out += "build " + ninjaPath(job.output.string());
    if (!job.extraOutputs.empty()) out += " |";
    for (const auto& extra : job.extraOutputs) out += " " + ninjaPath(extra.string());
    out += ": bake";
    for (const auto& in : job.inputs) out += " " + ninjaPath(in.string());
    out += "\n  cmd = " + ninjaValue(jobCommand(level, job, cookCache)) + "\n";
    out += "  what = " + ninjaValue(job.what + " " + job.key) + "\n";
  }
  out += "\nbuild all: phony";
  for (const auto& job : jobs) out += " " + ninjaPath(job.output.string());
  out += "\ndefault all\n";
  return out;
}

std::string jobLines(const scene::Level& level, const std::vector<gi::BakeJob>& jobs,
                     const std::filesystem::path& cookCache) {
  std::string out;
  for (const auto& job : jobs) {
    out += "{\"key\": " + jsonString(job.key) + ", \"technique\": " + jsonString(job.technique) +
           ", \"what\": " + jsonString(job.what) + ", \"command\": " + jsonString(jobCommand(level, job, cookCache)) +
           ", \"inputs\": [";
    for (std::size_t i = 0; i < job.inputs.size(); ++i) out += (i ? ", " : "") + jsonString(job.inputs[i].string());
    out += "], \"output\": " + jsonString(job.output.string()) + ", \"extra_outputs\": [";
    // The further entries the same run writes (BakeJob::extraOutputs; the plan's implicit outputs).
    for (std::size_t i = 0; i < job.extraOutputs.size(); ++i) out += (i ? ", " : "") + jsonString(job.extraOutputs[i].string());
    out += "]}\n";
  }
  return out;
}

}  // namespace bounce::game
