#include "engine/gi/sl/technique.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <optional>

#include "engine/anim/pose.hpp"
#include "engine/core/error.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/log.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/participants.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/incident/session_light.hpp"
#include "engine/gi/resolution.hpp"
#include "engine/scene/components.hpp"

namespace bounce::gi::sl {
namespace {

// The uncut accuracy rows' SLs (influence 0, order 4, fused walk, no hierarchy or local lights), with the
// SLs' bounce in relight's transport on or off and, for the split rows, pass 2's terms.
void configureUncut(scene::Level& level, bool slBounce, std::optional<int> terms) {
  level.probes.slBounce = slBounce;
  for (auto& e : level.entities)
    if (e.sl) {
      e.sl->order = 4;
      e.sl->influence = 0.0f;
      e.sl->hierarchy = false;
      e.sl->fused = true;  // the "terms=" rows' parts must add up to the rows without them
      e.sl->localLights = false;
      if (terms) e.sl->terms = *terms;
    }
}

constexpr std::string_view kCacheKind = "sl";

std::string describe(const std::string& name, const BakeSettings& s) {
  char text[256];
  std::snprintf(text, sizeof text, "sl      %s: %d spheres, order %d, %d directions", name.c_str(), s.spheres, s.order,
                s.directions);
  return text;
}

// One entity's bake, gathered once per job list.
struct ObjectBake {
  std::string name;
  ObjectInput input;
  BakeSettings settings;
  std::filesystem::path output;
};

std::string bakeLine(const ObjectBake& ob, const SphereSet& set, double seconds) {
  std::size_t samples = 0;
  for (const auto& s : set.spheres) samples += s.samples.size();
  char text[512];
  const float bounce = set.spheres.empty() ? 1.0f : set.spheres.front().bounceScale;
  const float shadow = set.spheres.empty() ? 1.0f : set.spheres.front().shadowScale;
  std::snprintf(text, sizeof text,
                ": %.3f s, %zu surface samples, coverage error %.4f, volume overshoot %.3f, bounce scale %.3f, shadow "
                "scale %.3f -> %s",
                seconds, samples, double(set.coverageError), double(set.volumeOvershoot), double(bounce), double(shadow),
                ob.output.c_str());
  return describe(ob.name, ob.settings) + text;
}

SphereSet bakeAndSave(const ObjectBake& ob, std::string* line) {
  const auto start = std::chrono::steady_clock::now();
  SphereSet set = bake(ob.input.object, ob.settings, ob.input.skin);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  save(set, ob.output);
  if (line) *line = bakeLine(ob, set, seconds);
  return set;
}

class SlTechnique final : public Technique {
 public:
  scene::Effect effect() const override { return scene::Effect::Sl; }

  bool takesPart(const LevelContext& lc, std::string* why) const override {
    const bool any = !gi::participantsOf<scene::Sl>(lc.registry).empty();
    if (!any && why) *why = "no entity has an sl component";
    return any;
  }

  std::vector<BakeJob> bakeJobs(const LevelContext& lc, std::string_view part) const override {
    const std::vector<ecs::Entity> entities = gi::participantsOf<scene::Sl>(lc.registry, part);
    ref::ReferenceAssets assets;
    gi::loadAssetsOf(lc.registry, entities, lc.cookCache, assets);
    std::vector<std::filesystem::path> inputs;
    if (!lc.level.source.empty()) inputs.push_back(lc.level.source);
    std::vector<BakeJob> jobs;
    for (ecs::Entity e : entities) {
      auto ob = std::make_shared<ObjectBake>();
      ob->name = lc.registry.get<scene::Name>(e).id;
      ob->input = objectInput(lc.registry, e, assets);
      ob->settings = settingsFrom(lc.registry.get<scene::Sl>(e));
      BakeJob job;
      job.technique = "sl";
      job.what = "sl " + ob->name;
      job.part = ob->name;
      job.key = cacheKey(ob->input, ob->settings);
      ob->output = cachePath(job.key, cacheFolder());
      job.output = ob->output;
      job.inputs = inputs;
      job.inputs.push_back(lc.registry.get<scene::MeshRef>(e).asset);
      job.cached = [ob]() -> std::optional<std::string> {
        if (!gi::cacheEntriesLoad("sl", {ob->output}, [](const std::filesystem::path& p) { load(p); }))
          return std::nullopt;
        return describe(ob->name, ob->settings) + ": cached " + ob->output.string();
      };
      job.run = [ob] {
        std::string line;
        bakeAndSave(*ob, &line);
        return line;
      };
      jobs.push_back(std::move(job));
    }
    return jobs;
  }

  std::string_view cacheKind() const override { return kCacheKind; }

  std::unique_ptr<TechniqueRuntime> create(SessionContext& sc) const override {
    // Pass 2 holds every SL of the frame in uniform blocks of kMaxShadedSpheres (shade.hpp): a level
    // asking for more is bad input, said before anything is baked, not an internal error at frame 0.
    std::size_t spheres = 0;
    const std::vector<ecs::Entity> entities = gi::participantsOf<scene::Sl>(sc.registry);
    for (ecs::Entity e : entities) spheres += std::size_t(sc.registry.get<scene::Sl>(e).spheres);
    if (spheres > kMaxShadedSpheres)
      throw InputError(sc.level.source.string() + ": /entities: " + std::to_string(spheres) + " sl spheres on " +
                       std::to_string(entities.size()) + " entities (expected at most " +
                       std::to_string(kMaxShadedSpheres) + " in all: pass 2 holds them in uniform blocks)");
    // Pass 2 shades every SL of the frame in one draw (blocking couples the objects), so blocking and
    // influence are per level, not per entity: entities that disagree are bad input, not silently the
    // first one's setting.
    const scene::EntityDesc* first = nullptr;
    for (const scene::EntityDesc& e : sc.level.entities) {
      if (!e.sl) continue;
      if (!first) {
        first = &e;
        continue;
      }
      const auto blockingName = [](const scene::Sl& c) { return c.perObject ? "per-object" : "per-sphere"; };
      const auto num = [](float f) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", double(f));
        return std::string(text);
      };
      if (e.sl->perObject != first->sl->perObject)
        throw InputError(sc.level.source.string() + ": " + e.pointer + "/sl/blocking: \"" + blockingName(*e.sl) +
                         "\" differs from entity \"" + first->id + "\"'s \"" + blockingName(*first->sl) +
                         "\" (expected one blocking for every sl entity of a level: pass 2 shades them in one draw)");
      if (e.sl->blockedAtSphere != first->sl->blockedAtSphere)
        throw InputError(sc.level.source.string() + ": " + e.pointer + "/sl/blocked_light: \"" +
                         (e.sl->blockedAtSphere ? "sphere" : "receiver") + "\" differs from entity \"" + first->id + "\"'s \"" +
                         (first->sl->blockedAtSphere ? "sphere" : "receiver") +
                         "\" (expected one blocked_light for every sl entity of a level: pass 2 shades them in one draw)");
      if (e.sl->blockedMap != first->sl->blockedMap)
        throw InputError(sc.level.source.string() + ": " + e.pointer + "/sl/blocked_read: \"" +
                         (e.sl->blockedMap ? "map" : "sh") + "\" differs from entity \"" + first->id + "\"'s \"" +
                         (first->sl->blockedMap ? "map" : "sh") +
                         "\" (expected one blocked_read for every sl entity of a level: pass 2 shades them in one draw)");
      if (e.sl->influence != first->sl->influence)
        throw InputError(sc.level.source.string() + ": " + e.pointer + "/sl/influence: " + num(e.sl->influence) +
                         " differs from entity \"" + first->id + "\"'s " + num(first->sl->influence) +
                         " (expected one influence for every sl entity of a level: pass 2 shades them in one draw)");
      if (e.sl->step != first->sl->step)
        throw InputError(sc.level.source.string() + ": " + e.pointer + "/sl/resolution: \"" +
                         resolutionName(std::uint32_t(e.sl->step)) + "\" differs from entity \"" + first->id +
                         "\"'s \"" + resolutionName(std::uint32_t(first->sl->step)) +
                         "\" (expected one resolution for every sl entity of a level: pass 2 shades them in one draw)");
      if (e.sl->localLights != first->sl->localLights)
        throw InputError(sc.level.source.string() + ": " + e.pointer + "/sl/local_lights: " +
                         (e.sl->localLights ? "true" : "false") + " differs from entity \"" + first->id + "\"'s " +
                         (first->sl->localLights ? "true" : "false") +
                         " (expected one setting for every sl entity of a level: \"sl.local\" shades them in one draw)");
      if (e.sl->hierarchy != first->sl->hierarchy)
        throw InputError(sc.level.source.string() + ": " + e.pointer + "/sl/hierarchy: " +
                         (e.sl->hierarchy ? "true" : "false") + " differs from entity \"" + first->id + "\"'s " +
                         (first->sl->hierarchy ? "true" : "false") +
                         " (expected one setting for every sl entity of a level: pass 2 shades them in one draw)");
      if (e.sl->fused != first->sl->fused)
        throw InputError(sc.level.source.string() + ": " + e.pointer + "/sl/fused: " + (e.sl->fused ? "true" : "false") +
                         " differs from entity \"" + first->id + "\"'s " + (first->sl->fused ? "true" : "false") +
                         " (expected one setting for every sl entity of a level: pass 2 shades them in one draw)");
    }
    // "blocked_read": "map": the SLs' blended direction maps share one uniform block of
    // kMaxMappedSpheres maps (shade.hpp).
    if (first && first->sl->blockedAtSphere && first->sl->blockedMap && spheres > kMaxMappedSpheres)
      throw InputError(sc.level.source.string() + ": " + first->pointer + "/sl/blocked_read: \"map\" with " +
                       std::to_string(spheres) + " sl spheres (expected at most " + std::to_string(kMaxMappedSpheres) +
                       " in all with the direction maps: pass 2 holds one 16² map per SL in a 64 KiB uniform block)");
    // The hierarchy's per-tile ratios travel as kMaxHierarchyObjects flat varyings (node.hpp).
    std::size_t objects = 0;
    for (const scene::EntityDesc& e : sc.level.entities) objects += e.sl ? 1 : 0;
    if (first && first->sl->hierarchy && objects > kMaxHierarchyObjects)
      throw InputError(sc.level.source.string() + ": " + first->pointer + "/sl/hierarchy: true on " +
                       std::to_string(objects) + " sl entities (expected at most " +
                       std::to_string(kMaxHierarchyObjects) + " with the hierarchy: one tile ratio per object)");
    // With the hierarchy pass 2's blocks also hold one parent SL per entity (intensity.cpp setRange_),
    // so the 128 counts spheres and parents together: 2 × 64 spheres + 2 parents is bad input here, not
    // IntensityPass's InternalError at the first frame.
    if (first && first->sl->hierarchy && spheres + entities.size() > kMaxShadedSpheres)
      throw InputError(sc.level.source.string() + ": " + first->pointer + "/sl/hierarchy: true with " +
                       std::to_string(spheres) + " sl spheres + " + std::to_string(entities.size()) +
                       " parents (expected at most " + std::to_string(kMaxShadedSpheres) +
                       " in all with the hierarchy: one parent per entity)");
    auto runtime = std::make_unique<SessionRuntime>(sc.registry, sc.cookCache, cacheFolder());
    runtime->enableGpu(sc);
    return runtime;
  }

  // spheres × SH order × blocking (issue 13), with the probes' indirect light as DNRT's rows have it.
  void accuracyRows(std::vector<AccuracyRow>& rows) const override {
    for (const int spheres : {8, 16, 32})
      for (const int order : {3, 4})
        for (const bool perObject : {false, true}) {
          AccuracyRow r;
          r.technique = "sl";
          r.setting = "spheres=" + std::to_string(spheres) + ";order=" + std::to_string(order) +
                      ";blocking=" + (perObject ? "per-object" : "per-sphere") + ";ref=all";
          r.effects = {"direct", "shadows", "probes", "sl"};
          r.passes = {"shadow", "lighting", "probes", "sl.intensity", "sl"};
          r.optionalPasses = {"sl.shadow"};  // its own pass only unfused (README "SL: one walk for sl and sl.shadow")
          r.configure = [=](scene::Level& level) {
            for (auto& e : level.entities)
              if (e.sl) {
                e.sl->spheres = spheres;
                e.sl->order = order;
                e.sl->perObject = perObject;
                e.sl->localLights = false;  // the rows below have it on
              }
          };
          rows.push_back(std::move(r));
        }
    // §7.3 local lights (issue 13 item 4): the same with the level's point and spot lights as SLs —
    // the objects' shadow on them from "sl.local" instead of the shadow map.
    for (const int spheres : {16, 32})
      for (const bool perObject : {false, true}) {
        AccuracyRow r;
        r.technique = "sl";
        r.setting = "spheres=" + std::to_string(spheres) + ";order=4;blocking=" +
                    (perObject ? "per-object" : "per-sphere") + ";local_lights=on;ref=all";
        r.effects = {"direct", "shadows", "probes", "sl"};
        r.passes = {"shadow", "lighting", "probes", "sl.intensity", "sl", "sl.local"};
        r.optionalPasses = {"sl.shadow"};  // fused into "sl" unless "fused": false
        r.configure = [=](scene::Level& level) {
          for (auto& e : level.entities)
            if (e.sl) {
              e.sl->spheres = spheres;
              e.sl->order = 4;
              e.sl->perObject = perObject;
              e.sl->localLights = true;
            }
        };
        rows.push_back(std::move(r));
      }
    // §7.3 hierarchy (README "SL hierarchy on the GPU"): the level's own spheres and blocking, order 4,
    // the influence cut F at 12 (the default), 6 and 4, without and with the parents standing in for
    // what the cut removes — whether the children's cut can be tighter (cheaper) with the parents on.
    for (const float influence : {12.0f, 6.0f, 4.0f})
      for (const bool hierarchy : {false, true}) {
        AccuracyRow r;
        r.technique = "sl";
        char f[16];
        std::snprintf(f, sizeof f, "%g", double(influence));
        r.setting = std::string("spheres=level;order=4;influence=") + f + ";hierarchy=" + (hierarchy ? "on" : "off") + ";ref=all";
        r.effects = {"direct", "shadows", "probes", "sl"};
        r.passes = {"shadow", "lighting", "probes", "sl.intensity", "sl"};
        // A row runs only where its passes ran; the hierarchy's tile passes only run with it on, and
        // "sl.shadow" is its own pass then (one walk for both terms only without the hierarchy).
        if (hierarchy) r.passes.insert(r.passes.end(), {"sl.hierarchy", "sl.shadow.hierarchy", "sl.shadow"});
        else r.optionalPasses = {"sl.shadow"};
        r.configure = [=](scene::Level& level) {
          for (auto& e : level.entities)
            if (e.sl) {
              e.sl->order = 4;
              e.sl->influence = influence;
              e.sl->hierarchy = hierarchy;
              // "blocked_light": "sphere" is not built with the hierarchy (level.cpp refuses the pair):
              // its rows read the receiver's SH.
              if (hierarchy) e.sl->blockedAtSphere = false;
              e.sl->localLights = false;
            }
        };
        rows.push_back(std::move(r));
      }
    // Uncut (influence 0), without and with the SLs' bounce in relight's transport ("probes":
    // {"sl_bounce": true}; README "SL's bounce in relight's transport, session 15"): the setting is built
    // for pass 2 uncut — at the cut it unbalances bounce and shadow, so only these rows turn it on. On a
    // level without "probes": {"relight": true} the two rows are the same image.
    for (const bool slBounce : {false, true}) {
      AccuracyRow r;
      r.technique = "sl";
      r.setting = std::string("spheres=level;order=4;influence=0;sl_bounce=") + (slBounce ? "on" : "off") + ";ref=all";
      r.effects = {"direct", "shadows", "probes", "sl"};
      r.passes = {"shadow", "lighting", "probes", "sl.intensity", "sl"};
      r.optionalPasses = {"sl.shadow", "sl.relight_bounce"};
      r.configure = [=](scene::Level& level) { configureUncut(level, slBounce, std::nullopt); };
      rows.push_back(std::move(r));
    }
    // Pass 2's resolution (README "SL at quarter resolution, session 10"): the level's own spheres,
    // blocking and influence, order 4, at full, half and quarter resolution with the edge-aware upsample.
    for (const int step : {1, 2, 4}) {
      AccuracyRow r;
      r.technique = "sl";
      r.setting = std::string("spheres=level;order=4;resolution=") + resolutionName(std::uint32_t(step)) +
                  ";ref=all";
      r.effects = {"direct", "shadows", "probes", "sl"};
      r.passes = {"shadow", "lighting", "probes", "sl.intensity", "sl"};
      if (step > 1) r.passes.push_back("sl.upsample");
      r.optionalPasses = {"sl.shadow"};  // fused into "sl" unless "fused": false
      r.configure = [=](scene::Level& level) {
        for (auto& e : level.entities)
          if (e.sl) {
            e.sl->order = 4;
            e.sl->step = step;
            e.sl->localLights = false;
          }
      };
      rows.push_back(std::move(r));
    }
    // What the level's SL adds, one term at a time (README "SL on the characters: what the error is
    // made of"): the fused pass with only the SLs' bounce E (Eq. 13), only the shadow on the probes'
    // light (Eq. 6), or neither (the probes, relit, with SL's passes running) — at the cut F of 12 and 6.
    // The parts add up to the row with both: tools/sl_parts.py reads them from --effect-images.
    for (const float influence : {12.0f, 6.0f})
      for (const auto& [name, terms] : {std::pair{"none", 0}, {"bounce", 1}, {"shadow", 2}}) {
        AccuracyRow r;
        r.technique = "sl";
        char f[16];
        std::snprintf(f, sizeof f, "%g", double(influence));
        r.setting = std::string("spheres=level;order=4;influence=") + f + ";terms=" + name + ";ref=all";
        r.effects = {"direct", "shadows", "probes", "sl"};
        r.passes = {"shadow", "lighting", "probes", "sl.intensity", "sl"};
        r.optionalPasses = {"sl.shadow"};  // never drawn: the rows need the fused pass
        r.configure = [=, terms = terms](scene::Level& level) {
          for (auto& e : level.entities)
            if (e.sl) {
              e.sl->order = 4;
              e.sl->influence = influence;
              e.sl->hierarchy = false;
              e.sl->fused = true;
              e.sl->localLights = false;
              e.sl->terms = terms;
            }
        };
        rows.push_back(std::move(r));
      }
    // The same parts uncut (influence 0), and the bounce part once more with "sl_bounce" (README "SL's
    // bounce on the characters, session 16"): tools/sl_bounce_split.py --influence 0 [--sl-bounce on]
    // splits the rows "influence=0;sl_bounce=off|on" above into relight, bounce and shadow against the
    // black-character reference's parts. Only a row with the bounce bit runs sl.relight_bounce
    // (Node::addTo), so "terms=none" and "terms=shadow" are the same images with it on: not repeated.
    // All four carry "sl_bounce=" so AccuracyRun leaves them out (uncut pass 2's cost in CI).
    for (const auto& [name, terms, slBounce] : {std::tuple{"none", 0, false}, {"bounce", 1, false}, {"shadow", 2, false},
                                                 {"bounce", 1, true}}) {
      AccuracyRow r;
      r.technique = "sl";
      r.setting = std::string("spheres=level;order=4;influence=0;terms=") + name + ";sl_bounce=" + (slBounce ? "on" : "off") +
                  ";ref=all";
      r.effects = {"direct", "shadows", "probes", "sl"};
      r.passes = {"shadow", "lighting", "probes", "sl.intensity", "sl"};
      r.optionalPasses = {"sl.shadow", "sl.relight_bounce"};
      r.configure = [terms = terms, slBounce = slBounce](scene::Level& level) { configureUncut(level, slBounce, terms); };
      rows.push_back(std::move(r));
    }
  }
  // "sl.shadow" runs only beside "probes" (its light is what it shadows), as its own pass only with the
  // hierarchy or "fused": false (else "sl" holds it: README "SL: one walk for sl and sl.shadow").
  std::vector<std::string> passes() const override { return {"sl.intensity", "sl.hierarchy", "sl", "sl.shadow.hierarchy", "sl.shadow", "sl.local"}; }
};

}  // namespace

const Technique& technique() {
  static const SlTechnique t;
  return t;
}

BakeSettings settingsFrom(const scene::Sl& c) {
  BakeSettings s;
  s.spheres = c.spheres;
  s.order = c.order;
  checkSettings(s);
  return s;
}

ObjectInput objectInput(ecs::Registry& registry, ecs::Entity entity, const ref::ReferenceAssets& assets) {
  ObjectInput in;
  in.object = dnrt::objectScene(registry, entity, assets);
  const scene::MeshRef& ref = registry.get<scene::MeshRef>(entity);
  std::size_t indices = 0;
  for (const auto& m : in.object.meshes) indices += m.indices.size();
  if (indices < 3) {
    const auto* name = registry.tryGet<scene::Name>(entity);
    throwInputError(ref.asset.string(), "mesh",
                    "no triangles for the sl spheres of entity " + (name ? name->id : std::string("?")),
                    "a mesh with triangles");
  }
  in.skin = skinOf(assets.get(ref).cpu, instancedPrimitives(assets.get(ref).cpu, ref));
  return in;
}

std::string cacheKey(const ObjectInput& in, const BakeSettings& s) {
  Hasher h;
  h.str("sl-sphere-set-v3");  // baker and BSLSPSET format version: bump when either changes (v3: the subdivided surface cover of sphere_fit.hpp)
  h.pod(s.spheres).pod(s.order).pod(s.directions).pod(s.samplesPerAxis).pod(s.surfaceSamples).pod(s.iterations);
  const ref::SceneDesc& object = in.object;
  ref::hashGeometry(h, object);
  h.u64(in.skin.joints.size());
  for (std::size_t m = 0; m < in.skin.joints.size(); ++m) {
    h.u64(in.skin.joints[m].size()).bytes(in.skin.joints[m].data(), in.skin.joints[m].size() * sizeof(glm::u16vec4));
    h.u64(in.skin.weights[m].size()).bytes(in.skin.weights[m].data(), in.skin.weights[m].size() * sizeof(glm::vec4));
  }
  return h.hex();
}

std::filesystem::path cachePath(const std::string& key, const std::filesystem::path& cacheDir) {
  return cacheDir / ("sl-" + key + ".slset");
}

std::filesystem::path cacheFolder() { return cacheDir(kCacheKind); }

SessionRuntime::SessionRuntime(ecs::Registry& registry, const std::filesystem::path& cookCache,
                               const std::filesystem::path& cacheDir) {
  const std::vector<ecs::Entity> entities = gi::participantsOf<scene::Sl>(registry);
  gi::loadAssetsOf(registry, entities, cookCache, assets_);
  for (ecs::Entity e : entities) {
    Participant p;
    p.entity = e;
    p.name = registry.get<scene::Name>(e).id;
    p.component = registry.get<scene::Sl>(e);
    ObjectBake ob;
    ob.name = p.name;
    ob.input = objectInput(registry, e, assets_);
    ob.settings = settingsFrom(p.component);
    ob.output = cachePath(cacheKey(ob.input, ob.settings), cacheDir);
    bool cached = false;
    if (std::filesystem::exists(ob.output)) {
      try {
        p.set = load(ob.output);
        cached = true;
      } catch (const InputError& err) {
        log::warn(std::string("sl: re-baking a corrupt cache entry: ") + err.what());
      }
    }
    if (!cached) {
      std::string line;
      p.set = bakeAndSave(ob, &line);
      log::info(line);
    }
    const scene::MeshRef& ref = registry.get<scene::MeshRef>(e);
    p.poser = std::make_unique<SpherePoser>(assets_.get(ref).cpu, ref, p.set);
    participants_.push_back(std::move(p));
  }
  update(FrameUpdate{registry, 0.0});
  updateMs_.clear();
}

void SessionRuntime::update(const FrameUpdate& frame) {
  const auto start = std::chrono::steady_clock::now();
  for (Participant& p : participants_) {
    const auto* world = frame.registry.tryGet<scene::WorldTransform>(p.entity);
    p.poser->pose(world ? world->matrix : glm::mat4(1.0f), frame.registry.tryGet<anim::Pose>(p.entity), p.spheres);
  }
  updateMs_.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
}

double SessionRuntime::medianUpdateMs() const {
  if (updateMs_.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> sorted = updateMs_;
  std::sort(sorted.begin(), sorted.end());
  return sorted[sorted.size() / 2];
}

std::vector<std::string> SessionRuntime::profileLines() const {
  if (updateMs_.empty()) return {};
  std::vector<double> sorted = updateMs_;
  std::sort(sorted.begin(), sorted.end());
  std::size_t spheres = 0;
  for (const auto& p : participants_) spheres += p.spheres.size();
  char text[256];
  std::snprintf(text, sizeof text, "sl update: %zu spheres on %zu entities, CPU median %.3f ms over %zu frames (§7.1 poses)",
                spheres, participants_.size(), sorted[sorted.size() / 2], sorted.size());
  return {text};
}

void SessionRuntime::enableGpu(SessionContext& sc) {
  if (participants_.empty()) return;
  std::vector<const SphereSet*> sets;
  int order = 3;
  for (const Participant& p : participants_) {
    sets.push_back(&p.set);
    order = std::max(order, p.set.settings.order);
  }
  const scene::Sl& first = participants_.front().component;  // pass 2's settings: the first participant's
  const Blocking blocking = first.perObject ? Blocking::PerObject : Blocking::PerSphere;
  indirect_ = &incident::sessionLight(sc).indirect();
  blockedMap_ = first.blockedAtSphere && first.blockedMap;
  std::uint32_t spheres = 0;
  for (const Participant& p : participants_) spheres += std::uint32_t(p.set.spheres.size());
  const std::uint64_t range = sc.ctx.limits().maxUniformBufferRange;
  if (blockedMap_ && !mapsFitUniformRange(spheres, range)) {
    // Vulkan guarantees 16 KiB (16 SLs' maps); lavapipe and desktop GPUs give ≥ 64 KiB.
    log::warn(sc.level.source.string() + ": sl: \"blocked_read\": \"map\" needs a " +
              std::to_string(indirectBlockBytes(spheres) / 1024) + " KiB uniform block for " + std::to_string(spheres) +
              " SLs, above this device's maxUniformBufferRange of " + std::to_string(range) +
              " bytes: reading the blocked light from the SH instead");
    blockedMap_ = false;
  }
  node_ = std::make_unique<Node>(sc.ctx, sc.renderer.pipelines(), sc.renderer.frames().framesInFlight(), sets, order,
                                 blocking, first.influence, resolutionFromStep(std::uint32_t(first.step)),
                                 ProbeLight{sc.services.probeVolume, sc.services.probeSh, sc.services.probeMoments},
                                 first.localLights, first.hierarchy, first.fused, std::uint32_t(first.terms),
                                 first.blockedAtSphere, first.tileCut, blockedMap_);
  if (sc.services.relightSlBounce) node_->enableRelightBounce(*sc.services.relightSlBounce);
}

render::Renderer::GraphNode SessionRuntime::node() {
  if (!node_) return [](rg::RenderGraph&, render::PassContext&) {};
  return [this](rg::RenderGraph& graph, render::PassContext& pc) {
    posed_.clear();
    objects_.clear();
    indirectSh_.clear();
    indirectMaps_.clear();
    const bool maps = blockedMap_;
    for (std::size_t o = 0; o < participants_.size(); ++o)
      for (const PosedSphere& s : participants_[o].spheres) {
        posed_.push_back(s);
        objects_.push_back(std::uint32_t(o));
        if (maps) {  // one probe lookup for both: the SH (pass 1) and the blended map (pass 2's blocked light)
          indirectMaps_.emplace_back();
          indirectSh_.push_back(indirect_->radianceShAndMap(s.centre, indirectMaps_.back()));
        } else {
          indirectSh_.push_back(indirect_->radianceSH(s.centre));
        }
      }
    node_->addTo(graph, pc, posed_, objects_, indirectSh_, indirectMaps_);
  };
}

}  // namespace bounce::gi::sl
