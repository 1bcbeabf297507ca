// RTF in the technique table (issue 14, step 1–2) on the CPU: the level component (strict parsing,
// one-line errors), participation, the bake job (content key, cache entry, the line it prints, a
// corrupt entry re-baked), and the per-frame update (the bouncing step of Algorithm 1 and the
// records the shading pass reads) against evaluate.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/participants.hpp"
#include "engine/gi/rtf/overlap.hpp"
#include "engine/gi/rtf/technique.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"
#include "engine/scene/level.hpp"
#include "engine/scene/systems.hpp"
#include "tests/support/level_errors.hpp"
#include "tests/support/technique_level.hpp"
#include "tests/support/box_mesh.hpp"
#include "tests/support/point_light.hpp"

namespace bounce::gi::rtf {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = BOUNCE_SOURCE_DIR;
fs::path outDir() { return fs::path(BOUNCE_TEST_OUT) / "rtf"; }
// The shared helpers (tests/support/technique_level.hpp) with this folder and the effects [direct, rtf].
using testlevel::boxAsset, testlevel::cookCache, testlevel::Loaded;
std::string mesh() { return testlevel::boxMesh(); }
fs::path writeLevel(const std::string& name, const std::string& entities, const std::string& effects = R"(["direct", "rtf"])") {
  return testlevel::writeLevel(outDir(), name, entities, effects);
}
std::string loadError(const std::string& name, const std::string& entity) {
  return testlevel::loadError(outDir(), name, entity, R"(["direct", "rtf"])");
}
// Test-sized settings: a bake of the 24-vertex box in well under a second.
const std::string kTiny = R"("proxies": 2, "spheres": 3, "face": 2, "rays": 4, "vertex_rays": 4, "clusters": 2, "components": 2)";

TEST(RtfComponent, ParsesWithDefaults) {
  const fs::path path = writeLevel("rtf-ok", R"({"id": "a", "dynamic": true, )" + mesh() +
                                                 R"(, "rtf": {"proxies": 12, "bounces": 3, "spheres": 6, "face": 4, "rays": 16,
                                                   "vertex_rays": 6, "clusters": 5, "components": 0, "inner": 0.25, "outer": 6,
                                                   "sh": 4, "tail": 0.02}},
                                                 {"id": "b", "dynamic": true, )" + mesh() + R"(, "rtf": {}})");
  const scene::Level level = scene::loadLevel(path);
  ASSERT_EQ(level.entities.size(), 2u);
  EXPECT_EQ(level.entities[0].rtf, (scene::Rtf{12, 3, 6, 4, 16, 6, 5, 0, 0, 0.25f, 6.0f, 4, 0.02f}));
  EXPECT_EQ(level.entities[1].rtf, scene::Rtf{});
  EXPECT_EQ(level.entities[1].rtf->sh, 9);
  EXPECT_EQ(level.entities[1].rtf->tail, 0.0f);  // no tail: the field ends at r_N + Δr
  const FieldSettings s = settingsFrom(*level.entities[0].rtf);
  EXPECT_EQ(s.proxies, 12);
  EXPECT_EQ(s.spheres, 6);
  EXPECT_EQ(s.faceSize, 4);
  EXPECT_EQ(s.raysPerAxis, 16);
  EXPECT_EQ(s.vertexRaysPerAxis, 6);
  EXPECT_EQ(s.clusters, 5);
  EXPECT_EQ(s.components, 0);
  EXPECT_EQ(s.innerRadius, 0.25f);
  EXPECT_EQ(s.outerRadius, 6.0f);
}

TEST(RtfComponent, BadInputIsOneLine) {
  const std::string dyn = R"({"id": "a", "dynamic": true, )" + mesh();
  EXPECT_EQ(loadError("rtf-proxies", dyn + R"(, "rtf": {"proxies": 65}})"),
            "FILE: /entities/0/rtf/proxies: 65 is out of range (expected an integer in [1, 64])");
  EXPECT_EQ(loadError("rtf-bounces0", dyn + R"(, "rtf": {"bounces": 0}})"),
            "FILE: /entities/0/rtf/bounces: 0 is out of range (expected an integer in [1, 4])");
  EXPECT_EQ(loadError("rtf-bounces5", dyn + R"(, "rtf": {"bounces": 5}})"),
            "FILE: /entities/0/rtf/bounces: 5 is out of range (expected an integer in [1, 4])");
  EXPECT_EQ(loadError("rtf-spheres", dyn + R"(, "rtf": {"spheres": 1}})"),
            "FILE: /entities/0/rtf/spheres: 1 is out of range (expected an integer in [2, 64])");
  EXPECT_EQ(loadError("rtf-bounces-type", dyn + R"(, "rtf": {"bounces": "two"}})").rfind("FILE: /entities/0/rtf/bounces: ", 0), 0u);
  EXPECT_EQ(loadError("rtf-outer", dyn + R"(, "rtf": {"inner": 2, "outer": 2}})"),
            "FILE: /entities/0/rtf/outer: outer radius 2 is not above inner 2 (expected outer > inner (defaults 0.5 and 4))");
  EXPECT_EQ(loadError("rtf-inner", dyn + R"(, "rtf": {"inner": 5}})"),
            "FILE: /entities/0/rtf/inner: outer radius 4 is not above inner 5 (expected outer > inner (defaults 0.5 and 4))");
  EXPECT_EQ(loadError("rtf-sh", dyn + R"(, "rtf": {"sh": 5}})"), "FILE: /entities/0/rtf/sh: SH count 5 (expected 4 or 9)");
  EXPECT_EQ(loadError("rtf-tail", dyn + R"(, "rtf": {"tail": 1}})"),
            "FILE: /entities/0/rtf/tail: 1 is out of range (expected a number in [0, 1))");
  EXPECT_EQ(loadError("rtf-tail-neg", dyn + R"(, "rtf": {"tail": -0.1}})"),
            "FILE: /entities/0/rtf/tail: -0.1 is out of range (expected a number in [0, 1))");
  EXPECT_EQ(loadError("rtf-bytes", dyn + R"(, "rtf": {"components": 8, "byte_components": 9}})"),
            "FILE: /entities/0/rtf/byte_components: 9 is above components 8 (expected an integer in [0, components]: the 8-bit "
            "tail is part of the components)");
  EXPECT_EQ(loadError("rtf-bytes-default", dyn + R"(, "rtf": {"byte_components": 5}})"),
            "FILE: /entities/0/rtf/byte_components: 5 is above components 4 (expected an integer in [0, components]: the 8-bit "
            "tail is part of the components)");  // components' default (4) bounds it too
  EXPECT_EQ(loadError("rtf-bytes-neg", dyn + R"(, "rtf": {"byte_components": -1}})"),
            "FILE: /entities/0/rtf/byte_components: -1 is out of range (expected an integer in [0, 256])");
  EXPECT_EQ(loadError("rtf-key", dyn + R"(, "rtf": {"proxy": 8}})").rfind("FILE: /entities/0/rtf/proxy: unknown key", 0), 0u);
  EXPECT_EQ(loadError("rtf-static", R"({"id": "a", )" + mesh() + R"(, "rtf": {}})"),
            "FILE: /entities/0/rtf: a radiance transfer field on a static entity (expected \"dynamic\": true or a motion)");
  EXPECT_EQ(loadError("rtf-no-mesh", R"({"id": "a", "dynamic": true, "rtf": {}})"),
            "FILE: /entities/0/rtf: a radiance transfer field on an entity without a mesh (expected a \"mesh\" key)");
}

// The level's own "rtf": {"resolution"} (beside the entities' fields): the shading draws' step, default
// full (1) — no shipped level sets it — "half" 2, "quarter" 4; anything else is one line at its place
// (the `bounce` binary's exit 2 is the same InputError).
TEST(RtfLevel, ResolutionKeyAndItsBadInput) {
  const auto levelWith = [&](const std::string& name, const std::string& rtfLevelJson) {
    const fs::path path = outDir() / (name + ".json");
    fs::create_directories(outDir());
    writeFileAtomic(path, R"({"bounce_level": 1, "effects": ["direct", "rtf"], "rtf": )" + rtfLevelJson +
                              R"(, "entities": [{"id": "a", "dynamic": true, )" + mesh() + R"(, "rtf": {}}]})");
    return path;
  };
  for (const char* shipped : {"cornell-5", "cornell-rtf"})
    EXPECT_EQ(scene::loadLevel(kSource / "content/levels" / (std::string(shipped) + ".json")).rtf.step, 1u) << shipped;
  EXPECT_EQ(scene::loadLevel(levelWith("rtf-res-default", "{}")).rtf.step, 1u);
  EXPECT_EQ(scene::loadLevel(levelWith("rtf-res-full", R"({"resolution": "full"})")).rtf.step, 1u);
  EXPECT_EQ(scene::loadLevel(levelWith("rtf-res-half", R"({"resolution": "half"})")).rtf.step, 2u);
  EXPECT_EQ(scene::loadLevel(levelWith("rtf-res-quarter", R"({"resolution": "quarter"})")).rtf.step, 4u);
  EXPECT_EQ(scene::loadLevel(levelWith("rtf-res-quarter", R"({"resolution": "quarter"})")).dnrt.step, 1u)
      << "the rtf key is not DNRT's";
  testlevel::expectResolutionKeyErrors("rtf", "bounces", [&](const std::string& json) { return levelWith("rtf-res-bad", json); });
}

TEST(RtfTechnique, TakesPartAndBakesOneEntryPerEntity) {
  const Technique& t = technique();
  EXPECT_EQ(t.cacheKind(), "rtf");
  Loaded none(writeLevel("rtf-none", R"({"id": "a", "dynamic": true, )" + mesh() + "}"));
  EXPECT_EQ(effectNote(t, none.context()),
            "note: effect rtf is named but no entity takes part (no entity has an rtf component): no pass");
  Loaded l(writeLevel("rtf-box", R"({"id": "box", "dynamic": true, )" + mesh() + R"(, "rtf": {)" + kTiny + "}}"));
  const auto lc = l.context();
  EXPECT_EQ(effectNote(t, lc), std::nullopt);
  const auto jobs = t.bakeJobs(lc, {});
  ASSERT_EQ(jobs.size(), 1u);
  const BakeJob& job = jobs[0];
  EXPECT_EQ(job.technique, "rtf");
  EXPECT_EQ(job.part, "box");
  EXPECT_EQ(job.key.size(), 16u);
  EXPECT_EQ(job.output, cacheFolder() / ("rtf-" + job.key + ".field"));
  EXPECT_TRUE(t.bakeJobs(lc, "no-such-entity").empty());
  ASSERT_EQ(t.bakeJobs(lc, "box").size(), 1u);
  EXPECT_EQ(t.bakeJobs(lc, "box")[0].key, job.key);  // planned alone: same key
  // The bounce count is a run-time setting: same entry. A bake setting is another entry.
  Loaded bounces(writeLevel("rtf-box-b3", R"({"id": "box", "dynamic": true, )" + mesh() + R"(, "rtf": {)" + kTiny +
                                               R"(, "bounces": 3}})"));
  EXPECT_EQ(t.bakeJobs(bounces.context(), {})[0].key, job.key);
  Loaded sh4(writeLevel("rtf-box-sh4", R"({"id": "box", "dynamic": true, )" + mesh() + R"(, "rtf": {)" + kTiny + R"(, "sh": 4}})"));
  EXPECT_EQ(t.bakeJobs(sh4.context(), {})[0].key, job.key);  // the receiver's SH count: run time too
  Loaded other(writeLevel("rtf-box-p3", R"({"id": "box", "dynamic": true, )" + mesh() +
                                            R"(, "rtf": {"proxies": 3, "spheres": 3, "face": 2, "rays": 4, "vertex_rays": 4, "clusters": 2, "components": 2}})"));
  EXPECT_NE(t.bakeJobs(other.context(), {})[0].key, job.key);

  fs::remove(job.output);
  EXPECT_EQ(job.cached(), std::nullopt);
  const std::string line = job.run();
  EXPECT_EQ(line.rfind("rtf     box: 2 proxies, 3 spheres x 6x2x2, 2 x 2 CPCA: ", 0), 0u) << line;
  EXPECT_NE(line.find(" MB -> " + job.output.string()), std::string::npos) << line;
  const Field f = load(job.output);
  EXPECT_EQ(f.settings.proxies, 2);
  EXPECT_EQ(f.proxies.size(), 2u);
  EXPECT_EQ(sampleCount(f.settings), 3u * 6u * 4u);
  EXPECT_EQ(job.cached(), "rtf     box: 2 proxies, 3 spheres x 6x2x2, 2 x 2 CPCA: cached " + job.output.string());
  // A corrupt entry is not "cached" (it is re-baked).
  writeFileAtomic(job.output, std::string("BRTFFLD garbage"));
  EXPECT_EQ(job.cached(), std::nullopt);
  fs::remove(job.output);
}

// "byte_components" (the CPCA's 8-bit tail, n₈) reaches the bake from the level: its own cache entry,
// a field file whose CPCA stores that many components in 8 bits, and the job's line says so.
TEST(RtfTechnique, ByteComponentsReachTheBakeAndTheCacheKey) {
  const Technique& t = technique();
  // Its own settings (vertex_rays 3, 3 components): no other test's entry is shared or removed.
  const std::string kSmall = R"("proxies": 2, "spheres": 3, "face": 2, "rays": 4, "vertex_rays": 3, "clusters": 2, "components": 3)";
  Loaded plain(writeLevel("rtf-box-n0", R"({"id": "box", "dynamic": true, )" + mesh() + R"(, "rtf": {)" + kSmall + "}}"));
  Loaded zero(writeLevel("rtf-box-n0b", R"({"id": "box", "dynamic": true, )" + mesh() + R"(, "rtf": {)" + kSmall +
                                             R"(, "byte_components": 0}})"));
  Loaded bytes(writeLevel("rtf-box-n2", R"({"id": "box", "dynamic": true, )" + mesh() + R"(, "rtf": {)" + kSmall +
                                             R"(, "byte_components": 2}})"));
  EXPECT_EQ(plain.level.entities[0].rtf->byteComponents, 0);
  EXPECT_EQ(bytes.level.entities[0].rtf->byteComponents, 2);
  EXPECT_EQ(settingsFrom(*bytes.level.entities[0].rtf).byteComponents, 2);
  const BakeJob job0 = t.bakeJobs(plain.context(), {}).at(0);
  EXPECT_EQ(t.bakeJobs(zero.context(), {}).at(0).key, job0.key);  // 0 is the default: the same entry
  const BakeJob job = t.bakeJobs(bytes.context(), {}).at(0);
  EXPECT_NE(job.key, job0.key);
  fs::remove(job.output);
  const std::string line = job.run();
  EXPECT_EQ(line.rfind("rtf     box: 2 proxies, 3 spheres x 6x2x2, 2 x 3 CPCA (last 2 in 8 bits): ", 0), 0u) << line;
  const Field f = load(job.output);
  EXPECT_EQ(f.settings.byteComponents, 2);
  EXPECT_EQ(f.itf.components, 3);
  EXPECT_EQ(f.itf.byteComponents, 2);
  EXPECT_TRUE(isQuantized(f.itf));
  fs::remove(job.output);
}

// An rtf entity whose mesh has no triangles (tests/data's box.gltf is a mesh-less stub): one line.
TEST(RtfTechnique, MeshWithoutTrianglesIsBadInput) {
  const std::string stub = (kSource / "tests/data/levels/assets/box.gltf").string();
  Loaded l(writeLevel("rtf-no-triangles", R"({"id": "a", "dynamic": true, "mesh": {"asset": ")" + stub + R"("}, "rtf": {}})"));
  try {
    technique().bakeJobs(l.context(), {});
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), stub + ": mesh: no triangles for the rtf field of entity a (expected a mesh with triangles)");
  }
}

// A constant directional sky: radiance SH with l = 1 and l = 2 content, the same at every point.
struct Sky final : incident::IndirectSource {
  incident::RadianceSH sh{};
  Sky() {
    const float v[9] = {3.0f, 0.8f, 1.4f, -0.6f, 0.5f, -0.9f, 0.7f, 0.4f, -1.1f};
    for (int i = 0; i < 9; ++i) sh[std::size_t(i)] = v[i] * glm::vec3(1.0f, 0.8f, 0.6f);
  }
  incident::RadianceSH radianceSH(glm::vec3) const override { return sh; }
};

// The level's rtf entities as Update takes them: each bake job run (where not cached), its field
// loaded, its entity found by name, its bounces from the level's "rtf" block.
std::vector<Participant> bakedParticipants(Loaded& l) {
  std::vector<Participant> parts;
  for (const BakeJob& job : technique().bakeJobs(l.context(), {})) {
    if (!job.cached()) job.run();
    Participant p;
    p.name = job.part;
    p.field = load(job.output);
    l.registry.view<scene::Name>().each([&](ecs::Entity e, scene::Name& n) {
      if (n.id == job.part) p.entity = e;
    });
    p.bounces = l.registry.get<scene::Rtf>(p.entity).bounces;
    parts.push_back(std::move(p));
  }
  return parts;
}

// The objects a field's record names as "on another object" (RtfObjectGpu::onObject): the nearest other
// centres, nearest first, ties to the lower index, at most `count`, never the object itself. 12 centres
// on the x axis (distances from centre 5: 0, 1, 1, 2, 2, …): the cap of 8 keeps the 8 nearest.
TEST(RtfUpdate, NearestOthersAreTheClosestCentresTiesByIndex) {
  std::vector<glm::vec3> centres;
  for (int k = 0; k < 12; ++k) centres.emplace_back(float(k), 0.0f, 0.0f);
  EXPECT_EQ(nearestOthers(centres, 5, 8), (std::vector<std::size_t>{4, 6, 3, 7, 2, 8, 1, 9}));
  EXPECT_EQ(nearestOthers(centres, 0, 3), (std::vector<std::size_t>{1, 2, 3}));
  EXPECT_EQ(nearestOthers(centres, 11, 20).size(), 11u);  // fewer others than the cap: all of them
  EXPECT_TRUE(nearestOthers(std::vector<glm::vec3>{glm::vec3(0.0f)}, 0, 8).empty());
}

// Two boxes with fields: Update::frame is the bouncing step of evaluate.hpp with the largest
// `bounces`, its records map o to q = 0 and a point one η away to |q| = 1, and rotate normals into
// the object's frame; the blocked matrix reproduces shade()'s blocked term.
TEST(RtfUpdate, FrameIsTheBouncingStepAndPacksTheRecords) {
  // Its own bake settings (vertex_rays 5): the test above corrupts and removes kTiny's entry, and
  // ctest runs tests in parallel.
  const std::string kTiny = R"("proxies": 2, "spheres": 3, "face": 2, "rays": 4, "vertex_rays": 5, "clusters": 2, "components": 2)";
  Loaded l(writeLevel("rtf-two", R"({"id": "a", "dynamic": true, "transform": {"translation": [0, 0, 0], "scale": [0.1, 0.1, 0.1]}, )" +
                                     mesh() + R"(, "rtf": {)" + kTiny + R"(, "bounces": 1}},
                                     {"id": "b", "dynamic": true, "transform": {"translation": [0.3, 0, 0], "rotation_euler_deg": [10, 40, 0], "scale": [0.1, 0.1, 0.1]}, )" +
                                     mesh() + R"(, "rtf": {)" + kTiny + R"(, "bounces": 2}})"));
  std::vector<Participant> parts = bakedParticipants(l);
  ASSERT_EQ(parts.size(), 2u);
  Update update(l.registry, parts);
  EXPECT_EQ(update.bounces(), 2);
  const Sky sky;
  update.setIndirect(&sky);
  const FrameObjects f = update.frame({});
  ASSERT_EQ(f.participant, (std::vector<std::size_t>{0, 1}));
  ASSERT_EQ(update.bounceMs().size(), 1u);
  std::vector<Object> objects;
  for (const Participant& p : parts) objects.push_back({&p.field, l.registry.get<scene::WorldTransform>(p.entity).matrix});
  const BounceResult want = bounce(objects, sky, 2);
  ASSERT_EQ(f.proxyLight.size(), 2u);
  EXPECT_EQ(f.proxyLight, want.proxyLight);
  EXPECT_EQ(f.bounceEnergy, want.bounceEnergy);
  ASSERT_EQ(f.bounceEnergy.size(), 2u);
  EXPECT_GT(f.bounceEnergy[1], 0.0);  // light did bounce from one box onto the other
  // The blocked term's per-sample factor is the two boxes' shared occlusion (overlap.hpp; README RTF
  // "Seventh pass"): the boxes stand 3 η apart, so some of each one's samples lie in the other's field.
  ASSERT_EQ(f.shares.size(), 2u);
  for (std::size_t o = 0; o < 2; ++o) {
    const OcclusionShares want = sharedOcclusion(objects, o);
    EXPECT_EQ(f.shares[o].scale, want.scale) << o;
    EXPECT_EQ(f.shares[o].onObjects, want.onObjects) << o;
    int shared = 0;
    for (const glm::vec4& s : f.shares[o].scale) shared += s.x < 1.0f;
    EXPECT_GT(shared, 0) << o;
  }

  for (std::size_t o = 0; o < 2; ++o) {
    const Field& field = parts[o].field;
    const Placement pl = place(field, objects[o].world);
    const RtfObjectGpu& r = f.records[o];
    EXPECT_EQ(r.ids.x, parts[o].entity.index() + 1u);
    // The other rtf object's entity + 1, then none: the receivers that read X's on-object variant.
    EXPECT_EQ(r.onObject[0], glm::uvec4(parts[1 - o].entity.index() + 1u, kRtfNoEntity, kRtfNoEntity, kRtfNoEntity));
    EXPECT_EQ(r.onObject[1], glm::uvec4(kRtfNoEntity));
    auto q = [&](glm::vec3 p) { return glm::vec3(glm::dot(r.toQ[0], glm::vec4(p, 1.0f)), glm::dot(r.toQ[1], glm::vec4(p, 1.0f)),
                                                 glm::dot(r.toQ[2], glm::vec4(p, 1.0f))); };
    EXPECT_LT(glm::length(q(pl.centreWorld)), 1e-4f);
    EXPECT_NEAR(glm::length(q(pl.centreWorld + pl.radiusWorld * glm::normalize(glm::vec3(1, 2, -1)))), 1.0f, 1e-4f);
    const float dr = (field.settings.outerRadius - field.settings.innerRadius) / float(field.settings.spheres - 1);
    EXPECT_NEAR(r.centreWorld.w, (field.settings.outerRadius + dr) * pl.radiusWorld, 1e-5f);
    // The blocked term of shade() for object o alone at a receiver outside it, normal n:
    // ρ/π E_n((u − V) ⊙ L) = Σ_j (u − V)_j Σ_i y_i(n_local) blocked[j·9 + i].
    const glm::vec3 rWorld = pl.centreWorld + 1.7f * pl.radiusWorld * glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
    const glm::vec3 n = glm::normalize(glm::vec3(-0.2f, -1.0f, 0.1f));
    const std::vector<Object> alone = {objects[o]};
    BounceResult none;
    none.xi = {std::vector<glm::vec3>(sampleCount(field.settings) * kShCount, glm::vec3(0.0f))};
    const Shading s = shade(alone, none, sky, rWorld, n, glm::vec3(1.0f), -1);
    const glm::vec3 qLocal = q(rWorld);
    const ShScalar V = occlusion(field, qLocal);
    const glm::vec3 nLocal(glm::dot(glm::vec3(r.toLocal[0]), n), glm::dot(glm::vec3(r.toLocal[1]), n), glm::dot(glm::vec3(r.toLocal[2]), n));
    const auto y = sh::evalBasis<float>(3, nLocal);
    glm::vec3 blocked(0.0f);
    for (int j = 0; j < kShCount; ++j) {
      glm::vec3 w(0.0f);
      for (int i = 0; i < 9; ++i) w += y[i] * glm::vec3(r.blocked[j * 9 + i]);
      blocked += ((j == 0 ? float(4.0 * math::kPi * sh::constants::kY00) : 0.0f) - V[std::size_t(j)]) * w;
    }
    EXPECT_EQ(s.interreflected, glm::vec3(0.0f));
    EXPECT_GT(glm::length(s.blocked), 1e-3f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(blocked[c], s.blocked[c], 1e-4f * std::max(1.0f, std::abs(s.blocked[c]))) << o << " " << c;
  }
}

}  // namespace
}  // namespace bounce::gi::rtf

namespace bounce::gi::rtf {
namespace {

// L_00 linear in the position (the other coefficients 0): what blockedScale reads.
struct Ramp final : incident::IndirectSource {
  incident::RadianceSH radianceSH(glm::vec3 p) const override {
    incident::RadianceSH sh{};
    sh[0] = glm::vec3(2.0f + 0.5f * p.x, 3.0f + 0.25f * p.y, 1.0f + 0.1f * p.z);
    return sh;
  }
};

struct BlockedScaleCase {
  Field field;
  glm::mat4 world;
  glm::vec3 o;
  float eta;
  glm::mat3 rotation;
  BlockedScaleCase() {
    field.settings.spheres = 5;
    field.settings.faceSize = 3;
    field.settings.innerRadius = 0.5f;
    field.settings.outerRadius = 4.0f;
    field.centre = glm::vec3(0.1f, -0.2f, 0.3f);
    field.radius = 1.5f;
    // Scale 0.5, a rotation, then a translation: η = 0.75 m, o = world · centre.
    world = glm::translate(glm::mat4(1.0f), glm::vec3(2.0f, 1.0f, -1.0f)) *
            glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f))) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
    o = glm::vec3(world * glm::vec4(field.centre, 1.0f));
    eta = 0.75f;
    rotation = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f))));
  }
  // Sample r's world position, from field.hpp's order, computed here on its own.
  glm::vec3 sample(std::size_t r) const {
    const FieldSettings& s = field.settings;
    const int per = 6 * s.faceSize * s.faceSize, n2 = s.faceSize * s.faceSize;
    const int sphere = int(r) / per, rest = int(r) % per, face = rest / n2;
    const glm::vec3 d(sh::cubeTexelDirection(face, rest % n2 % s.faceSize, rest % n2 / s.faceSize, s.faceSize));
    return o + rotation * (eta * sphereRadius(s, sphere) * d);
  }
};

TEST(RtfUpdate, BlockedScaleIsOneUnderAUniformSkyAndTheLightRatioAtEachSample) {
  const BlockedScaleCase c;
  // Light the same everywhere: the blocked light at the receiver is the light at o, exactly.
  const Sky sky;
  for (const glm::vec4& s : blockedScale(c.field, c.world, sky)) EXPECT_EQ(glm::vec3(s), glm::vec3(1.0f));
  // Light that varies: s = L_00(sample) / L_00(o) per channel, at the sample's world position.
  const Ramp ramp;
  const std::vector<glm::vec4> s = blockedScale(c.field, c.world, ramp);
  ASSERT_EQ(s.size(), sampleCount(c.field.settings));
  const glm::vec3 at = ramp.radianceSH(c.o)[0];
  for (std::size_t r = 0; r < s.size(); ++r) {
    const glm::vec3 want = ramp.radianceSH(c.sample(r))[0] / at;
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(s[r][ch], want[ch], 1e-5f * want[ch]) << r << " " << ch;
  }
}

TEST(RtfUpdate, BlockedScaleHoldsItsLastValueBehindStaticGeometry) {
  // A floor quad 1.2 η below o (world y): samples below it are hidden from o and take the value of
  // the last sample on their ray above it; samples above it are the plain ratio.
  const BlockedScaleCase c;
  const float floorY = c.o.y - 1.2f * c.eta;
  ref::SceneDesc floor;
  floor.materials.push_back(ref::RefMaterial{glm::vec3(0.5f)});
  ref::RefMesh m;
  m.material = 0;
  const float h = 100.0f;
  for (glm::vec3 p : {glm::vec3(-h, floorY, -h), glm::vec3(-h, floorY, h), glm::vec3(h, floorY, h), glm::vec3(h, floorY, -h)}) {
    m.positions.push_back(p);
    m.normals.push_back(glm::vec3(0.0f, 1.0f, 0.0f));
  }
  m.indices = {0, 1, 2, 0, 2, 3};
  floor.meshes.push_back(m);
  const ref::SceneBvh bvh(floor);
  const Ramp ramp;
  const std::vector<glm::vec4> s = blockedScale(c.field, c.world, ramp, &bvh);
  const std::vector<glm::vec4> open = blockedScale(c.field, c.world, ramp);
  const FieldSettings& fs = c.field.settings;
  const std::size_t per = std::size_t(6 * fs.faceSize * fs.faceSize);
  int hidden = 0, held = 0;
  for (std::size_t ray = 0; ray < per; ++ray) {
    glm::vec4 last(1.0f);
    for (int sphere = 0; sphere < fs.spheres; ++sphere) {
      const std::size_t r = std::size_t(sphere) * per + ray;
      if (c.sample(r).y > floorY) {
        EXPECT_EQ(s[r], open[r]) << r;
        last = open[r];
      } else {
        ++hidden;
        EXPECT_EQ(s[r], last) << r;
        held += sphere > 0 && c.sample(r - per).y > floorY;
      }
    }
  }
  EXPECT_GT(hidden, 20);
  EXPECT_GT(held, 5);  // rays that cross the floor between two spheres
}

// The GPU record of a mirrored object (det(world) < 0, gi::Placement): mirroring the object and its
// light together by X = diag(−1, 1, 1) leaves what rtf.frag computes unchanged — the same q for the
// mirrored point, the same local normal for the mirrored normal (toLocal is the reflection's
// transpose, not a rotation), the same blocked light in the object's frame. Before session 12,
// toLocal was quat_cast of the reflection: an unrelated rotation.
TEST(RtfUpdate, MirroredRecordSeesTheWorldThroughItsMirror) {
  const BlockedScaleCase c;
  const glm::mat4 X = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
  ShRgb L{}, mirroredL{};
  const glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.5f, 0.8f));
  const auto y = sh::evalBasis<float>(4, d), yx = sh::evalBasis<float>(4, glm::vec3(-d.x, d.y, d.z));
  for (int i = 0; i < kShCount; ++i) {
    L[std::size_t(i)] = glm::vec3(1.0f + 0.1f * float(i), 0.5f - 0.07f * float(i), 0.3f * float(i % 3) - 0.2f);
    // L'(ω) = L(Xω): Y_i(X d) = ±Y_i(d), the sign read off at a generic direction.
    mirroredL[std::size_t(i)] = (y[std::size_t(i)] * yx[std::size_t(i)] > 0.0f ? 1.0f : -1.0f) * L[std::size_t(i)];
  }
  const RtfObjectGpu a = packObject(c.field, c.world, L, 0u), b = packObject(c.field, X * c.world, mirroredL, 0u);
  const glm::mat3 x(X);
  auto rows = [](const glm::vec4 (&m)[3], glm::vec4 v) { return glm::vec3(glm::dot(m[0], v), glm::dot(m[1], v), glm::dot(m[2], v)); };
  for (const glm::vec3 n : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::normalize(glm::vec3(0.3f, -1.0f, 0.4f)), glm::normalize(glm::vec3(-2, 1, 3))}) {
    EXPECT_LT(glm::length(rows(b.toLocal, glm::vec4(x * n, 0.0f)) - rows(a.toLocal, glm::vec4(n, 0.0f))), 1e-5f);
    const glm::vec3 p = c.o + 2.0f * n;
    EXPECT_LT(glm::length(rows(b.toQ, glm::vec4(x * p, 1.0f)) - rows(a.toQ, glm::vec4(p, 1.0f))), 1e-5f);
  }
  float worst = 0.0f, largest = 0.0f;
  for (int k = 0; k < kShCount * 9; ++k)
    worst = std::max(worst, glm::length(b.blocked[k] - a.blocked[k])), largest = std::max(largest, glm::length(a.blocked[k]));
  ASSERT_GT(largest, 0.1f);
  EXPECT_LT(worst, 1e-5f * largest) << "largest " << largest;
}

// ---- the lamp through the other posed objects (occluders.hpp; issue 14, session 18) ----------------

using bounce::testing::pointLight;  // tests/support/point_light.hpp

// A level with a small box "low" (0.1 m, its centre at height lowY) under a big one "high" (0.6 m at
// 0.5 m), both rtf objects with a tiny one-bounce field; vertexRays differs per test so that their
// cached bakes do not collide.
Loaded lowAndHighBoxes(const std::string& name, const std::string& lowY, int vertexRays) {
  const std::string tiny = R"("proxies": 2, "spheres": 3, "face": 2, "rays": 4, "vertex_rays": )" + std::to_string(vertexRays) +
                           R"(, "clusters": 2, "components": 2, "bounces": 1)";
  return Loaded(writeLevel(name, R"({"id": "low", "dynamic": true, "transform": {"translation": [0, )" + lowY +
                                     R"(, 0], "scale": [0.1, 0.1, 0.1]}, )" + mesh() + R"(, "rtf": {)" + tiny + R"(}},
                                     {"id": "high", "dynamic": true, "transform": {"translation": [0, 0.5, 0], "scale": [0.6, 0.6, 0.6]}, )" +
                                     mesh() + R"(, "rtf": {)" + tiny + R"(}})"));
}

// The bouncing step's lamp at the proxies (update.hpp setOccluders): a small box under a big one gets no
// lamp light (no indirect light, 1 bounce: its proxies' light is the lamp's alone); the big box's own
// proxies, inside its mesh, are not shadowed by it (the same light as without occluders, bit for bit);
// moving the blocker away gives the small box the light it has without occluders again.
TEST(RtfUpdate, LampIsTracedThroughTheOtherPosedObjects) {
  Loaded l(lowAndHighBoxes("rtf-lamp", "0", 7));
  std::vector<Participant> parts = bakedParticipants(l);  // kTiny's "bounces": 1
  std::vector<ref::SceneDesc> meshes;
  ref::ReferenceAssets assets;
  std::vector<ecs::Entity> entities;
  for (const Participant& p : parts) entities.push_back(p.entity);
  ASSERT_EQ(parts.size(), 2u);
  ASSERT_EQ(parts[0].name, "low");
  gi::loadAssetsOf(l.registry, entities, cookCache(), assets);
  for (ecs::Entity e : entities) meshes.push_back(dnrt::objectScene(l.registry, e, assets));
  Update traced(l.registry, parts), plain(l.registry, parts);
  traced.setOccluders(std::make_unique<PosedOccluders>(std::move(meshes)), nullptr);
  const std::vector<render::LightGpu> lamp = {pointLight(glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(1.0f, 0.9f, 0.8f))};
  const auto energy = [](const std::vector<glm::vec3>& light) {
    double e = 0.0;
    for (const glm::vec3& c : light) e += double(std::abs(c.r) + std::abs(c.g) + std::abs(c.b));
    return e;
  };
  {
    const FrameObjects t = traced.frame(lamp), u = plain.frame(lamp);
    ASSERT_EQ(t.proxyLight.size(), 2u);
    EXPECT_GT(energy(u.proxyLight[0]), 0.0);   // without occluders the lamp reaches the small box's proxies
    EXPECT_EQ(energy(t.proxyLight[0]), 0.0);   // behind the big box: none of it
    EXPECT_GT(energy(t.proxyLight[1]), 0.0);   // the big box is not its own blocker
    EXPECT_EQ(t.proxyLight[1], u.proxyLight[1]);
  }
  l.registry.get<scene::WorldTransform>(parts[1].entity).matrix =
      glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 0.5f, 0.0f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.6f));
  {
    const FrameObjects t = traced.frame(lamp), u = plain.frame(lamp);
    EXPECT_GT(energy(t.proxyLight[0]), 0.0);
    EXPECT_EQ(t.proxyLight, u.proxyLight);  // the blocker moved away: the light without occluders again
  }
  EXPECT_EQ(traced.bounceMs().size(), 2u);
}

// Update's room-shadow path with a level (update.hpp setRoomShadows; room_shadows.hpp): a small box on a
// 2 × 2 m floor under a big box and a lamp. With room shadows every proxy's l = 0 light is at most its
// light without them (the objects only take the room's lamp bounce away) and never negative; the small
// box, whose proxies see the big box's shadow on the floor around them, loses light, and more than
// with the big box moved 3 m aside (its shadow then falls off the floor: what is left is the small box's
// own shadow under it; measured: the small box's proxies lose 0.088 of 3.92 in red, 0.053 aside). 1 bounce,
// so the proxies' light is the source's alone. Tolerance 1e-6 relative on "at most": the sum in another order.
TEST(RtfUpdate, RoomShadowsTakeTheObjectsShadowsOnTheLevelOffTheProxies) {
  Loaded l(lowAndHighBoxes("rtf-room-shadows", "0.05", 6));
  std::vector<Participant> parts = bakedParticipants(l);
  ASSERT_EQ(parts.size(), 2u);
  ASSERT_EQ(parts[0].name, "low");
  ref::ReferenceAssets assets;
  std::vector<ecs::Entity> entities;
  for (const Participant& p : parts) entities.push_back(p.entity);
  gi::loadAssetsOf(l.registry, entities, cookCache(), assets);
  const auto occluders = [&] {
    std::vector<ref::SceneDesc> meshes;
    for (ecs::Entity e : entities) meshes.push_back(dnrt::objectScene(l.registry, e, assets));
    return std::make_unique<PosedOccluders>(std::move(meshes));
  };
  const ref::SceneBvh level(bounce::testing::floorMesh(1.0f, glm::vec3(0.5f)));
  const Sky sky;
  Update shadowed(l.registry, parts), plain(l.registry, parts);
  for (Update* u : {&shadowed, &plain}) {
    u->setIndirect(&sky);
    u->setOccluders(occluders(), &level);
  }
  shadowed.setRoomShadows(&level);
  const std::vector<render::LightGpu> lamp = {pointLight(glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(1.0f, 0.9f, 0.8f))};
  // Σ over object o's proxies of l = 0 (rotation-invariant, so the object frame's is the world's), per channel.
  const auto l0 = [](const FrameObjects& f, std::size_t o) {
    glm::dvec3 sum(0.0);
    for (std::size_t k = 0; k < f.proxyLight[o].size(); k += kShCount) sum += glm::dvec3(f.proxyLight[o][k]);
    return sum;
  };
  const auto check = [&](const FrameObjects& s, const FrameObjects& p) {
    for (std::size_t o = 0; o < 2; ++o)
      for (std::size_t k = 0; k < s.proxyLight[o].size(); k += kShCount)
        for (int c = 0; c < 3; ++c) {
          EXPECT_LE(s.proxyLight[o][k][c], p.proxyLight[o][k][c] + 1e-6f * std::abs(p.proxyLight[o][k][c])) << o << " " << k << " " << c;
          EXPECT_GE(s.proxyLight[o][k][c], 0.0f) << o << " " << k << " " << c;
        }
    return l0(p, 0) - l0(s, 0);  // the small box's loss
  };
  const glm::dvec3 under = check(shadowed.frame(lamp), plain.frame(lamp));
  l.registry.get<scene::WorldTransform>(parts[1].entity).matrix =
      glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 0.5f, 0.0f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.6f));
  const glm::dvec3 aside = check(shadowed.frame(lamp), plain.frame(lamp));
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(under[c], 0.0) << c;
    EXPECT_GT(under[c], aside[c]) << c;
  }
  EXPECT_EQ(shadowed.bounceMs().size(), 2u);
}

}  // namespace
}  // namespace bounce::gi::rtf
