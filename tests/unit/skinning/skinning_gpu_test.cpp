// GPU skinning (shaders/skinning/skinning.comp) against the CPU face (engine/anim/skinning.cpp):
// every vertex of CesiumMan and Fox at several clip times; a skinned mesh's shadow moves when only
// its clip plays; the skinning pass runs only when a skinned entity is drawn; and the raster
// entity-id silhouette of a posed character matches the reference tracer's (same CPU pose).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "engine/anim/animator.hpp"
#include "engine/core/file.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/ref/tracer.hpp"
#include "engine/render/gpu_scene.hpp"
#include "engine/render/mesh_gpu.hpp"
#include "engine/scene/components.hpp"
#include "game/session.hpp"

using namespace bounce;
namespace fs = std::filesystem;

namespace {

// CPU = GPU tolerance, fp32: both sum the same ≤ 8 weighted joint matrices in the same order, but
// the GPU may fuse multiply-adds and computes the normal matrix with GLSL inverse() instead of
// glm::inverseTranspose(). Positions: relative to the larger of |p| and the joint translations
// (Fox's asset space is in centimetres, |p| ~ 100), 32 ulps of 1 = 4e-6. Normals are unit vectors:
// 1e-5 absolute (a cofactor 3×3 inverse loses a few ulps more when a joint scales).
constexpr float kPositionRelTol = 4e-6f;
constexpr float kNormalTol = 1e-5f;

fs::path assets() {
  const char* env = std::getenv("BOUNCE_SHARED_DIR");
  return fs::path(env && *env ? env : BOUNCE_SHARED_DIR) / "assets";
}
fs::path out() { return fs::path(BOUNCE_TEST_OUT) / "skinning"; }

std::string sci(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3e", v);
  return b;
}

std::string meshEntity(const std::string& id, const fs::path& asset, const std::string& extra) {
  return R"({"id": ")" + id + R"(", "mesh": {"asset": ")" + asset.string() + R"("})" + extra + "}";
}

fs::path writeLevel(const std::string& name, const std::string& effects, const std::vector<std::string>& entities) {
  std::string es;
  for (const auto& e : entities) es += (es.empty() ? "" : ",\n") + e;
  const fs::path p = out() / name;
  writeFileAtomic(p, R"({"bounce_level": 1, "effects": )" + effects + R"(, "entities": [)" + es + "]}");
  return p;
}

const std::string kCamera =
    R"({"id": "camera", "transform": {"translation": [0, 1, 3.2]}, "camera": {"yfov_deg": 50, "near": 0.05, "far": 20}})";

// The CPU face of the session's last frame: the same registry, level and time extracted with GPU
// skinning off (CPU skinning, morphs and subdivision fill posedVertices; no jobs are queued).
render::RenderWorld cpuFace(game::Session& session) {
  render::RenderWorld cpuWorld;
  render::ExtractOptions options;
  options.extent = {32, 32};
  options.gpuSkinning = false;
  session.gpuScene().extract(session.registry(), session.level(), options, cpuWorld);
  return cpuWorld;
}

// One frame's CPU = GPU comparison of posed vertices (8 floats each: position, normal, uv): the worst
// position distance relative to max(1, |p|), the worst normal distance, and the uv mismatches
// (compared exactly: both faces copy the bind uv).
struct PosedCompare {
  float worstP = 0.0f, worstN = 0.0f;
  std::size_t vertices = 0, uvMismatches = 0, firstUvMismatch = 0;

  // Vertices [gpuBase, gpuBase + count) of `gpu` against [cpuBase, cpuBase + count) of `cpu`.
  void add(const std::vector<float>& gpu, std::size_t gpuBase, const std::vector<float>& cpu, std::size_t cpuBase,
           std::size_t count) {
    for (std::size_t v = 0; v < count; ++v) {
      const float* g = &gpu[(gpuBase + v) * 8];
      const float* c = &cpu[(cpuBase + v) * 8];
      const glm::vec3 gp(g[0], g[1], g[2]), cp(c[0], c[1], c[2]);
      worstP = std::max(worstP, glm::distance(gp, cp) / std::max(1.0f, glm::length(cp)));
      worstN = std::max(worstN, glm::distance(glm::vec3(g[3], g[4], g[5]), glm::vec3(c[3], c[4], c[5])));
      if ((g[6] != c[6] || g[7] != c[7]) && uvMismatches++ == 0) firstUvMismatch = v;
      ++vertices;
    }
  }
  // The tolerances, and the worst values as the test's properties "<prefix>worst-position-rel-t<100 t>"
  // and "<prefix>worst-normal-t<100 t>".
  void expectWithin(float positionRelTol, float normalTol, const std::string& prefix, double t) const {
    EXPECT_LE(worstP, positionRelTol);
    EXPECT_LE(worstN, normalTol);
    ::testing::Test::RecordProperty(prefix + "worst-position-rel-t" + std::to_string(int(t * 100)), sci(worstP));
    ::testing::Test::RecordProperty(prefix + "worst-normal-t" + std::to_string(int(t * 100)), sci(worstN));
  }
};

TEST(SkinningGpu, CpuEqualsGpuOnEveryVertexOfCesiumManAndFox) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path level = writeLevel(
      "cpu-gpu.json", R"(["direct"])",
      {kCamera, meshEntity("man", assets() / "CesiumMan/glTF-Binary/CesiumMan.glb", ""),
       meshEntity("fox", assets() / "Fox/glTF-Binary/Fox.glb",
                  R"(, "transform": {"translation": [1, 0, 0], "scale": [0.01, 0.01, 0.01]}, "animation": {"clip": "Run"})")});
  game::Session session(ctx, scene::loadLevel(level));
  gpu::OffscreenPresenter presenter(ctx, {32, 32});
  std::size_t checked = 0;
  for (double t : {0.0, 0.37, 1.1, 2.9}) {
    SCOPED_TRACE(t);
    session.update(t);
    session.render(presenter, {});
    const std::vector<float> gpuPosed = session.renderer().readPosedVertices();
    ASSERT_EQ(session.world().skinJobs.size(), 2u);  // both characters went through the pass
    const render::RenderWorld cpuWorld = cpuFace(session);
    ASSERT_TRUE(cpuWorld.skinJobs.empty());
    ASSERT_EQ(cpuWorld.posedVertices.size(), gpuPosed.size());
    PosedCompare cmp;
    cmp.add(gpuPosed, 0, cpuWorld.posedVertices, 0, gpuPosed.size() / 8);
    ASSERT_EQ(cmp.uvMismatches, 0u) << "uv of vertex " << cmp.firstUvMismatch;
    checked += cmp.vertices;
    cmp.expectWithin(kPositionRelTol, kNormalTol, "", t);
  }
  EXPECT_GT(checked, 4u * 4000u);  // CesiumMan 3273 + Fox 1728 vertices, every time
}

// Morph targets on the GPU (the skinning pass's morph step) against MorphJob on the CPU, on the
// generated content/src/morph asset (the shared assets hold no morphing model): "sheet" morphs
// alone, "arm" morphs then skins (two joints), both driven by the clip "Wave". Same tolerances as
// skinning: three weighted displacements add a few ulps to positions of size ~1 m, and a
// morph-only normal is the unnormalised n₀ + Σ w·Δn (|n| ≤ ~2) on both faces.
TEST(SkinningGpu, MorphTargetsCpuEqualsGpuOnEveryVertex) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path morph = fs::path(BOUNCE_SOURCE_DIR) / "content/src/morph/morph.gltf";
  const fs::path level = writeLevel("morph-cpu-gpu.json", R"(["direct"])",
                                    {kCamera, meshEntity("morph", morph, R"(, "animation": {"clip": "Wave"})")});
  game::Session session(ctx, scene::loadLevel(level));
  gpu::OffscreenPresenter presenter(ctx, {32, 32});
  std::size_t checked = 0;
  float largestMorph = 0.0f;
  for (double t : {0.0, 0.3, 0.8, 1.3, 1.75}) {
    SCOPED_TRACE(t);
    session.update(t);
    session.render(presenter, {});
    EXPECT_EQ(session.renderer().executedPasses(), (std::vector<std::string>{"skinning", "gbuffer", "lighting", "tonemap"}));
    const std::vector<float> gpuPosed = session.renderer().readPosedVertices();
    const auto& jobs = session.world().skinJobs;
    ASSERT_EQ(jobs.size(), 2u);  // both meshes went through the pass
    EXPECT_FALSE(jobs[0].skinned);  // sheet: morph only
    EXPECT_TRUE(jobs[1].skinned);   // arm: morph, then skin
    EXPECT_EQ(jobs[0].mesh->morphTargets, 3u);
    EXPECT_EQ(jobs[1].mesh->morphTargets, 3u);
    ASSERT_EQ(session.world().morphWeights.size(), 6u);
    const render::RenderWorld cpuWorld = cpuFace(session);
    ASSERT_TRUE(cpuWorld.skinJobs.empty());
    ASSERT_EQ(cpuWorld.posedVertices.size(), gpuPosed.size());
    ASSERT_EQ(cpuWorld.draws.size(), session.world().draws.size());
    // The GPU world's conservative bounds (bind box grown by w_t·each target's box, then under every
    // joint) contain the CPU world's, which come from the exact posed vertices.
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(session.world().sceneMin[k], cpuWorld.sceneMin[k]) << "axis " << k;
      EXPECT_GE(session.world().sceneMax[k], cpuWorld.sceneMax[k]) << "axis " << k;
    }
    PosedCompare cmp;
    cmp.add(gpuPosed, 0, cpuWorld.posedVertices, 0, gpuPosed.size() / 8);
    ASSERT_EQ(cmp.uvMismatches, 0u) << "uv of vertex " << cmp.firstUvMismatch;
    checked += cmp.vertices;
    // The sheet's bind pose is z = 0 everywhere: its posed |z| is how far the morph moved it.
    for (std::size_t v = 0; v < 32 * 32; ++v) largestMorph = std::max(largestMorph, std::abs(cpuWorld.posedVertices[v * 8 + 2]));
    cmp.expectWithin(kPositionRelTol, kNormalTol, "morph-", t);
  }
  EXPECT_EQ(checked, 5u * 2u * 32u * 32u);
  EXPECT_GT(largestMorph, 0.15f);  // the bulge's weight reaches 1 (0.25 m) at t = 0.5 ± 0.2
}

// Subdivided cages, CPU face (engine/anim LimitStencilJob after CPU skinning) vs GPU face (the
// subdivision pass after the skinning pass). Both sum the same stencil weights in the same order
// on cages that already differ by kPositionRelTol; a limit point sums 20–60 weighted cage points,
// so a few dozen ulps: 1e-5 relative. Normals come from the cross product of two tangents that
// are themselves sums with cancelling weights: 1e-4 absolute on unit vectors.
constexpr float kRefinedPositionRelTol = 1e-5f;
constexpr float kRefinedNormalTol = 1e-4f;

// Each posed mesh instance's vertex range in a world: (posedBase, vertex count), in draw order.
std::vector<std::pair<std::uint32_t, std::uint32_t>> posedRanges(const render::RenderWorld& w) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const auto& d : w.draws)
    if (d.posed() && (out.empty() || out.back().first != d.posedBase)) out.emplace_back(d.posedBase, d.mesh->vertexCount);
  return out;
}

TEST(SkinningGpu, SubdividedCagesCpuEqualsGpuOnEveryRefinedVertex) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const std::string subdiv = R"(, "subdivision": {"scheme": "catmull-clark", "levels": 1})";
  const fs::path level = writeLevel(
      "subdiv-cpu-gpu.json", R"(["direct"])",
      {kCamera,
       R"({"id": "man", "mesh": {"asset": ")" + (assets() / "CesiumMan/glTF-Binary/CesiumMan.glb").string() + "\"" + subdiv + "}}",
       R"({"id": "fox", "mesh": {"asset": ")" + (assets() / "Fox/glTF-Binary/Fox.glb").string() + "\"" + subdiv +
           R"(}, "transform": {"translation": [1, 0, 0], "scale": [0.01, 0.01, 0.01]}, "animation": {"clip": "Run"}})"});
  game::Session session(ctx, scene::loadLevel(level));
  gpu::OffscreenPresenter presenter(ctx, {32, 32});
  std::size_t checked = 0;
  for (double t : {0.0, 0.37, 1.1}) {
    SCOPED_TRACE(t);
    session.update(t);
    session.render(presenter, {});
    EXPECT_EQ(session.renderer().executedPasses(),
              (std::vector<std::string>{"skinning", "subdivision", "gbuffer", "lighting", "tonemap"}));
    const std::vector<float> gpuPosed = session.renderer().readPosedVertices();
    ASSERT_EQ(session.world().skinJobs.size(), 2u);
    ASSERT_EQ(session.world().subdivisionJobs.size(), 2u);
    const render::RenderWorld cpuWorld = cpuFace(session);
    ASSERT_TRUE(cpuWorld.subdivisionJobs.empty());
    const auto gpuRanges = posedRanges(session.world()), cpuRanges = posedRanges(cpuWorld);
    ASSERT_EQ(gpuRanges.size(), 2u);
    ASSERT_EQ(cpuRanges.size(), 2u);
    PosedCompare cmp;
    for (std::size_t r = 0; r < 2; ++r) {
      ASSERT_EQ(gpuRanges[r].second, cpuRanges[r].second);
      cmp.add(gpuPosed, gpuRanges[r].first, cpuWorld.posedVertices, cpuRanges[r].first, gpuRanges[r].second);
      ASSERT_EQ(cmp.uvMismatches, 0u) << "uv of refined vertex " << cmp.firstUvMismatch;
    }
    checked += cmp.vertices;
    cmp.expectWithin(kRefinedPositionRelTol, kRefinedNormalTol, "refined-", t);
  }
  EXPECT_GE(checked, 3u * 19965u);  // CesiumMan and Fox refined once (catmull-clark, 1 level): 19,965 vertices
}

// A subdivided morphed mesh: its cage morphed (and skinned) by the skinning pass, then refined by
// the subdivision pass, against the CPU's MorphJob → SkinningJob → LimitStencilJob. Tolerances as
// for the subdivided characters below.
TEST(SkinningGpu, SubdividedMorphCagesCpuEqualsGpu) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path morph = fs::path(BOUNCE_SOURCE_DIR) / "content/src/morph/morph.gltf";
  const fs::path level = writeLevel(
      "morph-subdiv-cpu-gpu.json", R"(["direct"])",
      {kCamera, R"({"id": "morph", "mesh": {"asset": ")" + morph.string() +
                    R"(", "subdivision": {"scheme": "catmull-clark", "levels": 1}}, "animation": {"clip": "Wave"}})"});
  game::Session session(ctx, scene::loadLevel(level));
  gpu::OffscreenPresenter presenter(ctx, {32, 32});
  std::size_t checked = 0;
  for (double t : {0.3, 1.3}) {
    SCOPED_TRACE(t);
    session.update(t);
    session.render(presenter, {});
    EXPECT_EQ(session.renderer().executedPasses(),
              (std::vector<std::string>{"skinning", "subdivision", "gbuffer", "lighting", "tonemap"}));
    const std::vector<float> gpuPosed = session.renderer().readPosedVertices();
    ASSERT_EQ(session.world().skinJobs.size(), 2u);
    ASSERT_EQ(session.world().subdivisionJobs.size(), 2u);
    const render::RenderWorld cpuWorld = cpuFace(session);
    const auto gpuRanges = posedRanges(session.world()), cpuRanges = posedRanges(cpuWorld);
    ASSERT_EQ(gpuRanges.size(), 2u);
    ASSERT_EQ(cpuRanges.size(), 2u);
    PosedCompare cmp;
    for (std::size_t r = 0; r < 2; ++r) {
      ASSERT_EQ(gpuRanges[r].second, cpuRanges[r].second);
      cmp.add(gpuPosed, gpuRanges[r].first, cpuWorld.posedVertices, cpuRanges[r].first, gpuRanges[r].second);
    }
    checked += cmp.vertices;
    cmp.expectWithin(kRefinedPositionRelTol, kRefinedNormalTol, "morph-refined-", t);
  }
  EXPECT_GE(checked, 2u * 2u * 32u * 32u);  // refined: more vertices than the two 32×32 cages
}

TEST(SkinningGpu, PassRunsOnlyWithASkinnedEntityAndBeforeTheDraws) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path with = writeLevel("pass-with.json", R"(["direct", "shadows"])",
                                   {kCamera, meshEntity("man", assets() / "CesiumMan/glTF-Binary/CesiumMan.glb", ""),
                                    R"({"id": "lamp", "transform": {"translation": [0, 3, 1]}, "light": {"type": "point", "intensity": 5}})"});
  const fs::path without = writeLevel("pass-without.json", R"(["direct", "shadows"])",
                                      {kCamera, meshEntity("box", assets() / "Box/glTF-Binary/Box.glb", ""),
                                       R"({"id": "lamp", "transform": {"translation": [0, 3, 1]}, "light": {"type": "point", "intensity": 5}})"});
  auto passes = [&](const fs::path& level) {
    game::Session session(ctx, scene::loadLevel(level));
    session.update(0.5);
    gpu::OffscreenPresenter presenter(ctx, {32, 32});
    session.render(presenter, {});
    return session.renderer().executedPasses();
  };
  EXPECT_EQ(passes(with), (std::vector<std::string>{"skinning", "shadow", "gbuffer", "lighting", "tonemap"}));
  EXPECT_EQ(passes(without), (std::vector<std::string>{"shadow", "gbuffer", "lighting", "tonemap"}));
}

TEST(SkinningGpu, SkinningAndSubdivisionCulledWhenNoSkinnedEntityIsVisibleOrCastsAShadow) {
  // The passes are added whenever a skinned entity exists (its skin job is queued); the graph culls
  // them when neither the G-buffer (no posed draw in the camera frustum) nor the shadow pass (none
  // in a shadow layer's) reads the posed vertices. The camera at z = 3.2 looks down −z: the
  // character at z = 6 is behind it; a point light's six faces see all around it.
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const std::string man = (assets() / "CesiumMan/glTF-Binary/CesiumMan.glb").string();
  const std::string subdiv = R"(, "subdivision": {"scheme": "catmull-clark", "levels": 1})";
  const std::string lamp = R"({"id": "lamp", "transform": {"translation": [0, 3, 4]}, "light": {"type": "point", "intensity": 5}})";
  auto passes = [&](const std::string& name, const std::string& effects, const std::string& z, bool subdivided, bool light) {
    std::vector<std::string> entities = {
        kCamera, R"({"id": "man", "transform": {"translation": [0, 0, )" + z + R"(]}, "mesh": {"asset": ")" + man + "\"" +
                     (subdivided ? subdiv : "") + "}}"};
    if (light) entities.push_back(lamp);
    game::Session session(ctx, scene::loadLevel(writeLevel(name, effects, entities)));
    session.update(0.5);
    gpu::OffscreenPresenter presenter(ctx, {32, 32});
    session.render(presenter, {});
    EXPECT_EQ(session.world().skinJobs.size(), 1u) << name;  // queued: any culling is the graph's
    EXPECT_EQ(session.world().subdivisionJobs.size(), subdivided ? 1u : 0u) << name;
    return session.renderer().executedPasses();
  };
  using P = std::vector<std::string>;
  EXPECT_EQ(passes("cull-visible.json", R"(["direct"])", "0", false, false), (P{"skinning", "gbuffer", "lighting", "tonemap"}));
  EXPECT_EQ(passes("cull-behind.json", R"(["direct"])", "6", false, false), (P{"gbuffer", "lighting", "tonemap"}));
  EXPECT_EQ(passes("cull-behind-shadow.json", R"(["direct", "shadows"])", "6", false, true),
            (P{"skinning", "shadow", "gbuffer", "lighting", "tonemap"}));
  EXPECT_EQ(passes("cull-sub-visible.json", R"(["direct"])", "0", true, false),
            (P{"skinning", "subdivision", "gbuffer", "lighting", "tonemap"}));
  EXPECT_EQ(passes("cull-sub-behind.json", R"(["direct"])", "6", true, false), (P{"gbuffer", "lighting", "tonemap"}));
}

TEST(SkinningGpu, BoxFrustumTestIsConservativeAndExact) {
  // A camera at the origin looking down −z, 90° field of view, near 0.1, far 10.
  const glm::mat4 viewProj = render::perspectiveVk(glm::radians(90.0f), 1.0f, 0.1f, 10.0f);
  EXPECT_TRUE(render::boxMeetsFrustum(viewProj, {-0.5f, -0.5f, -3.0f}, {0.5f, 0.5f, -2.0f}, true));   // ahead
  EXPECT_FALSE(render::boxMeetsFrustum(viewProj, {-0.5f, -0.5f, 2.0f}, {0.5f, 0.5f, 3.0f}, true));    // behind
  EXPECT_FALSE(render::boxMeetsFrustum(viewProj, {5.0f, -0.5f, -3.0f}, {6.0f, 0.5f, -2.0f}, true));   // right of x = −z
  EXPECT_TRUE(render::boxMeetsFrustum(viewProj, {2.5f, -0.5f, -3.0f}, {6.0f, 0.5f, -2.0f}, true));    // straddles it
  EXPECT_FALSE(render::boxMeetsFrustum(viewProj, {-0.5f, -0.5f, -13.0f}, {0.5f, 0.5f, -11.0f}, true));  // past far
  EXPECT_TRUE(render::boxMeetsFrustum(viewProj, {-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}, true));    // around the eye
  // Between the eye and the near plane: outside with the near plane, inside without it.
  EXPECT_FALSE(render::boxMeetsFrustum(viewProj, {-0.01f, -0.01f, -0.05f}, {0.01f, 0.01f, -0.02f}, true));
  EXPECT_TRUE(render::boxMeetsFrustum(viewProj, {-0.01f, -0.01f, -0.05f}, {0.01f, 0.01f, -0.02f}, false));
}

// Display image of one debug view of `session` at time t.
std::vector<std::uint8_t> view(game::Session& session, double t, render::DebugView v, std::uint32_t size) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  session.update(t);
  gpu::OffscreenPresenter presenter(ctx, {size, size});
  render::FrameSettings s;
  s.debugView = v;
  session.render(presenter, s);
  session.renderer().frames().waitIdle();
  return gpu::readback(ctx, session.renderer().displayImage());
}

// Floor pixels (the same entity colour in both frames, so not the character) whose shadow view
// changes between t = 0 and t = 0.6, on a level where only the clip moves the character.
std::size_t movedShadowPixels(bool animated) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path level = writeLevel(
      animated ? "shadow-animated.json" : "shadow-still.json", R"(["direct", "shadows"])",
      {R"({"id": "camera", "transform": {"translation": [0, 4, 0.3], "rotation_euler_deg": [-90, 0, 0]}, "camera": {"yfov_deg": 60, "near": 0.05, "far": 20}})",
       R"({"id": "floor", "transform": {"scale": [6, 1, 6]}, "mesh": {"asset": ")" +
           (fs::path(BOUNCE_SOURCE_DIR) / "tests/data/render/quad.gltf").string() + R"("}, "material": {"albedo": [0.8, 0.8, 0.8]}})",
       meshEntity("man", assets() / "CesiumMan/glTF-Binary/CesiumMan.glb",
                  animated ? "" : R"(, "animation": false)"),
       R"({"id": "lamp", "transform": {"translation": [1.5, 2.5, 0.5]}, "light": {"type": "point", "intensity": 6}})"});
  game::Session session(ctx, scene::loadLevel(level));
  constexpr std::uint32_t kSize = 128;
  const auto id0 = view(session, 0.0, render::DebugView::EntityId, kSize);
  const auto sh0 = view(session, 0.0, render::DebugView::Shadow, kSize);
  const auto id1 = view(session, 0.6, render::DebugView::EntityId, kSize);
  const auto sh1 = view(session, 0.6, render::DebugView::Shadow, kSize);
  std::size_t moved = 0;
  for (std::size_t p = 0; p < std::size_t(kSize) * kSize; ++p) {
    const bool sameSurface = std::equal(&id0[p * 4], &id0[p * 4 + 3], &id1[p * 4]);
    if (sameSurface && std::abs(int(sh0[p * 4]) - int(sh1[p * 4])) > 64) ++moved;
  }
  return moved;
}

TEST(SkinningGpu, ASkinnedMeshCastsAMovingShadow) {
  // Only the clip plays (no motion): the character's shadow on the floor must change. Seen from
  // above, the walking legs and swinging arms shade ~100+ floor pixels differently at 128².
  constexpr std::size_t kMinMoved = 30;
  const std::size_t moved = movedShadowPixels(true);
  EXPECT_GE(moved, kMinMoved);
  RecordProperty("moved-shadow-pixels", std::to_string(moved));
  EXPECT_EQ(movedShadowPixels(false), 0u);  // "animation": false holds the pose: nothing moves
}

TEST(SkinningGpu, RasterSilhouetteMatchesTheTracersAt256) {
  // Only the character (black background): raster entity-id pixels vs pixels whose tracer camera
  // ray hits the scene, both of the pose at t = 0.8 (the tracer's from the CPU evaluation).
  constexpr std::uint32_t kSize = 256;
  constexpr double kMinIoU = 0.99;
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path level = writeLevel(
      "silhouette.json", R"(["direct"])",
      {R"({"id": "camera", "transform": {"translation": [0.1, 0.8, 2.0]}, "camera": {"yfov_deg": 50, "near": 0.05, "far": 20}})",
       meshEntity("man", assets() / "CesiumMan/glTF-Binary/CesiumMan.glb", "")});
  game::Session session(ctx, scene::loadLevel(level));
  const auto ids = view(session, 0.8, render::DebugView::EntityId, kSize);

  ref::ReferenceAssets refAssets;
  refAssets.load(session.registry(), game::cookCacheDir());
  const ref::SceneBvh bvh(ref::extractScene(session.registry(), session.level(), refAssets));
  std::size_t both = 0, either = 0, raster = 0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      const std::size_t p = std::size_t(y) * kSize + x;
      const bool r = ids[p * 4] | ids[p * 4 + 1] | ids[p * 4 + 2];
      const ref::CameraRay ray = ref::cameraRay(bvh.scene().camera, kSize, kSize, x, y);
      ref::Hit hit;
      const bool t = bvh.intersect(ray.origin, ray.direction, ray.tMin, ray.tMax, hit);
      both += r && t;
      either += r || t;
      raster += r;
    }
  ASSERT_GT(raster, 2000u);  // the character covers a good part of the view
  const double iou = double(both) / double(either);
  EXPECT_GE(iou, kMinIoU);
  RecordProperty("silhouette-iou", sci(iou));
  RecordProperty("silhouette-pixels", std::to_string(raster) + " raster, " + std::to_string(either - both) + " differ");
}

}  // namespace
