// bounce bake LEVEL [--effects LIST] [--force]: everything the level's effects precompute, through
// the same caches play/capture/profile use, with one line per bake (what, where, how long). Needs
// no Vulkan device: probes and DNRT fields are baked on the CPU with Embree.
//   probes  the irradiance volume of the static scene (engine/gi/probes/bake.hpp)
//   dnrt    one neighbouring-transfer field per entity with a `dnrt` component (engine/gi/dnrt/bake.hpp)
// --force re-bakes even when the cache holds a valid entry (to time a bake).
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/probes/bake.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/systems.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"

namespace bounce::game {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void bakeProbes(const scene::Level& level, bool force) {
  const gi::probes::ProbeSettings settings = probeSettings(level);
  // One line per bake: this command prints it, so the bake's own log line is off.
  gi::probes::LoadResult r = gi::probes::loadOrBake(level, cookCacheDir(), probeCacheDir(), settings, false);
  if (r.fromCache && force) {
    std::filesystem::remove(r.file);
    r = gi::probes::loadOrBake(level, cookCacheDir(), probeCacheDir(), settings, false);
  }
  const auto& g = r.volume.grid;
  if (r.fromCache) {
    std::printf("probes  %dx%dx%d at %g m, SH order %d: cached %s\n", g.count.x, g.count.y, g.count.z, g.spacing,
                r.volume.order, r.file.c_str());
    return;
  }
  std::printf("probes  %dx%dx%d at %g m, SH order %d, %u rays: %.3f s (%.3f ms/probe, %zu inside geometry) -> %s\n",
              g.count.x, g.count.y, g.count.z, g.spacing, r.volume.order, settings.rays, r.stats.seconds,
              r.stats.msPerProbe(), r.stats.invalid, r.file.c_str());
}

void bakeDnrt(const scene::Level& level, bool force) {
  gi::dnrt::LevelObjects objects;
  gi::dnrt::loadLevelObjects(level, cookCacheDir(), objects);
  auto& registry = objects.registry;
  const auto& assets = objects.assets;
  const auto& entities = objects.entities;
  if (entities.empty()) std::printf("dnrt    no entity has a dnrt component\n");
  for (ecs::Entity e : entities) {
    const std::string name = registry.get<scene::Name>(e).id;
    const ref::SceneDesc object = gi::dnrt::objectScene(registry, e, assets);
    const gi::dnrt::FieldSettings settings = gi::dnrt::settingsFrom(registry.get<scene::Dnrt>(e));
    const std::filesystem::path path = gi::dnrt::cachePath(object, settings, dnrtCacheDir());
    const int n = settings.grid, rays = settings.samplesPerAxis * settings.samplesPerAxis;
    if (!force && std::filesystem::exists(path)) {
      // bakeCached re-bakes a corrupt entry; report what it did.
      bool cached = false;
      const auto start = std::chrono::steady_clock::now();
      gi::dnrt::bakeCached(object, settings, dnrtCacheDir(), &cached);
      if (cached) {
        std::printf("dnrt    %s: %d^3 x %d rays, %d SH: cached %s\n", name.c_str(), n, rays, settings.shCount, path.c_str());
        continue;
      }
      std::printf("dnrt    %s: %d^3 x %d rays, %d SH: %.3f s (corrupt cache entry re-baked) -> %s\n", name.c_str(), n,
                  rays, settings.shCount, secondsSince(start), path.c_str());
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const gi::dnrt::BakeResult r = gi::dnrt::bake(object, settings);
    const double seconds = secondsSince(start);
    std::filesystem::create_directories(path.parent_path());
    gi::dnrt::save(r.field, path);
    std::printf("dnrt    %s: %d^3 x %d rays, %d SH: %.3f s, %zu vertices inside filled, 8-bit error %.3g (bound %.3g), "
                "ranges %s -> %s\n",
                name.c_str(), n, rays, settings.shCount, seconds, r.insideVertices, r.quantization.maxAbs,
                r.quantization.bound, r.withinAnalyticBound ? "inside the analytic bound (Table 1)" : "OUT OF BOUND",
                path.c_str());
  }
}

}  // namespace

int runBake(const cli::Args& args) {
  scene::Level level = loadLevelWithEffects(args.positional[0], args.list("--effects"));
  const bool force = args.has("--force");
  bool any = false;
  if (level.effects.has(scene::Effect::Probes)) bakeProbes(level, force), any = true;
  if (level.effects.has(scene::Effect::Dnrt)) bakeDnrt(level, force), any = true;
  if (!any) std::printf("nothing to bake: the effects name neither probes nor dnrt\n");
  return 0;
}

}  // namespace bounce::game
