// bounce cache --stats | --prune [LEVEL...]: the cache root (engine/core/paths.hpp cacheRoot():
// BOUNCE_CACHE, default <build>/cache), one folder per kind.
//   --stats  entries and bytes per kind
//   --prune  removes, from the given levels' point of view (default: every content/levels/*.json,
//            with its own effects), every entry nobody names, and leftover temporary files of
//            killed jobs:
//              bake kinds (the table's: probes, dnrt)  not named by a bake job of the levels
//              reference                               not named by a level's reference job (the
//                                                      references `bounce accuracy` traces at its
//                                                      defaults: `bounce bake LEVEL --only reference`)
//              cooked (<root>/cooked only)             not the cook of an asset the levels use
//            Other folders (levels/, screenshots, a BOUNCE_COOK_CACHE elsewhere) are left alone.
//            What a pruned entry was for is re-made on next use (cooked, traced, baked).
#include <cstdio>
#include <map>
#include <set>

#include "engine/asset/cook.hpp"
#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/paths.hpp"
#include "engine/scene/asset_instances.hpp"
#include "game/bake_jobs.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"

namespace bounce::game {
namespace fs = std::filesystem;

namespace {

struct KindStats {
  std::size_t entries = 0;
  std::uintmax_t bytes = 0;
};

std::map<std::string, KindStats> stats(const fs::path& root) {
  std::map<std::string, KindStats> out;
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return out;
  for (const auto& kind : fs::directory_iterator(root, ec)) {
    if (!kind.is_directory()) continue;
    KindStats& s = out[kind.path().filename().string()];
    for (const auto& f : fs::recursive_directory_iterator(kind.path(), ec))
      if (f.is_regular_file()) ++s.entries, s.bytes += f.file_size();
  }
  return out;
}

// The cooked-asset keys a level uses: each mesh's cook as every consumer makes it
// (scene::cookOptionsForRef) and the plain cook (options {}: subdivision's node list, VLM authoring).
std::set<std::string> cookedKeys(const scene::Level& level) {
  std::set<std::string> out;
  for (const auto& e : level.entities) {
    if (!e.mesh) continue;
    out.insert(asset::cacheKey(e.mesh->asset, scene::cookOptionsForRef(*e.mesh, cookCacheDir())));
    out.insert(asset::cacheKey(e.mesh->asset, {}));
  }
  return out;
}

}  // namespace

int runCache(const cli::Args& args) {
  if (args.has("--stats") == args.has("--prune"))
    throwInputError("bounce cache", "--stats/--prune", "none or both given", "exactly one of --stats, --prune");
  const fs::path root = cacheRoot();
  if (args.has("--stats")) {
    std::printf("cache %s\n%-12s %8s %12s\n", root.c_str(), "kind", "entries", "MiB");
    KindStats total;
    for (const auto& [kind, s] : stats(root)) {
      std::printf("%-12s %8zu %12.2f\n", kind.c_str(), s.entries, double(s.bytes) / (1024.0 * 1024.0));
      total.entries += s.entries, total.bytes += s.bytes;
    }
    std::printf("%-12s %8zu %12.2f\n", "total", total.entries, double(total.bytes) / (1024.0 * 1024.0));
    return 0;
  }

  std::vector<fs::path> levels;
  for (const auto& p : args.positional) levels.emplace_back(p);
  if (levels.empty()) {
    std::error_code ec;
    for (const auto& f : fs::directory_iterator(contentDir() / "levels", ec))
      if (f.path().extension() == ".json") levels.push_back(f.path());
  }
  std::set<fs::path> keep;
  std::set<std::string> kinds = {std::string(kReferenceKind), "cooked"};
  for (const fs::path& path : levels) {
    const scene::Level level = scene::loadLevel(path);  // a broken level is bad input: nothing is removed
    for (const auto& job : levelJobs(level, cookCacheDir()).jobs) keep.insert(fs::weakly_canonical(job.output));
    for (const auto& job : referenceJobs(level, cookCacheDir())) keep.insert(fs::weakly_canonical(job.output));
    for (const std::string& key : cookedKeys(level)) keep.insert(fs::weakly_canonical(root / "cooked" / (key + ".bcook")));
  }
  for (const gi::Technique* t : gi::techniques())
    if (!t->cacheKind().empty()) kinds.insert(std::string(t->cacheKind()));
  std::size_t removed = 0, kept = 0;
  std::uintmax_t freed = 0;
  for (const std::string& kind : kinds) {
    std::error_code ec;
    const fs::path dir = root / kind;
    if (!fs::is_directory(dir, ec)) continue;
    for (const auto& f : fs::directory_iterator(dir, ec)) {
      if (!f.is_regular_file()) continue;
      if (keep.count(fs::weakly_canonical(f.path()))) {
        ++kept;
        continue;
      }
      freed += f.file_size();
      fs::remove(f.path(), ec);
      ++removed;
    }
  }
  std::printf("pruned %zu entr%s (%.2f MiB) not named by the bake, reference or cook jobs of %zu level(s); kept %zu\n", removed,
              removed == 1 ? "y" : "ies", double(freed) / (1024.0 * 1024.0), levels.size(), kept);
  return 0;
}

}  // namespace bounce::game
