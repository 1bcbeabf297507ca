// SL in the technique table (issue 13, steps 1–2) on the CPU: the level component (strict parsing,
// one-line errors), participation, the bake job (content key, cache entry, what it prints), the
// session runtime's cache round trip and the per-frame sphere poses of §7.1 on a rigid object
// (exact: the entity's transform) and on a skinned character (the covered vertices' motion).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/anim/animator.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/sl/hierarchy.hpp"
#include "engine/gi/sl/resolution.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/gi/sl/technique.hpp"
#include "engine/gi/sl/update.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/scene/level.hpp"
#include "engine/scene/systems.hpp"
#include "tests/support/technique_level.hpp"

namespace bounce::gi::sl {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = BOUNCE_SOURCE_DIR;
fs::path outDir() { return fs::path(BOUNCE_TEST_OUT) / "sl"; }
// The shared helpers (tests/support/technique_level.hpp) with this folder and the effects [direct, sl].
using testlevel::boxAsset, testlevel::cookCache, testlevel::Loaded;
std::string mesh() { return testlevel::boxMesh(); }
fs::path writeLevel(const std::string& name, const std::string& entities, const std::string& effects = R"(["direct", "sl"])") {
  return testlevel::writeLevel(outDir(), name, entities, effects);
}
std::string loadError(const std::string& name, const std::string& entity) {
  return testlevel::loadError(outDir(), name, entity, R"(["direct", "sl"])");
}

TEST(SlComponent, ParsesWithDefaults) {
  const fs::path path = writeLevel("sl-ok", R"({"id": "a", "dynamic": true, )" + mesh() +
                                                R"(, "sl": {"spheres": 32, "order": 3, "blocking": "per-object", "influence": 0, "resolution": "half"}},
                                               {"id": "b", "dynamic": true, )" + mesh() + R"(, "sl": {}})");
  const scene::Level level = scene::loadLevel(path);
  ASSERT_EQ(level.entities.size(), 2u);
  EXPECT_EQ(level.entities[0].sl, (scene::Sl{32, 3, true, 0.0f, 2}));
  EXPECT_EQ(level.entities[1].sl, (scene::Sl{16, 4, false, 12.0f, 1}));
  // "quarter": one pass-2 sample per 4 × 4 G-buffer pixels (engine/gi/resolution.hpp).
  const scene::Level quarter = scene::loadLevel(
      writeLevel("sl-quarter", R"({"id": "a", "dynamic": true, )" + mesh() + R"(, "sl": {"resolution": "quarter"}})"));
  EXPECT_EQ(quarter.entities[0].sl->step, 4);
  EXPECT_EQ(gi::resolutionStep(gi::resolutionFromStep(std::uint32_t(quarter.entities[0].sl->step))), 4u);
  EXPECT_FALSE(level.entities[0].sl->localLights);
  EXPECT_FALSE(level.entities[0].sl->blockedAtSphere);  // "blocked_light": "receiver" unless asked
  EXPECT_TRUE(scene::loadLevel(writeLevel("sl-sphere", R"({"id": "a", "dynamic": true, )" + mesh() +
                                                           R"(, "sl": {"blocked_light": "sphere"}})"))
                  .entities[0]
                  .sl->blockedAtSphere);
  EXPECT_FALSE(level.entities[0].sl->blockedMap);  // "blocked_read": "sh" unless asked
  EXPECT_TRUE(scene::loadLevel(writeLevel("sl-map", R"({"id": "a", "dynamic": true, )" + mesh() +
                                                        R"(, "sl": {"blocked_light": "sphere", "blocked_read": "map"}})"))
                  .entities[0]
                  .sl->blockedMap);
  EXPECT_EQ(settingsFrom(*level.entities[0].sl).spheres, 32);
  EXPECT_EQ(settingsFrom(*level.entities[0].sl).order, 3);
}

// One table of pass 2's steps (engine/gi/resolution.hpp): names and steps round-trip, every other
// step is refused (the upsample's ldexp fraction is exact only for powers of two, and 3 must not
// silently become full resolution), and the level, `bounce bench` and the accuracy rows read it.
TEST(SlResolution, OneNameForEachOfTheStepsOneTwoFour) {
  using namespace gi::sl;
  const std::pair<const char*, std::uint32_t> table[] = {{"full", 1u}, {"half", 2u}, {"quarter", 4u}};
  for (const auto& [name, step] : table) {
    EXPECT_EQ(parseResolution(name), step) << name;
    EXPECT_STREQ(resolutionName(step), name);
    EXPECT_EQ(resolutionStep(resolutionFromStep(step)), step);
  }
  EXPECT_STREQ(reducedTargetName(2u), "sl.half");
  EXPECT_STREQ(reducedTargetName(4u), "sl.quarter");
  EXPECT_THROW(reducedTargetName(1u), InternalError);  // full resolution has no reduced target
  for (const char* bad : {"", "Full", "eighth", "third", "2"}) EXPECT_EQ(parseResolution(bad), std::nullopt) << bad;
  for (const std::uint32_t bad : {0u, 3u, 5u, 8u, 0xffffffffu}) {
    EXPECT_FALSE(isResolutionStep(bad)) << bad;
    EXPECT_THROW(resolutionFromStep(bad), InternalError) << bad;
    EXPECT_THROW(resolutionName(bad), InternalError) << bad;
    EXPECT_THROW(reducedTargetName(bad), InternalError) << bad;
  }
}

TEST(SlComponent, BadInputIsOneLine) {
  const std::string dyn = R"({"id": "a", "dynamic": true, )" + mesh();
  EXPECT_EQ(loadError("sl-order", dyn + R"(, "sl": {"order": 5}})"),
            "FILE: /entities/0/sl/order: SH order 5 (expected 3 or 4)");
  EXPECT_EQ(loadError("sl-spheres", dyn + R"(, "sl": {"spheres": 65}})"),
            "FILE: /entities/0/sl/spheres: 65 is out of range (expected an integer in [1, 64])");
  EXPECT_EQ(loadError("sl-blocking", dyn + R"(, "sl": {"blocking": "per-pixel"}})"),
            "FILE: /entities/0/sl/blocking: unknown blocking \"per-pixel\" (expected per-sphere or per-object)");
  EXPECT_EQ(loadError("sl-influence", dyn + R"(, "sl": {"influence": 2.5}})"),
            "FILE: /entities/0/sl/influence: influence 2.5 (expected 0 (off) or 3..1000 sphere radii)");
  EXPECT_EQ(loadError("sl-resolution", dyn + R"(, "sl": {"resolution": "eighth"}})"),
            "FILE: /entities/0/sl/resolution: unknown resolution \"eighth\" (expected full, half or quarter)");
  EXPECT_EQ(loadError("sl-local", dyn + R"(, "sl": {"local_lights": 1}})"),
            "FILE: /entities/0/sl/local_lights: wrong type: integer (expected true or false)");
  EXPECT_EQ(loadError("sl-hierarchy", dyn + R"(, "sl": {"hierarchy": "on"}})"),
            "FILE: /entities/0/sl/hierarchy: wrong type: string (expected true or false)");
  EXPECT_EQ(loadError("sl-blocked", dyn + R"(, "sl": {"blocked_light": "object"}})"),
            "FILE: /entities/0/sl/blocked_light: unknown blocked_light \"object\" (expected receiver or sphere)");
  EXPECT_EQ(loadError("sl-blocked-hierarchy", dyn + R"(, "sl": {"hierarchy": true, "blocked_light": "sphere"}})"),
            "FILE: /entities/0/sl/blocked_light: blocked_light \"sphere\" with \"hierarchy\": true (expected \"receiver\" "
            "with the hierarchy (its parents read the receiver's SH))");
  EXPECT_EQ(loadError("sl-read", dyn + R"(, "sl": {"blocked_light": "sphere", "blocked_read": "texture"}})"),
            "FILE: /entities/0/sl/blocked_read: unknown blocked_read \"texture\" (expected sh or map)");
  EXPECT_EQ(loadError("sl-read-receiver", dyn + R"(, "sl": {"blocked_read": "map"}})"),
            "FILE: /entities/0/sl/blocked_read: blocked_read \"map\" without blocked_light \"sphere\" (expected \"sh\", or "
            "\"blocked_light\": \"sphere\" (the map is read at the SLs))");
  EXPECT_EQ(loadError("light-radius", R"({"id": "l", "light": {"type": "point", "radius": -1}})"),
            "FILE: /entities/0/light/radius: -1 is out of range (expected a number in [0, 100])");
  EXPECT_EQ(loadError("light-radius-sun", R"({"id": "l", "light": {"type": "directional", "radius": 1}})"),
            "FILE: /entities/0/light/radius: a directional light has no position (expected no radius)");
  EXPECT_EQ(loadError("sl-key", dyn + R"(, "sl": {"sphere": 8}})").rfind("FILE: /entities/0/sl/sphere: unknown key", 0), 0u);
  EXPECT_EQ(loadError("sl-static", R"({"id": "a", )" + mesh() + R"(, "sl": {}})"),
            "FILE: /entities/0/sl: spherical lights on a static entity (expected \"dynamic\": true or a motion)");
  EXPECT_EQ(loadError("sl-no-mesh", R"({"id": "a", "dynamic": true, "sl": {}})"),
            "FILE: /entities/0/sl: spherical lights on an entity without a mesh (expected a \"mesh\" key)");
}

// An sl entity whose mesh has no triangles (tests/data's box.gltf is a mesh-less stub): one line.
TEST(SlComponent, MeshWithoutTrianglesIsBadInput) {
  const std::string stub = (kSource / "tests/data/levels/assets/box.gltf").string();
  const fs::path path = writeLevel("sl-no-triangles", R"({"id": "a", "dynamic": true, "mesh": {"asset": ")" + stub +
                                                           R"("}, "sl": {}})");
  scene::Level level = scene::loadLevel(path);
  ecs::Registry r;
  scene::instantiate(level, r);
  scene::transformSystem(r);
  try {
    technique().bakeJobs(LevelContext{level, r, cookCache()}, {});
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), stub + ": mesh: no triangles for the sl spheres of entity a (expected a mesh with triangles)");
  }
}

TEST(SlTechnique, TakesPartAndBakesOneEntryPerEntity) {
  const Technique& t = technique();
  EXPECT_EQ(t.cacheKind(), "sl");
  Loaded none(writeLevel("sl-none", R"({"id": "a", "dynamic": true, )" + mesh() + "}"));
  EXPECT_EQ(effectNote(t, none.context()), "note: effect sl is named but no entity takes part (no entity has an sl "
                                           "component): no pass");
  Loaded l(writeLevel("sl-box", R"({"id": "box", "dynamic": true, )" + mesh() + R"(, "sl": {"spheres": 3, "order": 3}})"));
  const auto lc = l.context();
  EXPECT_EQ(effectNote(t, lc), std::nullopt);
  const auto jobs = t.bakeJobs(lc, {});
  ASSERT_EQ(jobs.size(), 1u);
  const BakeJob& job = jobs[0];
  EXPECT_EQ(job.technique, "sl");
  EXPECT_EQ(job.part, "box");
  EXPECT_EQ(job.key.size(), 16u);
  EXPECT_EQ(job.output, cacheFolder() / ("sl-" + job.key + ".slset"));
  EXPECT_TRUE(t.bakeJobs(lc, "no-such-entity").empty());
  ASSERT_EQ(t.bakeJobs(lc, "box").size(), 1u);
  EXPECT_EQ(t.bakeJobs(lc, "box")[0].key, job.key);  // planned alone: same key
  // Another setting is another entry.
  Loaded other(writeLevel("sl-box4", R"({"id": "box", "dynamic": true, )" + mesh() + R"(, "sl": {"spheres": 4, "order": 3}})"));
  EXPECT_NE(t.bakeJobs(other.context(), {})[0].key, job.key);

  fs::remove(job.output);
  EXPECT_EQ(job.cached(), std::nullopt);
  const std::string line = job.run();
  EXPECT_EQ(line.rfind("sl      box: 3 spheres, order 3, 92 directions: ", 0), 0u) << line;
  EXPECT_NE(line.find(job.output.string()), std::string::npos) << line;
  const SphereSet set = load(job.output);
  EXPECT_EQ(set.spheres.size(), 3u);
  EXPECT_EQ(set.settings.order, 3);
  EXPECT_EQ(job.cached(), "sl      box: 3 spheres, order 3, 92 directions: cached " + job.output.string());
  // A corrupt entry is not "cached" (it is re-baked).
  writeFileAtomic(job.output, std::string("BSLSPSET garbage"));
  EXPECT_EQ(job.cached(), std::nullopt);
  fs::remove(job.output);
}

// A rigid object: every SL moves exactly by the entity's transform (uniform scale scales radii).
TEST(SlUpdate, RigidObjectMovesByItsTransform) {
  Loaded l(writeLevel("sl-rigid", R"({"id": "box", "dynamic": true, )" + mesh() + R"(, "sl": {"spheres": 2, "order": 3}})"));
  SessionRuntime runtime(l.registry, cookCache(), outDir() / "cache");
  ASSERT_EQ(runtime.participants().size(), 1u);
  const Participant& p = runtime.participants()[0];
  ASSERT_EQ(p.set.spheres.size(), 2u);
  ASSERT_EQ(p.spheres.size(), 2u);
  // A second runtime reads the entry the first wrote (same set, byte for byte).
  SessionRuntime again(l.registry, cookCache(), outDir() / "cache");
  EXPECT_EQ(serialize(again.participants()[0].set), serialize(p.set));

  const glm::mat4 rotate = glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1, 2, 3)));
  const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(1.5f, -2.0f, 0.25f)) * rotate *
                          glm::scale(glm::mat4(1.0f), glm::vec3(2.5f));
  l.registry.get<scene::WorldTransform>(p.entity).matrix = world;
  EXPECT_TRUE(runtime.profileLines().empty());  // no frame yet
  runtime.update(FrameUpdate{l.registry, 0.0});
  ASSERT_EQ(runtime.profileLines().size(), 1u);
  EXPECT_EQ(runtime.profileLines()[0].rfind("sl update: 2 spheres on 1 entities, CPU median ", 0), 0u) << runtime.profileLines()[0];
  EXPECT_NE(runtime.profileLines()[0].find(" ms over 1 frames (§7.1 poses)"), std::string::npos);
  for (std::size_t s = 0; s < 2; ++s) {
    const PosedSphere& q = runtime.participants()[0].spheres[s];
    const glm::vec3 expected = glm::vec3(world * glm::vec4(p.set.spheres[s].centre, 1.0f));
    EXPECT_LT(glm::length(q.centre - expected), 1e-5f);
    EXPECT_NEAR(q.radius, 2.5f * p.set.spheres[s].radius, 1e-5f);
    for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(q.rotation[c] - glm::vec3(rotate[c])), 1e-5f) << c;
  }
}

TEST(SlUpdate, ClosestRotation) {
  const glm::dmat3 r = glm::dmat3(glm::rotate(glm::dmat4(1.0), 1.1, glm::normalize(glm::dvec3(-1, 2, 0.5))));
  const glm::dmat3 stretched = r * glm::dmat3(glm::dvec3(3, 0, 0), glm::dvec3(0, 0.5, 0), glm::dvec3(0, 0, 1.5));
  const glm::dmat3 q = closestRotation(stretched);
  for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(q[c] - r[c]), 1e-12) << c;
  EXPECT_EQ(closestRotation(glm::dmat3(0.0)), glm::dmat3(1.0));  // singular: identity, no NaN
}

// §7.3's parents per frame (update.hpp parentSpheres): per object, hierarchy.hpp parentOf's sphere of its
// posed SLs (the C++ reference's own), identity rotation, every child inside; objects interleaved in
// SL order, and an id with no SL gets radius 0.
TEST(SlUpdate, ParentSpheresAreParentOfsSpherePerObject) {
  std::vector<PosedSphere> posed;
  std::vector<std::uint32_t> objects;
  for (int i = 0; i < 9; ++i) {
    PosedSphere p;
    p.centre = glm::vec3(0.3f * float(i % 3), -0.2f * float(i), 1.0f + 0.1f * float(i * i % 5));
    p.radius = 0.05f + 0.02f * float(i);
    p.rotation = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.4f * float(i), glm::vec3(0, 1, 0)));
    posed.push_back(p);
    objects.push_back(i % 3 == 1 ? 2u : 0u);  // objects 0 and 2; id 1 has none
  }
  const std::vector<PosedSphere> parents = parentSpheres(posed, objects);
  ASSERT_EQ(parents.size(), 3u);
  EXPECT_EQ(parents[1].radius, 0.0f);
  for (std::uint32_t o : {0u, 2u}) {
    std::vector<Light> kids;
    for (std::size_t i = 0; i < posed.size(); ++i)
      if (objects[i] == o) {
        Light l;
        l.object = int(o);
        l.sphere = {glm::dvec3(posed[i].centre), double(posed[i].radius)};
        l.intensity.assign(16, glm::dvec3(0.0));
        kids.push_back(l);
      }
    const Light want = parentOf(kids);
    EXPECT_LT(glm::length(glm::dvec3(parents[o].centre) - want.sphere.centre), 1e-6) << o;
    EXPECT_NEAR(parents[o].radius, want.sphere.radius, 1e-6) << o;
    EXPECT_EQ(parents[o].rotation, glm::mat3(1.0f));
    for (const Light& k : kids)
      EXPECT_LE(glm::length(k.sphere.centre - glm::dvec3(parents[o].centre)) + k.sphere.radius,
                double(parents[o].radius) * (1.0 + 1e-6));
  }
}

// The fox of characters.json, running: every SL follows its covered vertices. Each covered vertex's
// posed position comes from ref::extractScene (the renderer's and tracer's own posing, a path
// independent of SpherePoser's averages); it is compared with where the SL carries the vertex's
// bake-frame offset, x̂_v = c' + s·R·(p_v − c). Rotation and translation are the AVERAGE of the
// vertices' (§7.1), so a vertex moves off that by the deformation within the SL; the bounds below are
// on that soft-deformation error, in units of the SL's radius. Each vertex's own T_v is exact.
TEST(SlUpdate, SkinnedCharacterSpheresFollowTheirVertices) {
  scene::Level level = scene::loadLevel(kSource / "content/levels/characters.json");
  ecs::Registry registry;
  scene::instantiate(level, registry);
  anim::attachAnimators(registry, cookCache());
  ecs::Entity fox{};
  registry.view<scene::Name>().each([&](ecs::Entity e, scene::Name& n) {
    if (n.id == "fox") fox = e;
  });
  ASSERT_TRUE(registry.tryGet<scene::MeshRef>(fox));
  ref::ReferenceAssets assets;
  {
    ecs::Registry one;
    one.emplace<scene::MeshRef>(one.create(), registry.get<scene::MeshRef>(fox));
    assets.load(one, cookCache());
  }
  const ObjectInput in = objectInput(registry, fox, assets);
  ASSERT_FALSE(in.skin.joints.empty());
  BakeSettings s;
  s.spheres = 16;
  s.samplesPerAxis = 16;  // the test checks poses, not the sums
  s.surfaceSamples = 2048;
  const SphereSet set = bake(in.object, s, in.skin);
  const scene::MeshRef& ref = registry.get<scene::MeshRef>(fox);
  const SpherePoser poser(assets.get(ref).cpu, ref, set);

  std::vector<glm::vec3> bakePositions;
  for (const auto& m : in.object.meshes) bakePositions.insert(bakePositions.end(), m.positions.begin(), m.positions.end());
  for (const double t : {0.0, 0.37, 1.3}) {
    scene::motionSystem(registry, t);
    anim::animationSystem(registry, t);
    scene::transformSystem(registry);
    const auto* pose = registry.tryGet<anim::Pose>(fox);
    ASSERT_NE(pose, nullptr);
    std::vector<PosedSphere> posed;
    poser.pose(registry.get<scene::WorldTransform>(fox).matrix, pose, posed);
    ASSERT_EQ(posed.size(), set.spheres.size());
    // The same posed entity alone, through the tracer's scene extraction.
    ecs::Registry one;
    const ecs::Entity e = one.create();
    one.emplace<scene::MeshRef>(e, ref);
    one.emplace<scene::WorldTransform>(e, registry.get<scene::WorldTransform>(fox));
    one.emplace<anim::Pose>(e, *pose);
    const ref::SceneDesc world = ref::extractScene(one, scene::Level{}, assets, false);
    std::vector<glm::vec3> worldPositions;
    for (const auto& m : world.meshes) worldPositions.insert(worldPositions.end(), m.positions.begin(), m.positions.end());
    ASSERT_EQ(worldPositions.size(), bakePositions.size());
    // Each vertex's T_v takes its bake-frame position to where the renderer draws it (float maths
    // on positions of ~1 m: 1e-4 m).
    const std::vector<glm::dmat4> tv = poser.vertexTransforms(registry.get<scene::WorldTransform>(fox).matrix, pose);
    ASSERT_EQ(tv.size(), bakePositions.size());
    double tvWorst = 0.0;
    for (std::size_t v = 0; v < tv.size(); ++v)
      tvWorst = std::max(tvWorst, glm::length(glm::dvec3(tv[v] * glm::dvec4(glm::dvec3(bakePositions[v]), 1.0)) -
                                              glm::dvec3(worldPositions[v])));
    EXPECT_LT(tvWorst, 1e-4) << "t = " << t;
    double worst = 0.0, sum = 0.0, sumEntity = 0.0, worstEntity = 0.0;
    std::size_t count = 0;
    const glm::dmat4 entityWorld(registry.get<scene::WorldTransform>(fox).matrix);
    for (std::size_t i = 0; i < posed.size(); ++i) {
      const PosedSphere& q = posed[i];
      const glm::dmat3 rot(q.rotation);
      const glm::dmat3 gram = glm::transpose(rot) * rot - glm::dmat3(1.0);
      for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(gram[c]), 1e-5) << "orthonormal rotation, SL " << i;
      EXPECT_NEAR(glm::determinant(rot), 1.0, 1e-5);
      ASSERT_TRUE(std::isfinite(q.radius) && q.radius > 0.0f);
      const double scale = double(q.radius) / double(set.spheres[i].radius);
      for (std::uint32_t v : set.spheres[i].vertices) {
        const glm::dvec3 carried = glm::dvec3(q.centre) + scale * (rot * glm::dvec3(bakePositions[v] - set.spheres[i].centre));
        const double e = glm::length(carried - glm::dvec3(worldPositions[v])) / double(q.radius);
        // Baseline: the SL moved by the entity's transform only (the pose ignored).
        const glm::dvec3 rigid = glm::dvec3(entityWorld * glm::dvec4(glm::dvec3(bakePositions[v]), 1.0));
        const double eEntity = glm::length(rigid - glm::dvec3(worldPositions[v])) / double(q.radius);
        worst = std::max(worst, e), worstEntity = std::max(worstEntity, eEntity);
        sum += e, sumEntity += eEntity, ++count;
      }
    }
    std::printf("t = %.2f: covered-vertex offset mean %.3f R worst %.3f R; entity transform only: mean %.3f R worst %.3f R\n", t,
                sum / double(count), worst, sumEntity / double(count), worstEntity);
    // Measured (16 SLs on the running fox, t = 0, 0.37, 1.3): mean 0.36, 0.21, 0.32 R following the
    // vertices vs 0.73, 1.15, 0.79 R with the entity's transform alone; worst 2.1, 0.9, 1.8 R (legs
    // and tail bend inside one SL: beyond the paper's "soft" class). Asserted: following the
    // vertices at least 1.6× better on average than ignoring the pose, mean ≤ 0.45 R, worst ≤ 3 R.
    EXPECT_LT(sum, sumEntity / 1.6) << "t = " << t;
    EXPECT_LT(sum / double(count), 0.45) << "t = " << t;
    EXPECT_LT(worst, 3.0) << "t = " << t;
  }
}

}  // namespace
}  // namespace bounce::gi::sl

namespace bounce::gi::sl {
namespace {
// "local_lights" on the sl component and "radius" on a light (§7.3 local lights).
TEST(SlComponent, ParsesLocalLightsAndLightRadius) {
  const fs::path path = writeLevel("sl-local-ok", R"({"id": "a", "dynamic": true, )" + mesh() +
                                                      R"(, "sl": {"local_lights": true}},
                                                     {"id": "l", "light": {"type": "spot", "radius": 0.25}},
                                                     {"id": "m", "light": {"type": "point"}})");
  const scene::Level level = scene::loadLevel(path);
  ASSERT_EQ(level.entities.size(), 3u);
  EXPECT_TRUE(level.entities[0].sl->localLights);
  EXPECT_FLOAT_EQ(level.entities[1].light->radius, 0.25f);
  EXPECT_FLOAT_EQ(level.entities[2].light->radius, 0.0f);
}

TEST(SlComponent, ParsesHierarchy) {
  const fs::path path = writeLevel("sl-hierarchy-ok", R"({"id": "a", "dynamic": true, )" + mesh() +
                                                          R"(, "sl": {"hierarchy": true}},
                                                         {"id": "b", "dynamic": true, )" + mesh() + R"(, "sl": {}})");
  const scene::Level level = scene::loadLevel(path);
  ASSERT_EQ(level.entities.size(), 2u);
  EXPECT_TRUE(level.entities[0].sl->hierarchy);
  EXPECT_FALSE(level.entities[1].sl->hierarchy);  // off by default
}
}  // namespace
}  // namespace bounce::gi::sl

// "blocked_read": "map" on a device whose maxUniformBufferRange is below the maps' block reads the SH
// instead (SessionRuntime::enableGpu warns once): the maps fit where specSpheres(N) KiB ≤ the range.
// Vulkan's guaranteed 16 KiB holds 16 SLs (character-one.json's one set), not the characters level's
// 2 × 16; lavapipe's 64 KiB holds the 64 the level format allows.
namespace bounce::gi::sl {
TEST(SlTechnique, MapsFitTheDevicesUniformRangeOrTheLevelReadsTheSh) {
  EXPECT_TRUE(mapsFitUniformRange(16, 16384));
  EXPECT_FALSE(mapsFitUniformRange(17, 16384));  // 24 KiB: kSpheres rounds 17 up to 24
  EXPECT_FALSE(mapsFitUniformRange(32, 16384));
  EXPECT_TRUE(mapsFitUniformRange(32, 65536));
  EXPECT_TRUE(mapsFitUniformRange(64, 65536));
  EXPECT_FALSE(mapsFitUniformRange(65, std::uint64_t(1) << 32));  // beyond kMaxMappedSpheres on any device
  EXPECT_EQ(indirectBlockBytes(0), std::size_t(8192));             // the SH layout, whatever the range
}
}  // namespace bounce::gi::sl
