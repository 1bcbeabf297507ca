#pragma once
// The one interface through which a GI technique joins a session (DESIGN.md "One shape for every
// GI technique"; Granite's render graph is the model: a large technique plugs in through one small
// interface). A technique is a stateless description — which effect it answers to, whether the
// level calls for it, the bake jobs it needs, the runtime it builds, its `bounce accuracy` rows and
// the passes `bounce profile` times — and a per-session TechniqueRuntime it creates:
//
//   for (const gi::Technique* t : gi::techniques())              // the table (techniques.cpp)
//     if (level.effects.has(t->effect()) && t->takesPart(lc))    // named AND an entity takes part
//       runtimes.push_back(t->create(sc));                       // bakes through the cache if needed
//   each frame:  runtime->update(frame);                          // CPU, after transforms (and skinning)
//                renderer.setNode(t->name(), runtime->node());   // its passes, in table order
//
// Session, `bounce bake`, `bounce accuracy`, `bounce profile` and the play keys iterate the table;
// none of them names a technique. Adding one = its folder under engine/gi/<name>/ (bake.*, its
// data format, update.*, node.*, technique.*), its shaders in shaders/<name>/, its tests in
// tests/unit/<name>/, and one line in techniques.cpp.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/ecs/registry.hpp"
#include "engine/render/renderer.hpp"
#include "engine/scene/effects.hpp"
#include "engine/scene/level.hpp"

namespace bounce::gpu {
class Image;
}

namespace bounce::gi {

namespace probes {
struct ProbeVolume;
class RelightPass;
class ProbeNode;
}
namespace incident {
class SessionLight;
}

// One configuration `bounce accuracy` measures: a row of accuracy.csv.
struct AccuracyRow {
  std::string technique;  // CSV `technique`: the effect name (direct, probes, dnrt, vlm, ssao, hbao, sl, rtf)
  // CSV `setting`: key=value pairs joined by ';' (never a comma, so the CSV needs no quoting),
  // ending with the reference the row is compared with: "ref=direct" (bounces 0), "ref=1bounce"
  // (bounces 1) or "ref=all".
  std::string setting;
  std::vector<std::string> effects;               // the level's effects for this row
  std::optional<std::uint32_t> referenceBounces;  // empty: the full multi-bounce reference
  // The configuration's lighting passes (everything but the G-buffer and tonemap, which every
  // row shares): their summed median GPU time is the row's gpu_ms, and the row is available
  // only when the renderer executes all of them.
  std::vector<std::string> passes;
  // Passes that count towards gpu_ms when the renderer runs them but are not required for the row
  // to be available: DNRT's intrusion maps "dnrt.cube/<object>", present only on objects with
  // intrusion on (so the intrusion-off rows of the same technique still run).
  std::vector<std::string> optionalPasses;
  // Per-technique settings beyond the effect list (probe spacing, SH order, …), applied to the
  // level before it is rendered, with and without its dynamic entities alike. May be empty.
  std::function<void(scene::Level&)> configure;
};

// What participation and bake jobs are decided from: the level instantiated (transforms of t = 0
// resolved) and where its cooked assets are.
struct LevelContext {
  const scene::Level& level;
  ecs::Registry& registry;
  std::filesystem::path cookCache;
};

// One bake as a pure job (DESIGN.md "Scale beyond one machine"): inputs → ONE cache entry named by
// its content key (a hash of every input byte, the settings and the baker/format versions),
// written atomically (temp file + rename: a killed job leaves no entry, two jobs racing on one key
// both leave one valid entry).
struct BakeJob {
  std::string technique;   // effect name: "probes", "dnrt"
  std::string what;        // for people: "probes", "dnrt prop"
  std::string key;         // content key, 16 hex digits; unique among a level's jobs
  // Which of the technique's jobs: the entity id of a per-object bake ("prop-truck"), empty for a
  // per-level one. bakeJobs(lc, part) plans only this one (what `bounce bake --job` runs).
  std::string part;
  std::filesystem::path output;               // the cache entry it writes
  // Further entries the same run writes (DNRT's occlusion-only field), each before `output`, so
  // `output` existing means they do: Ninja implicit outputs (`build OUTPUT | EXTRA: bake`).
  std::vector<std::filesystem::path> extraOutputs;
  std::vector<std::filesystem::path> inputs;  // files it reads (the level, cooked assets)
  // When `output` holds a valid entry (read in full and validated: version, checksum), the line
  // `bounce bake` prints for it; nullopt when it is missing or invalid (then it must be re-baked).
  std::function<std::optional<std::string>()> cached;
  // Bakes and writes `output` (atomically); returns the line `bounce bake` prints.
  std::function<std::string()> run;
};

// Services one technique offers the ones after it in the table (DESIGN.md: the light arriving at a
// point is ONE shared service). Filled by runtimes as they are created, in table order.
struct Services {
  const probes::ProbeVolume* probeVolume = nullptr;  // the probes' baked volume, when they run
  // That volume on the device, as the probes node uploaded it once (shaders/probes/probe_sh.glsl's
  // two images: SH with the valid flag, visibility moments), for passes that read the probes' light
  // the way the probes pass does (sl.shadow) — bound, not uploaded again.
  const gpu::Image* probeSh = nullptr;
  const gpu::Image* probeMoments = nullptr;
  // The probes node itself, for DNRT's fused mode (ProbeNode::setFusedDnrt: its term in the probes pass).
  probes::ProbeNode* probeNode = nullptr;
  // DNRT's fused mode from the other side: set by DNRT's runtime, called by the probes' runtime on its
  // node when the probes are created after DNRT (`bounce play` turning probes on later), so the hook
  // reaches the probes node whichever runtime comes first.
  std::function<void(probes::ProbeNode&)> attachFusedDnrt;
  // Pass "probes.relight" when the level relights the probes with "sl_bounce" (relight_pass.hpp
  // setSlBounce): the SL node writes its surfels' E_SL into it (pass "sl.relight_bounce").
  probes::RelightPass* relightSlBounce = nullptr;
  // The incident-light service's session inputs (incident/session_light.hpp: the indirect source
  // and the static scene's light visibility), created by the first technique that asks through
  // incident::sessionLight(sc); shared_ptr so this header needs no complete type.
  std::shared_ptr<incident::SessionLight> light;
};

// What a technique's runtime is built from.
struct SessionContext {
  gpu::Context& ctx;
  render::Renderer& renderer;
  ecs::Registry& registry;
  const scene::Level& level;
  std::filesystem::path cookCache;
  Services& services;
};

// One frame's CPU inputs: the registry after motion, transforms (and skinning) of time `time`.
struct FrameUpdate {
  ecs::Registry& registry;
  double time = 0.0;  // simulation seconds
};

// A technique as it runs in one session.
class TechniqueRuntime {
 public:
  virtual ~TechniqueRuntime() = default;
  // Per-frame CPU work that does not need the frame's RenderWorld (e.g. SL's sphere poses, RTF's
  // bounce). Techniques whose per-frame work depends on what the frame draws (DNRT's visible
  // objects, VLM's grids over the scene bounds) do it in their node's setup instead.
  virtual void update(const FrameUpdate&) {}
  // Its render-graph node (Renderer::setNode(name, …)): reads "gbuffer.*", "lighting.hdr", … from
  // the blackboard by name and puts back what it writes.
  virtual render::Renderer::GraphNode node() = 0;
  // Lines `bounce profile` prints after the timing table (e.g. VLM's grid overflow).
  virtual std::vector<std::string> profileLines() const { return {}; }
};

class Technique {
 public:
  virtual ~Technique() = default;
  virtual scene::Effect effect() const = 0;
  std::string_view name() const { return scene::effectName(effect()); }
  // Whether some entity of the level takes part (the effect being named is checked by the caller).
  // When not, `why` (may be null) gets what is missing, e.g. "no entity has a dnrt component".
  virtual bool takesPart(const LevelContext& lc, std::string* why) const = 0;
  // Everything it precomputes for the level, one job per cache entry (none: nothing to bake). With
  // `part` non-empty, only the job(s) of that part (BakeJob::part), gathering only their inputs: a
  // job run in its own process plans just itself, so each process of a plan stays cheap.
  virtual std::vector<BakeJob> bakeJobs(const LevelContext&, std::string_view /*part*/) const { return {}; }
  // The cacheDir() kind its jobs write into ("probes", "dnrt"); empty when it bakes nothing.
  // `bounce cache --prune` cleans these folders.
  virtual std::string_view cacheKind() const { return {}; }
  // Its runtime for one session (baking through the cache what is missing). Only called when the
  // effect is named and takesPart() holds.
  virtual std::unique_ptr<TechniqueRuntime> create(SessionContext& sc) const = 0;
  // Its `bounce accuracy` rows (a settings grid), appended in CSV order.
  virtual void accuracyRows(std::vector<AccuracyRow>& rows) const = 0;
  // The outermost passes it adds, as `bounce profile` and the timings name them ("vlm.lights",
  // "vlm"); per-object scopes ("vlm/<entity>") nest inside them.
  virtual std::vector<std::string> passes() const = 0;
};

// THE table (techniques.cpp), in node order: a node may read what an earlier one published ("ao.term")
// and use an earlier one's Services (DNRT's c_j from the probes).
const std::vector<const Technique*>& techniques();
// The table's entry for an effect; null for direct and shadows (the renderer's own passes).
const Technique* findTechnique(scene::Effect effect);

// The one-line note for a technique whose effect is named but that will not run (no entity takes part), e.g.
// "note: effect rtf is named but no entity takes part (no entity has an rtf component): no pass";
// nullopt when it runs.
std::optional<std::string> effectNote(const Technique& technique, const LevelContext& lc);
// Prints a note on stderr once per process (a command building several sessions of one level, as
// `bounce accuracy` does, says it once).
void printNoteOnce(const std::string& note);

}  // namespace bounce::gi
