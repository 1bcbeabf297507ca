// The table of GI techniques (engine/gi/technique.hpp) on the CPU: one entry per technique effect
// (every effect but direct and shadows), participation and its notes, bake jobs with content keys, and the
// accuracy rows gathered from the table.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "engine/core/paths.hpp"
#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/technique.hpp"
#include "engine/scene/systems.hpp"
#include "game/accuracy_rows.hpp"
#include "game/bake_jobs.hpp"
#include "game/session.hpp"

namespace bounce {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = BOUNCE_SOURCE_DIR;
const fs::path kCornell1 = kSource / "content/levels/cornell-1.json";
const fs::path kCornell10 = kSource / "content/levels/cornell-10.json";
const fs::path kCornellVlm = kSource / "content/levels/cornell-vlm.json";

// A level instantiated as Session and `bounce bake` see it.
struct Loaded {
  scene::Level level;
  ecs::Registry registry;
  explicit Loaded(const fs::path& path, const std::string& effects = {}) : level(scene::loadLevel(path)) {
    if (!effects.empty()) scene::overrideEffects(level, effects);
    scene::instantiate(level, registry);
    scene::transformSystem(registry);
  }
  gi::LevelContext context() { return {level, registry, game::cookCacheDir()}; }
};

TEST(Techniques, OneEntryPerTechniqueEffectInNodeOrder) {
  std::vector<std::string> names;
  for (const gi::Technique* t : gi::techniques()) names.emplace_back(t->name());
  // AO first (probes read "ao.term"), probes before DNRT (its c_j), RTF last (it adds to all before it).
  EXPECT_EQ(names, (std::vector<std::string>{"ssao", "hbao", "probes", "dnrt", "vlm", "sl", "rtf"}));
  for (int i = 0; i < scene::kEffectCount; ++i) {
    const auto e = scene::Effect(i);
    const bool renderers = e == scene::Effect::Direct || e == scene::Effect::Shadows;
    EXPECT_EQ(gi::findTechnique(e) == nullptr, renderers) << scene::effectName(e);
  }
}

// RTF's entry (issue 14): on a level naming rtf without an rtf entity it takes no part, plans no
// bake, and the level gets the table's "no entity takes part" note.
TEST(Techniques, RtfWithoutParticipantsSaysSo) {
  Loaded l(kCornell1, "direct,rtf");
  const auto lc = l.context();
  const gi::Technique* t = gi::findTechnique(scene::Effect::Rtf);
  ASSERT_NE(t, nullptr);
  EXPECT_FALSE(t->takesPart(lc, nullptr));
  EXPECT_TRUE(t->bakeJobs(lc, {}).empty());
  EXPECT_EQ(t->cacheKind(), "rtf");
  EXPECT_EQ(t->passes(), (std::vector<std::string>{"rtf.bounce", "rtf", "rtf.upsample"}));
  EXPECT_EQ(gi::effectNote(*t, lc), "note: effect rtf is named but no entity takes part (no entity has an rtf component): no pass");
}

TEST(Techniques, NamedWithoutParticipantsGetsOneNote) {
  Loaded noVlm(kCornell1, "direct,vlm");  // cornell-1 has no virtual lights
  EXPECT_EQ(gi::effectNote(*gi::findTechnique(scene::Effect::Vlm), noVlm.context()),
            "note: effect vlm is named but no entity takes part (no entity has a vlm component or a mesh with "
            "extras.bounce_vlm): no pass");
  Loaded noDnrt(kSource / "tests/data/probes/room.json", "direct,dnrt");  // no `dnrt` component
  EXPECT_EQ(gi::effectNote(*gi::findTechnique(scene::Effect::Dnrt), noDnrt.context()),
            "note: effect dnrt is named but no entity takes part (no entity has a dnrt component): no pass");

  Loaded withBoth(kCornell1);
  EXPECT_EQ(gi::effectNote(*gi::findTechnique(scene::Effect::Dnrt), withBoth.context()), std::nullopt);
  EXPECT_EQ(gi::effectNote(*gi::findTechnique(scene::Effect::Probes), withBoth.context()), std::nullopt);
  Loaded vlm(kCornellVlm);
  EXPECT_EQ(gi::effectNote(*gi::findTechnique(scene::Effect::Vlm), vlm.context()), std::nullopt);
}

TEST(Techniques, BakeJobsOnePerCacheEntryWithDistinctKeys) {
  Loaded l(kCornell10);
  const game::LevelJobs planned = game::levelJobs(l.level, game::cookCacheDir());
  EXPECT_TRUE(planned.notes.empty());
  std::size_t probes = 0, dnrt = 0;
  std::set<std::string> keys;
  std::set<fs::path> outputs;
  for (const gi::BakeJob& job : planned.jobs) {
    probes += job.technique == "probes";
    dnrt += job.technique == "dnrt";
    EXPECT_EQ(job.key.size(), 16u) << job.what;
    EXPECT_TRUE(keys.insert(job.key).second) << "duplicate key " << job.key;
    EXPECT_TRUE(outputs.insert(job.output).second) << job.output;
    EXPECT_EQ(job.output.parent_path(), cacheDir(job.technique)) << job.output;
    EXPECT_NE(job.output.filename().string().find(job.key), std::string::npos) << job.output;
    EXPECT_FALSE(job.inputs.empty());
    EXPECT_TRUE(job.cached && job.run);
  }
  EXPECT_EQ(probes, 1u);
  // One field per distinct object of cornell-10's ten `dnrt` entities: the second truck and the
  // second textured box are the same object with the same settings, so they share one entry.
  EXPECT_EQ(dnrt, 8u);
  // The same level planned twice gives the same keys (pure jobs: the key is a function of the inputs).
  const game::LevelJobs again = game::levelJobs(l.level, game::cookCacheDir());
  ASSERT_EQ(again.jobs.size(), planned.jobs.size());
  for (std::size_t i = 0; i < again.jobs.size(); ++i) EXPECT_EQ(again.jobs[i].key, planned.jobs[i].key);
  // A job planned alone (its own process: --only TECHNIQUE:PART) gathers only its inputs and has
  // the same key and output as in the whole plan.
  for (const gi::BakeJob& job : planned.jobs) {
    const game::LevelJobs alone = game::levelJobs(l.level, game::cookCacheDir(), game::onlyValue(job));
    ASSERT_EQ(alone.jobs.size(), 1u) << game::onlyValue(job);
    EXPECT_EQ(alone.jobs[0].key, job.key) << game::onlyValue(job);
    EXPECT_EQ(alone.jobs[0].output, job.output);
  }
  EXPECT_EQ(game::levelJobs(l.level, game::cookCacheDir(), "dnrt").jobs.size(), 8u);
  EXPECT_TRUE(game::levelJobs(l.level, game::cookCacheDir(), "dnrt:no-such-entity").jobs.empty());
}

// `bounce bake --list-jobs`: one JSON object per job, every field of the job in a fixed order, the
// further entries a job writes (BakeJob::extraOutputs, the Ninja plan's implicit outputs) included.
TEST(Techniques, ListJobsJsonHasEveryFieldExtraOutputsIncluded) {
  const scene::Level level = scene::loadLevel(kCornell1);
  gi::BakeJob withExtra, plain;
  withExtra.technique = "dnrt";
  withExtra.what = "dnrt box \"a\" + occlusion";
  withExtra.part = "box";
  withExtra.key = "0123456789abcdef";
  withExtra.output = "/c/dnrt/0123456789abcdef.dnrt";
  withExtra.extraOutputs = {"/c/dnrt/fedcba9876543210.dnrt", "/c/dnrt/x.dnrt"};
  withExtra.inputs = {"/l/level.json", "/l/box.glb"};
  plain.technique = "probes";
  plain.what = "probes";
  plain.key = "00000000000000ff";
  plain.output = "/c/probes/00000000000000ff.probes";
  const std::string cmdA = game::jobCommand(level, withExtra, game::cookCacheDir()),
                    cmdB = game::jobCommand(level, plain, game::cookCacheDir());
  ASSERT_EQ(cmdA.find_first_of("\"\\"), std::string::npos) << "no JSON escapes in " << cmdA;
  ASSERT_EQ(cmdB.find_first_of("\"\\"), std::string::npos) << "no JSON escapes in " << cmdB;
  EXPECT_EQ(game::jobLines(level, {withExtra, plain}, game::cookCacheDir()),
            "{\"key\": \"0123456789abcdef\", \"technique\": \"dnrt\", \"what\": \"dnrt box \\\"a\\\" + occlusion\", "
            "\"command\": \"" + cmdA + "\", \"inputs\": [\"/l/level.json\", \"/l/box.glb\"], "
            "\"output\": \"/c/dnrt/0123456789abcdef.dnrt\", "
            "\"extra_outputs\": [\"/c/dnrt/fedcba9876543210.dnrt\", \"/c/dnrt/x.dnrt\"]}\n"
            "{\"key\": \"00000000000000ff\", \"technique\": \"probes\", \"what\": \"probes\", \"command\": \"" + cmdB +
            "\", \"inputs\": [], \"output\": \"/c/probes/00000000000000ff.probes\", \"extra_outputs\": []}\n");
  // A real one: cornell-1's DNRT objects leave the lights out of their anti-radiance, so each job also
  // writes the occlusion-only field; --list-jobs names it as the plan does.
  Loaded l(kCornell1);
  const game::LevelJobs planned = game::levelJobs(l.level, game::cookCacheDir(), "dnrt");
  ASSERT_FALSE(planned.jobs.empty());
  for (const gi::BakeJob& job : planned.jobs) {
    ASSERT_EQ(job.extraOutputs.size(), 1u) << job.what;
    const std::string line = game::jobLines(l.level, {job}, game::cookCacheDir());
    EXPECT_NE(line.find(", \"extra_outputs\": [\"" + job.extraOutputs[0].string() + "\"]}\n"), std::string::npos) << line;
    EXPECT_NE(game::ninjaPlan(l.level, {job}, game::cookCacheDir()).find(" | " + job.extraOutputs[0].string() + ": bake"),
              std::string::npos);
  }
}

// Issue 11: DNRT jobs are keyed by the cooked asset's content key (objectSourceKey), without
// decoding; the runtime, which keys the object scene it decoded (objectScene sets sourceKey), must
// name the same entries, or a session would re-bake what `bounce bake` wrote.
TEST(Techniques, DnrtJobKeysAreTheRuntimesKeys) {
  Loaded l(kCornell10);
  std::set<std::string> planned;
  for (const gi::BakeJob& job : game::levelJobs(l.level, game::cookCacheDir(), "dnrt").jobs) planned.insert(job.key);
  gi::dnrt::LevelObjects objects;
  gi::dnrt::loadLevelObjects(l.level, game::cookCacheDir(), objects);
  std::set<std::string> runtime;
  for (ecs::Entity e : objects.entities) {
    const ref::SceneDesc object = gi::dnrt::objectScene(objects.registry, e, objects.assets);
    EXPECT_EQ(object.sourceKey, gi::dnrt::objectSourceKey(objects.registry, e, game::cookCacheDir()));
    runtime.insert(gi::dnrt::cacheKey(object, gi::dnrt::settingsFrom(objects.registry.get<scene::Dnrt>(e))));
  }
  EXPECT_EQ(planned, runtime);
  // The source key follows what the object is made of: another albedo is another field.
  const ecs::Entity first = objects.entities.front();
  const auto& mesh = objects.registry.get<scene::MeshRef>(first);
  scene::MaterialOverride red;
  red.albedo = glm::vec3(0.9f, 0.1f, 0.1f);
  EXPECT_NE(gi::dnrt::objectSourceKey("k", mesh, nullptr), gi::dnrt::objectSourceKey("k", mesh, &red));
  EXPECT_NE(gi::dnrt::objectSourceKey("k", mesh, nullptr), gi::dnrt::objectSourceKey("k2", mesh, nullptr));
}

TEST(Techniques, AccuracyRowsComeFromTheTable) {
  std::set<std::string> fromRows;
  for (const auto& r : game::accuracyRows()) fromRows.insert(r.technique);
  std::set<std::string> expected = {"direct"};
  // Every technique that adds passes.
  for (const gi::Technique* t : gi::techniques())
    if (!t->passes().empty()) expected.insert(std::string(t->name()));
  EXPECT_EQ(fromRows, expected);
  // Every row's technique passes are the ones the technique says it adds.
  for (const auto& r : game::accuracyRows()) {
    if (r.technique == "direct") continue;
    const auto e = scene::effectFromName(r.technique);
    ASSERT_TRUE(e);
    const auto passes = gi::findTechnique(*e)->passes();
    for (const auto& p : passes) {
      if (p == "dnrt.cube") continue;  // optional: only objects with intrusion on have it
      if (p == "dnrt.combine.fused") continue;  // only objects in "mode": "fused" beside the probes
      if (p == "dnrt.fused.reduced") continue;  // the same, below full resolution
      // only below full resolution ("dnrt": {"resolution": "half"|"quarter"}), and then the row says so
      if (p == "dnrt.upsample" && !r.setting.starts_with("resolution=")) continue;
      if (p == "rtf.upsample" && !r.setting.starts_with("resolution=")) continue;  // "rtf": {"resolution"}, likewise
      // optional: only levels with "local_lights" on have it, and then their rows say so
      if (p == "sl.local" && r.setting.find("local_lights=on") == std::string::npos) continue;
      // likewise the hierarchy's tile passes (§7.3, "hierarchy": true)
      if ((p == "sl.hierarchy" || p == "sl.shadow.hierarchy") && r.setting.find("hierarchy=on") == std::string::npos) continue;
      // A pass the row lists as optional: "sl.shadow" (folded into "sl" unless the hierarchy is on),
      // "probes.tiles" (a pass only with relit probes; a baked volume builds its tiles once)
      if (std::find(r.optionalPasses.begin(), r.optionalPasses.end(), p) != r.optionalPasses.end()) continue;
      EXPECT_NE(std::find(r.passes.begin(), r.passes.end(), p), r.passes.end()) << r.technique << " " << p;
    }
  }
}

// A DNRT or RTF row measures at the resolution its setting names — "resolution=half;…" half, otherwise
// full — whatever the level's own "dnrt" / "rtf": {"resolution"}: a full-resolution row on a level shading
// at quarter would otherwise measure the quarter draw under a full label (and lack its pass list's upsample).
TEST(Techniques, AccuracyRowsSetTheirOwnResolution) {
  int checked = 0;
  for (const auto& r : game::accuracyRows()) {
    if (r.technique != "dnrt" && r.technique != "rtf") continue;
    const std::uint32_t want = r.setting.starts_with("resolution=half")      ? 2u
                               : r.setting.starts_with("resolution=quarter") ? 4u
                                                                              : 1u;
    for (const std::uint32_t levelStep : {1u, 2u, 4u}) {
      scene::Level level;
      level.dnrt.step = level.rtf.step = levelStep;
      r.configure(level);
      EXPECT_EQ(r.technique == "dnrt" ? level.dnrt.step : level.rtf.step, want) << r.setting << " on a level at step " << levelStep;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 26 + 12);  // DNRT's 24 + 2 reduced, RTF's 4 + 8 reduced
}

}  // namespace
}  // namespace bounce
