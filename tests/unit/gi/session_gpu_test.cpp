// Session builds the table's techniques (engine/gi/technique.hpp): only named effects in which an
// entity takes part run; unused ones are noted once and do not count as running (the
// play overlay shows them off); an effect named later (a play key) is built then, nodes kept in
// table order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>

#include "engine/core/error.hpp"
#include "engine/gpu/pipeline_table.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/scene/level.hpp"
#include "engine/gpu/testing.hpp"
#include "game/session.hpp"

using namespace bounce;

namespace {

// cornell-10: no entity with a vlm, sl or rtf component (cornell-1's prop has an sl one, cornell-5's props rtf).
const std::filesystem::path kCornell = std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-10.json";
constexpr VkExtent2D kExtent{64, 64};

scene::EffectSet effects(std::initializer_list<scene::Effect> list) {
  scene::EffectSet s;
  for (auto e : list) s.add(e);
  return s;
}

TEST(SessionTechniques, UnusedEffectsAreNotedAndDoNotRun) {
  game::Session session(gpu::testkit::sharedContext(),
                        game::loadLevelWithEffects(kCornell, std::vector<std::string>{"direct", "vlm", "sl", "rtf"}));
  EXPECT_EQ(session.notes(),
            (std::vector<std::string>{
                "note: effect vlm is named but no entity takes part (no entity has a vlm component or a mesh with "
                "extras.bounce_vlm): no pass",
                "note: effect sl is named but no entity takes part (no entity has an sl component): no pass",
                "note: effect rtf is named but no entity takes part (no entity has an rtf component): no pass"}));
  EXPECT_EQ(session.vlm(), nullptr);
  EXPECT_FALSE(session.runs(scene::Effect::Vlm));
  EXPECT_FALSE(session.runs(scene::Effect::Sl));
  EXPECT_FALSE(session.runs(scene::Effect::Rtf));
  EXPECT_TRUE(session.runs(scene::Effect::Direct));
  EXPECT_EQ(session.runningEffects(), effects({scene::Effect::Direct}));  // what the overlay shows green
  EXPECT_TRUE(session.profileLines().empty());

  gpu::OffscreenPresenter presenter(gpu::testkit::sharedContext(), kExtent);
  session.update(0.0);
  session.render(presenter, {});
  EXPECT_EQ(session.renderer().executedPasses(), (std::vector<std::string>{"gbuffer", "lighting", "tonemap"}));
  EXPECT_EQ(session.notes().size(), 3u) << "a second frame notes nothing again";
  session.renderer().frames().waitIdle();
}

// The play overlay's disabled checkboxes: whyCannotRun gives the table's note for an effect this level
// can never run, named or not, and nothing for one it can (the renderer's own passes, a technique
// with a participant even when not named).
TEST(SessionTechniques, WhyCannotRunNamesUnusedEffectsOnly) {
  game::Session session(gpu::testkit::sharedContext(),
                        game::loadLevelWithEffects(kCornell, std::vector<std::string>{"direct"}));
  EXPECT_EQ(session.whyCannotRun(scene::Effect::Direct), "");
  EXPECT_EQ(session.whyCannotRun(scene::Effect::Shadows), "");
  EXPECT_EQ(session.whyCannotRun(scene::Effect::Probes), "");
  EXPECT_EQ(session.whyCannotRun(scene::Effect::Ssao), "");
  EXPECT_EQ(session.whyCannotRun(scene::Effect::Sl),
            "note: effect sl is named but no entity takes part (no entity has an sl component): no pass");
  EXPECT_EQ(session.whyCannotRun(scene::Effect::Rtf),
            "note: effect rtf is named but no entity takes part (no entity has an rtf component): no pass");
  EXPECT_EQ(session.whyCannotRun(scene::Effect::Vlm),
            "note: effect vlm is named but no entity takes part (no entity has a vlm component or a mesh with "
            "extras.bounce_vlm): no pass");
  EXPECT_TRUE(session.notes().empty()) << "asking prints and records nothing";
}

TEST(SessionTechniques, EffectNamedLaterIsBuiltInTableOrder) {
  game::Session session(gpu::testkit::sharedContext(),
                        game::loadLevelWithEffects(kCornell, std::vector<std::string>{"direct", "probes"}));
  EXPECT_TRUE(session.notes().empty());
  EXPECT_NE(session.probes(), nullptr);
  EXPECT_EQ(session.ao(gi::ao::Kind::Ssao), nullptr);
  // The play key for ssao: named now, built at the next render, and run BEFORE probes (table order:
  // probes read "ao.term").
  session.level().effects.add(scene::Effect::Ssao);
  gpu::OffscreenPresenter presenter(gpu::testkit::sharedContext(), kExtent);
  session.update(0.0);
  session.render(presenter, {});
  EXPECT_NE(session.ao(gi::ao::Kind::Ssao), nullptr);
  EXPECT_TRUE(session.runs(scene::Effect::Ssao));
  EXPECT_EQ(session.renderer().executedPasses(),
            (std::vector<std::string>{"gbuffer", "lighting", "ssao", "probes", "tonemap"}));
  session.renderer().frames().waitIdle();
}

}  // namespace

// The lighting pass's uniform blocks hold at most kMaxLights lights and kMaxShadowLayers shadow
// layers: a level over that is refused as bad input when the session is made (one line naming the
// file, exit 2 in the CLI), not an internal error at the first frame.
TEST(SessionLights, MoreShadowLayersThanTheLightingPassHoldsIsBadInput) {
  auto levelWith = [](int pointLights) {
    std::string entities;
    for (int i = 0; i < pointLights; ++i)
      entities += std::string(i ? "," : "") + R"({"id": "lamp)" + std::to_string(i) +
                  R"(", "transform": {"translation": [0, 1, 0]}, "light": {"type": "point", "shadows": true}})";
    const auto path = std::filesystem::path(BOUNCE_TEST_OUT) / ("lights-" + std::to_string(pointLights) + ".json");
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << R"({"bounce_level": 1, "effects": ["direct", "shadows"], "entities": [)" + entities + "]}";
    return path;
  };
  // 32 shadowed point lights = 192 layers: the most that fits.
  EXPECT_NO_THROW(game::Session(gpu::testkit::sharedContext(), scene::loadLevel(levelWith(32))));
  const auto over = levelWith(33);
  try {
    game::Session session(gpu::testkit::sharedContext(), scene::loadLevel(over));
    FAIL() << "33 shadowed point lights were accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), over.string() + ": /entities: 33 lights with 198 shadow layers (expected at most 128 "
                                     "lights and 192 shadow layers; a point light with shadows takes 6, a spot 1)");
  }
}

// A box with a DNRT and an RTF field above a lit floor; `transform` and `motion` are the box's JSON.
// Effects dnrt and rtf only (no direct light, black background): the HDR image holds the box's GI
// terms alone. Tiny fields (grid 16, RTF's smallest settings): the bakes take well under a second.
std::filesystem::path boxLevel(const std::string& name, const std::string& transform, const std::string& motion,
                               const std::string& effects) {
  const std::string src = BOUNCE_SOURCE_DIR;
  const auto path = std::filesystem::path(BOUNCE_TEST_OUT) / "gi" / (name + ".json");
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << R"({"bounce_level": 1, "effects": )" + effects + R"(, "entities": [
    {"id": "floor", "transform": {"scale": [4, 1, 4]}, "mesh": {"asset": ")" + src + R"(/tests/data/render/quad.gltf"}},
    {"id": "camera", "transform": {"translation": [0, 1, 0], "rotation_euler_deg": [-90, 0, 0]},
     "camera": {"yfov_deg": 60, "near": 0.05, "far": 5}},
    {"id": "lamp", "transform": {"translation": [0, 2, 0]}, "light": {"type": "point", "intensity": 1}},
    {"id": "box", "dynamic": true, "transform": )" + transform + motion + R"(,
     "mesh": {"asset": ")" + src + R"(/content/src/BoxTextured/glTF-Draco-gltfpipeline/BoxTextured.gltf"},
     "dnrt": {"sh": 4, "grid": 16, "rays": 64},
     "rtf": {"proxies": 4, "bounces": 1, "spheres": 4, "face": 4, "rays": 8, "vertex_rays": 6, "clusters": 4,
             "components": 4, "inner": 2.5, "outer": 5}}]})";
  return path;
}

// A level transform whose scale place() refuses (gi/placement.hpp: smallest axis scale × field radius
// under ~1e-30) is the level's bad input when the session is made, one line at the entity's
// transform (exit 2 in the CLI), for DNRT and RTF alike; 1e-29 is placed.
TEST(SessionPlacement, ScaleTooSmallToPlaceIsBadInputAtTheTransform) {
  const std::string tiny = R"({"translation": [0, 0.12, 0], "scale": [1e-31, 1e-31, 1e-31]})";
  for (const std::string technique : {"dnrt", "rtf"}) {
    const auto path = boxLevel("tiny-" + technique, tiny, "", "[\"" + technique + "\"]");
    try {
      game::Session session(gpu::testkit::sharedContext(), scene::loadLevel(path));
      ADD_FAILURE() << technique << ": scale 1e-31 was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), path.string() + ": /entities/3/transform: " + technique +
                                           " cannot place \"box\": smallest world axis scale 1e-31 × field radius 0.866 "
                                           "(expected a finite transform whose smallest axis scale × the field radius is "
                                           "at least ~1e-30)");
    }
  }
  const auto placeable =
      boxLevel("small", R"({"translation": [0, 0.12, 0], "scale": [1e-29, 1e-29, 1e-29]})", "", R"(["dnrt", "rtf"])");
  EXPECT_NO_THROW(game::Session(gpu::testkit::sharedContext(), scene::loadLevel(placeable)));
}

// A motion whose scale passes through 0 (0.1 → −0.1 over 2 s: exactly 0 at t = 1) is no error: a
// frame whose transform place() refuses skips the object's GI, so DNRT and RTF add nothing there
// (every HDR value exactly 0, all finite) and the object's terms come back after it (mirrored).
TEST(SessionPlacement, ScaleThroughZeroSkipsTheObjectsGiForThatFrame) {
  const auto path = boxLevel("through-zero", R"({"translation": [0, 0.12, 0]})",
                             R"(, "motion": {"keyframes": {"times": [0, 2], "scale": [[0.1, 0.1, 0.1], [-0.1, -0.1, -0.1]],
                                 "mode": "once"}})",
                             R"(["dnrt", "rtf"])");
  game::Session session(gpu::testkit::sharedContext(), scene::loadLevel(path));
  gpu::OffscreenPresenter presenter(gpu::testkit::sharedContext(), kExtent);
  render::FrameSettings settings;
  settings.keepHdr = true;
  for (const double t : {0.0, 1.0, 2.0}) {
    session.update(t);
    ASSERT_NO_THROW(session.render(presenter, settings)) << "t = " << t;
    const std::vector<float> hdr = session.renderer().readHdr();
    ASSERT_EQ(hdr.size(), std::size_t(kExtent.width) * kExtent.height * 3);
    float largest = 0.0f;
    std::size_t nonFinite = 0;
    for (float v : hdr) {
      nonFinite += std::isfinite(v) ? 0 : 1;
      largest = std::max(largest, std::abs(v));
    }
    EXPECT_EQ(nonFinite, 0u) << "t = " << t;
    if (t == 1.0)
      EXPECT_EQ(largest, 0.0f) << "the object's GI at scale 0";
    else
      EXPECT_GT(largest, 1e-4f) << "t = " << t << ": the object's GI (scale ±0.1)";
  }
  session.renderer().frames().waitIdle();
}

// The Context's pipeline table (engine/gpu/pipeline_table.hpp), as `bounce accuracy` uses it: two
// Sessions per row on one Context. The second Session of a level builds no pipeline — every request
// it makes (as many as the first made) is answered from the table — and its image is bit-identical
// to one rendered with reuse off, where every request builds its own pipeline (exact bytes: the same
// creation input gives the same pipeline, so no tolerance). Renderer, shadows, DNRT and RTF passes.
TEST(SessionPipelines, SecondSessionOnOneContextBuildsNoneAndRendersAsWithReuseOff) {
  const auto path = boxLevel("pipelines", R"({"translation": [0, 0.12, 0], "scale": [0.1, 0.1, 0.1]})", "",
                             R"(["direct", "shadows", "dnrt", "rtf"])");
  auto render = [&](gpu::Context& ctx) {
    game::Session session(ctx, scene::loadLevel(path));
    gpu::OffscreenPresenter presenter(ctx, kExtent);
    render::FrameSettings settings;
    settings.keepHdr = true;
    session.update(0.0);
    session.render(presenter, settings);
    std::vector<float> hdr = session.renderer().readHdr();
    session.renderer().frames().waitIdle();
    return hdr;
  };
  gpu::ContextOptions on, off;
  on.reusePipelines = true;
  off.reusePipelines = false;
  gpu::Context shared(on);
  render(shared);  // the first Session: builds every pipeline (and bakes the fields into the cache)
  const gpu::PipelineTable::Counts first = shared.pipelines().counts();
  const std::vector<float> reused = render(shared);
  const gpu::PipelineTable::Counts second = shared.pipelines().counts();
  const std::uint64_t requests = first.built + first.reused;
  EXPECT_GT(first.built, 10u) << "gbuffer, shadow, lighting, tonemap, DNRT's and RTF's pipelines";
  EXPECT_EQ(second.built, first.built) << "the second Session built pipelines";
  EXPECT_EQ(second.reused - first.reused, requests);
  EXPECT_EQ(second.held, first.built);

  gpu::Context own(off);
  const std::vector<float> plain = render(own);
  EXPECT_EQ(own.pipelines().counts().built, requests) << "reuse off: every request builds";
  EXPECT_EQ(own.pipelines().counts().held, 0u);
  ASSERT_EQ(reused.size(), plain.size());
  EXPECT_EQ(std::memcmp(reused.data(), plain.data(), plain.size() * sizeof(float)), 0)
      << "the image with the table's pipelines differs from the one with pipelines of its own";
  float largest = 0.0f;
  for (float v : plain) largest = std::max(largest, std::abs(v));
  EXPECT_GT(largest, 1e-3f) << "a lit image, not two black ones";
}
