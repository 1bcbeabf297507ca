#include "engine/gi/rtf/technique.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <tuple>
#include <utility>

#include "engine/anim/skinning.hpp"
#include "engine/core/cache_entry.hpp"
#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/participants.hpp"
#include "engine/gi/resolution.hpp"  // header only: the resolution names
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/incident/session_light.hpp"
#include "engine/gi/probes/bake.hpp"
#include "engine/gi/probes/relight.hpp"
#include "engine/gi/rtf/bake.hpp"

namespace bounce::gi::rtf {
namespace {

constexpr std::string_view kCacheKind = "rtf";

std::string describe(const std::string& name, const FieldSettings& s) {
  char text[256];
  std::snprintf(text, sizeof text, "rtf     %s: %d proxies, %d spheres x 6x%dx%d, %d x %d CPCA", name.c_str(), s.proxies,
                s.spheres, s.faceSize, s.faceSize, s.clusters, s.components);
  std::string line = text;
  if (s.byteComponents > 0) line += " (last " + std::to_string(s.byteComponents) + " in 8 bits)";
  return line;
}

std::string nameOf(ecs::Registry& registry, ecs::Entity e) {
  const auto* name = registry.tryGet<scene::Name>(e);
  return name ? name->id : std::to_string(e.index());
}

// The object as its bake sees it; a mesh without triangles is bad input (one line).
ref::SceneDesc objectOf(ecs::Registry& registry, ecs::Entity e, const ref::ReferenceAssets& assets) {
  ref::SceneDesc object = dnrt::objectScene(registry, e, assets);
  std::size_t indices = 0;
  for (const auto& m : object.meshes) indices += m.indices.size();
  if (indices < 3)
    throwInputError(registry.get<scene::MeshRef>(e).asset.string(), "mesh",
                    "no triangles for the rtf field of entity " + nameOf(registry, e), "a mesh with triangles");
  return object;
}

// RTF is for rigid objects (§3: the transfer is baked once in the object's frame): a skinned or
// morphed mesh is baked in its bind pose and its field does not follow the animation. Said once,
// when its field is planned or loaded.
void warnIfDeformed(ecs::Registry& registry, ecs::Entity e, const ref::ReferenceAssets& assets) {
  if (anim::anyDeformed(assets.get(registry.get<scene::MeshRef>(e)).cpu))
    log::warn("rtf " + nameOf(registry, e) + ": the mesh is skinned or morphed; its RTF is baked in the bind pose "
              "and does not follow the animation");
}

struct ObjectBake {
  std::string name;
  ref::SceneDesc object;
  FieldSettings settings;
  std::filesystem::path output;
};

std::string bakeAndSave(const ObjectBake& ob) {
  const auto start = std::chrono::steady_clock::now();
  const BakeResult r = bake(ob.object, ob.settings);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::filesystem::create_directories(ob.output.parent_path());
  save(r.field, ob.output);
  char text[512];
  std::snprintf(text, sizeof text, ": %.3f s, CPCA %.1f:1 at Frobenius error %.4f, %.2f -> %.2f MB -> %s", seconds,
                r.stats.ratio, r.stats.frobenius, r.stats.rawMB, r.stats.compressedMB, ob.output.c_str());
  return describe(ob.name, ob.settings) + text;
}

class RtfTechnique final : public Technique {
 public:
  scene::Effect effect() const override { return scene::Effect::Rtf; }

  bool takesPart(const LevelContext& lc, std::string* why) const override {
    const bool any = !gi::participantsOf<scene::Rtf>(lc.registry).empty();
    if (!any && why) *why = "no entity has an rtf component";
    return any;
  }

  std::vector<BakeJob> bakeJobs(const LevelContext& lc, std::string_view part) const override {
    const std::vector<ecs::Entity> entities = gi::participantsOf<scene::Rtf>(lc.registry, part);
    ref::ReferenceAssets assets;
    gi::loadAssetsOf(lc.registry, entities, lc.cookCache, assets);
    std::vector<std::filesystem::path> inputs;
    if (!lc.level.source.empty()) inputs.push_back(lc.level.source);
    std::vector<BakeJob> jobs;
    for (ecs::Entity e : entities) {
      auto ob = std::make_shared<ObjectBake>();
      ob->name = nameOf(lc.registry, e);
      ob->object = objectOf(lc.registry, e, assets);
      warnIfDeformed(lc.registry, e, assets);
      ob->settings = settingsFrom(lc.registry.get<scene::Rtf>(e));
      BakeJob job;
      job.technique = "rtf";
      job.what = "rtf " + ob->name;
      job.part = ob->name;
      job.key = cacheKey(ob->object, ob->settings);  // ref::hashGeometry + settings + format version
      ob->output = cacheFolder() / ("rtf-" + job.key + ".field");
      job.output = ob->output;
      job.inputs = inputs;
      job.inputs.push_back(lc.registry.get<scene::MeshRef>(e).asset);
      job.cached = [ob]() -> std::optional<std::string> {
        if (!gi::cacheEntriesLoad("rtf", {ob->output}, [](const std::filesystem::path& p) { load(p); }))
          return std::nullopt;
        return describe(ob->name, ob->settings) + ": cached " + ob->output.string();
      };
      job.run = [ob] { return bakeAndSave(*ob); };
      jobs.push_back(std::move(job));
    }
    return jobs;
  }

  std::string_view cacheKind() const override { return kCacheKind; }

  std::unique_ptr<TechniqueRuntime> create(SessionContext& sc) const override {
    return std::make_unique<SessionRuntime>(sc, cacheFolder());
  }

  // RTF on top of probes, against the full multi-bounce reference: 1 and 2 inter-object bounces
  // (the "2 bounces better than 1") shaded with 9 SH, and 2 bounces with 4 SH (what the
  // cheaper "sh": 4 costs in accuracy), applied to every `rtf` entity; the bake settings stay the
  // level's. Its effect_rel_rmse is the number that matters (the static part is the probes').
  void accuracyRows(std::vector<AccuracyRow>& rows) const override {
    // A fourth row: 2 bounces, 9 SH and the 1/|q|² tail to τ = kAccuracyTail (scene::Rtf::tail).
    constexpr float kAccuracyTail = 0.01f;
    for (const std::tuple<int, int, float>& row : {std::tuple{1, 9, 0.0f}, std::tuple{2, 9, 0.0f}, std::tuple{2, 4, 0.0f},
                                                   std::tuple{2, 9, kAccuracyTail}}) {
      // Named copies, not a structured binding: clang 14 cannot capture bindings in the lambda below.
      const int bounces = std::get<0>(row), sh = std::get<1>(row);
      const float tail = std::get<2>(row);
      AccuracyRow r;
      r.technique = "rtf";
      r.setting = (sh == 4 ? "sh=4;" : "") + std::string(tail > 0.0f ? "tail=0.01;" : "") + "bounces=" +
                  std::to_string(bounces) + ";ref=all";
      r.effects = {"direct", "shadows", "probes", "rtf"};
      r.passes = {"shadow", "lighting", "probes", "rtf.bounce", "rtf"};
      r.configure = [bounces, sh, tail](scene::Level& level) {
        level.rtf.step = 1;  // full resolution, whatever the level's "rtf": {"resolution"}
        for (auto& e : level.entities)
          if (e.rtf) e.rtf->bounces = bounces, e.rtf->sh = sh, e.rtf->tail = tail;
      };
      rows.push_back(std::move(r));
    }
    // The shading at half and quarter resolution (the level's "rtf": {"resolution"}): what the reduced
    // draws and their upsample cost in accuracy (2 bounces, 9 and 4 SH), and at quarter the tail, whose
    // extra pixels cost a sixteenth there (1 and 2 bounces, 9 and 4 SH: the 4-SH pair is the cheapest
    // configuration, the one whose per-object cost meets DNRT's like for like; README "RTF's nearer-object
    // occlusion per receiver, session 26").
    for (const std::tuple<std::uint32_t, int, int, float>& row :
         {std::tuple{2u, 2, 9, 0.0f}, std::tuple{4u, 2, 9, 0.0f}, std::tuple{2u, 2, 4, 0.0f}, std::tuple{4u, 2, 4, 0.0f},
          std::tuple{4u, 1, 9, kAccuracyTail}, std::tuple{4u, 2, 9, kAccuracyTail}, std::tuple{4u, 1, 4, kAccuracyTail},
          std::tuple{4u, 2, 4, kAccuracyTail}}) {
      const std::uint32_t step = std::get<0>(row);
      const int bounces = std::get<1>(row), sh = std::get<2>(row);
      const float tail = std::get<3>(row);
      AccuracyRow r;
      r.technique = "rtf";
      r.setting = std::string("resolution=") + gi::resolutionName(step) + ";" + (sh == 4 ? "sh=4;" : "") +
                  (tail > 0.0f ? "tail=0.01;" : "") + "bounces=" + std::to_string(bounces) + ";ref=all";
      r.effects = {"direct", "shadows", "probes", "rtf"};
      r.passes = {"shadow", "lighting", "probes", "rtf.bounce", "rtf", "rtf.upsample"};
      r.configure = [step, bounces, sh, tail](scene::Level& level) {
        level.rtf.step = step;
        for (auto& e : level.entities)
          if (e.rtf) e.rtf->bounces = bounces, e.rtf->sh = sh, e.rtf->tail = tail;
      };
      rows.push_back(std::move(r));
    }
  }
  std::vector<std::string> passes() const override { return {"rtf.bounce", "rtf", "rtf.upsample"}; }
};

}  // namespace

const Technique& technique() {
  static const RtfTechnique t;
  return t;
}

FieldSettings settingsFrom(const scene::Rtf& c) {
  FieldSettings s;
  s.proxies = c.proxies;
  s.spheres = c.spheres;
  s.faceSize = c.face;
  s.raysPerAxis = c.rays;
  s.vertexRaysPerAxis = c.vertexRays;
  s.clusters = c.clusters;
  s.components = c.components;
  s.byteComponents = c.byteComponents;
  s.innerRadius = c.inner;
  s.outerRadius = c.outer;
  checkSettings(s);
  return s;
}

std::filesystem::path cacheFolder() { return cacheDir(kCacheKind); }

SessionRuntime::SessionRuntime(SessionContext& sc, const std::filesystem::path& cacheDir) {
  const std::vector<ecs::Entity> entities = gi::participantsOf<scene::Rtf>(sc.registry);
  ref::ReferenceAssets assets;
  gi::loadAssetsOf(sc.registry, entities, sc.cookCache, assets);
  std::vector<Participant> participants;
  std::vector<ref::SceneDesc> meshes;  // each participant's mesh in its own frame: the lamp's occluders
  for (ecs::Entity e : entities) {
    Participant p;
    p.entity = e;
    p.name = nameOf(sc.registry, e);
    const scene::Rtf& c = sc.registry.get<scene::Rtf>(e);
    p.bounces = c.bounces;
    p.sh = c.sh;
    ObjectBake ob{p.name, objectOf(sc.registry, e, assets), settingsFrom(c), {}};
    warnIfDeformed(sc.registry, e, assets);
    ob.output = cacheDir / ("rtf-" + cacheKey(ob.object, ob.settings) + ".field");
    bool cached = false;
    p.field = loadOrBake(
        ob.output, "rtf: re-baking a corrupt cache entry: ", [](const std::filesystem::path& f) { return load(f); },
        [&] {
          log::info(describe(p.name, ob.settings) + ": baking");
          return bake(ob.object, ob.settings).field;
        },
        [](const Field& f, const std::filesystem::path& path) { save(f, path); }, &cached);
    baked_ += cached ? 0 : 1;
    checkPlaceable(sc.level, sc.registry, e, "rtf", p.field.centre, p.field.radius);  // too small to place: bad input
    p.reach = tailReach(p.field, c.tail);
    participants.push_back(std::move(p));
    meshes.push_back(std::move(ob.object));
  }
  update_ = std::make_unique<Update>(sc.registry, std::move(participants));
  // The proxies' light: the probes (or the level's background) plus the frame's lights, their
  // visibility traced through the level's STATIC geometry and the OTHER posed rtf objects (each
  // object's own mesh left out: Eq. 8's transfer holds its self-shadowing; occluders.hpp); the
  // objects' OOFs then multiply it as Algorithm 1 does.
  incident::SessionLight& light = incident::sessionLight(sc);
  update_->setIndirect(&light.indirect());
  update_->setLightVisibility(&light.lightVisibility());
  update_->setOccluders(std::make_unique<PosedOccluders>(std::move(meshes)), &light.lightVisibility().bvh());
  // The baked probes hold the room lit where the objects shadow it (room_shadows.hpp: the room's albedo
  // at each hit from the textured static scene); a background has no room light. The CPU readers get the baked SH even when the probes are relit (kRelightCpuReaders
  // off, probes/relight.hpp); with it on, the relit SH would hold these shadows already.
  static_assert(!probes::kRelightCpuReaders, "rtf room shadows would count the relit probes' shadows twice");
  update_->setRoomShadows(sc.services.probeVolume != nullptr ? &light.surfaces() : nullptr);
  for (const Participant& p : update_->participants()) xi_.push_back(std::make_unique<XiPass>(sc.ctx, p.field));
  node_ = std::make_unique<Node>(sc.ctx, sc.renderer.pipelines(), sc.renderer.frames().framesInFlight());
  step_ = sc.level.rtf.step;  // "rtf": {"resolution"}
}

render::Renderer::GraphNode SessionRuntime::node() {
  return [this](rg::RenderGraph& graph, render::PassContext& pc) {
    FrameObjects f = update_->frame(pc.world->lights);
    std::vector<NodeObject> objects;
    for (std::size_t o = 0; o < f.participant.size(); ++o) {
      const std::size_t i = f.participant[o];
      objects.push_back({xi_[i].get(), std::move(f.proxyLight[o]), f.records[o], update_->participants()[i].name,
                         std::move(f.shares[o].scale), std::move(f.shares[o].onObjects)});
    }
    node_->addTo(graph, pc, std::move(objects), step_);
  };
}

std::vector<std::string> SessionRuntime::profileLines() const {
  const std::vector<double>& ms = update_->bounceMs();
  if (ms.empty()) return {};
  std::vector<double> sorted = ms;
  std::sort(sorted.begin(), sorted.end());
  char text[256];
  std::snprintf(text, sizeof text, "rtf bouncing step: %zu objects, %d bounces, CPU median %.3f ms over %zu frames (§5, Algorithm 1)",
                update_->participants().size(), update_->bounces(), sorted[sorted.size() / 2], sorted.size());
  return {text};
}

}  // namespace bounce::gi::rtf
