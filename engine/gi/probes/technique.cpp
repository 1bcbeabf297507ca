#include "engine/gi/probes/technique.hpp"

#include <chrono>
#include <cstdio>

#include "engine/core/paths.hpp"
#include "engine/gi/probes/bake.hpp"
#include "engine/gi/probes/node.hpp"
#include "engine/gi/probes/relight.hpp"
#include "engine/gi/incident/session_light.hpp"
#include "engine/core/log.hpp"

namespace bounce::gi::probes {
namespace {

constexpr std::string_view kCacheKind = "probes";
std::filesystem::path cacheFolder() { return cacheDir(kCacheKind); }

std::string bakeLine(const LoadResult& r, const ProbeSettings& settings) {
  const auto& g = r.volume.grid;
  char line[512];
  std::snprintf(line, sizeof line,
                "probes  %dx%dx%d at %g m, SH order %d, %u rays: %.3f s (%.3f ms/probe, %zu moved out of or off geometry, %zu inside it) -> %s",
                g.count.x, g.count.y, g.count.z, g.spacing, r.volume.order, settings.rays, r.stats.seconds,
                r.stats.msPerProbe(), r.stats.moved, r.stats.invalid, r.file.c_str());
  return line;
}

class ProbesTechnique final : public Technique {
 public:
  scene::Effect effect() const override { return scene::Effect::Probes; }
  // The volume covers the static scene and lights every drawn surface: no component needed.
  bool takesPart(const LevelContext&, std::string*) const override { return true; }

  std::vector<BakeJob> bakeJobs(const LevelContext& lc, std::string_view part) const override {
    if (!part.empty()) return {};  // one per-level job, no parts
    auto input = std::make_shared<BakeInput>(prepare(lc.level, lc.cookCache, settingsFrom(lc.level)));
    BakeJob job;
    job.technique = "probes";
    job.what = "probes";
    job.key = input->key;
    job.output = cachePath(*input, cacheFolder());
    job.inputs = input->files;
    job.cached = [file = job.output]() -> std::optional<std::string> {
      const std::optional<ProbeVolume> v = loadCached(file);
      if (!v) return std::nullopt;
      char line[512];
      std::snprintf(line, sizeof line, "probes  %dx%dx%d at %g m, SH order %d: cached %s", v->grid.count.x,
                    v->grid.count.y, v->grid.count.z, v->grid.spacing, v->order, file.c_str());
      return line;
    };
    job.run = [input] { return bakeLine(bakeToCache(*input, cacheFolder(), /*logBake=*/false), input->settings); };
    std::vector<BakeJob> jobs{job};
    if (lc.level.probes.relight) {  // the relight bake (relight.hpp): surfels and each probe's static transport
      const ProbeGrid grid = gridOf(*input);
      BakeJob r;
      r.technique = "probes";
      r.what = "probes.relight";
      r.output = relightCachePath(*input, grid, cacheFolder());
      r.key = r.output.stem().string().substr(input->key.size() + std::string("-relight-").size());
      r.inputs = input->files;
      r.cached = [file = r.output]() -> std::optional<std::string> {
        const std::optional<RelightData> d = loadCachedRelight(file);
        if (!d) return std::nullopt;
        return "probes.relight  " + std::to_string(d->surfels.size()) + " surfels, " + std::to_string(d->probes()) +
               " probes × " + std::to_string(d->rays) + " rays: cached " + file.string();
      };
      r.run = [input, grid, file = r.output] {
        const auto start = std::chrono::steady_clock::now();
        const RelightData d = bakeRelightToCache(*input, grid, cacheFolder());
        char line[512];
        std::snprintf(line, sizeof line, "probes.relight  %zu surfels, %zu probes × %u rays: %.3f s -> %s", d.surfels.size(),
                      d.probes(), d.rays, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                      file.c_str());
        return std::string(line);
      };
      jobs.push_back(std::move(r));
    }
    return jobs;
  }

  std::string_view cacheKind() const override { return kCacheKind; }

  std::unique_ptr<TechniqueRuntime> create(SessionContext& sc) const override {
    LoadResult baked = loadOrBake(sc.level, sc.cookCache, cacheFolder(), settingsFrom(sc.level));
    auto node = std::make_unique<ProbeNode>(sc.ctx, sc.renderer.pipelines(), std::move(baked.volume));
    sc.services.probeVolume = &node->volume();
    sc.services.probeSh = &node->shImage();
    sc.services.probeMoments = &node->momentsImage();
    sc.services.probeNode = node.get();
    if (sc.services.attachFusedDnrt) sc.services.attachFusedDnrt(*node);  // DNRT was created first
    if (sc.level.probes.relight) {
      // The relight bake (cached under its own key next to the volume) and the static scene's BVH
      // the session already builds for the incident-light service (V_static is traced against it).
      // Techniques that read the probes on the CPU (DNRT's c_j through incident::ProbeSource) keep
      // the baked SH.
      const BakeInput input = prepare(sc.level, sc.cookCache, settingsFrom(sc.level));
      RelightData data = loadOrBakeRelight(input, node->volume().grid, cacheFolder());
      const ref::SceneBvh& bvh = incident::sessionLight(sc).lightVisibility().bvh();
      node->enableRelight(sc.ctx, std::move(data), bvh);
      if (sc.level.probes.slBounce) {
        node->relight()->setSlBounce(true);
        sc.services.relightSlBounce = node->relight();
      }
    }
    return node;
  }

  // The baked irradiance volume (issue 3 §3): two probe spacings × two SH orders, on top of direct
  // light, against the full reference. Spacing and order reach the bake through the level's
  // "probes" settings (`configure`).
  void accuracyRows(std::vector<AccuracyRow>& rows) const override {
    for (const double spacing : {0.25, 0.125})  // metres; the Cornell box is 0.55 m wide
      for (const int order : {2, 3}) {          // SH order as bands: 2 = L1 (4 coefficients), 3 = L2 (9)
        AccuracyRow r;
        r.technique = "probes";
        char setting[96];
        std::snprintf(setting, sizeof setting, "spacing=%gm;sh_order=%d;ref=all", spacing, order);
        r.setting = setting;
        r.effects = {"direct", "shadows", "probes"};
        r.passes = {"shadow", "lighting", "probes"};
        r.optionalPasses = {"probes.tiles"};  // per frame only when relit (a baked volume's are built once)
        r.configure = [spacing, order](scene::Level& level) {
          level.probes.spacing = float(spacing);
          level.probes.order = order;
        };
        rows.push_back(std::move(r));
      }
  }

  std::vector<std::string> passes() const override { return {"probes.tiles", "probes"}; }
};

}  // namespace

const Technique& technique() {
  static const ProbesTechnique t;
  return t;
}

}  // namespace bounce::gi::probes
