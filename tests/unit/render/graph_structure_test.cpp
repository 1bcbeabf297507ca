// The per-frame render graph on a real level (content/levels/cornell-1.json): which passes exist
// (DOT from Renderer::graphDot) and which run (Renderer::executedPasses), as exact lists. This is
// "simulate only the effects a scene calls for" and the graph's cull step, seen from the renderer.
// Also: VkBackend pools transient images per frame slot, so a steady stream of frames creates no
// new physical images after every slot has recorded once.
#include <gtest/gtest.h>

#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/render/graph/usage.hpp"
#include "game/session.hpp"

using namespace bounce;

namespace {

const std::filesystem::path kCornell = std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json";
constexpr VkExtent2D kExtent{64, 64};
using Passes = std::vector<std::string>;

struct Result {
  Passes executed;
  std::string dot;
};

Result renderOnce(const std::optional<std::vector<std::string>>& effects, const render::FrameSettings& settings) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session(ctx, game::loadLevelWithEffects(kCornell, effects));
  session.update(0.0);
  gpu::OffscreenPresenter presenter(ctx, kExtent);
  session.render(presenter, settings);
  Result r;
  r.executed = session.renderer().executedPasses();
  r.dot = session.renderer().graphDot(session.world(), kExtent, settings);
  session.renderer().frames().waitIdle();
  return r;
}

// A pass node in the DOT dump: `[label="NAME", shape=box` (graph/dot.cpp), then its style.
bool hasPass(const std::string& dot, const std::string& name) {
  return dot.find("[label=\"" + name + "\", shape=box") != std::string::npos;
}
bool passCulled(const std::string& dot, const std::string& name) {
  return dot.find("[label=\"" + name + "\", shape=box, style=\"dashed\"") != std::string::npos;
}

}  // namespace

TEST(RendererGraph, DirectOnlyHasNoShadowPass) {
  const Result r = renderOnce(std::vector<std::string>{"direct"}, {});
  EXPECT_EQ(r.executed, (Passes{"gbuffer", "lighting", "tonemap"}));
  EXPECT_EQ(r.dot.find("shadow"), std::string::npos) << "no shadow pass, atlas or anything else named so";
  EXPECT_TRUE(hasPass(r.dot, "gbuffer"));
  EXPECT_TRUE(hasPass(r.dot, "lighting"));
  EXPECT_TRUE(hasPass(r.dot, "tonemap"));
}

TEST(RendererGraph, ShadowsEffectAddsShadowPassFirst) {
  const Result r = renderOnce(std::vector<std::string>{"direct", "shadows"}, {});
  EXPECT_EQ(r.executed, (Passes{"shadow", "gbuffer", "lighting", "tonemap"}));
  EXPECT_TRUE(hasPass(r.dot, "shadow"));
  EXPECT_FALSE(passCulled(r.dot, "shadow"));
  EXPECT_NE(r.dot.find("shadow.atlas"), std::string::npos);
}

TEST(RendererGraph, DebugViewCullsLightingAndSkipsTonemap) {
  render::FrameSettings s;
  s.debugView = render::DebugView::Albedo;
  const Result r = renderOnce(std::nullopt, s);  // the level's own effects: direct, shadows, probes, dnrt
  // The debug view reads the shadow atlas (for its shadow mode), so the shadow pass stays; the GI
  // nodes only add to "lighting.hdr", which nothing reads, so they go with the lighting pass.
  // cornell-1 relights its probes: probes.relight writes the probes' uniform block, imported as
  // graph buffer "probes.sh.block" that probes.tiles and probes read, so it goes with them (session
  // 11; before, a side-effect pass that ran for nothing).
  EXPECT_EQ(r.executed, (Passes{"shadow", "gbuffer", "debug-view"}));
  EXPECT_TRUE(passCulled(r.dot, "lighting"));
  EXPECT_TRUE(passCulled(r.dot, "probes.relight"));
  EXPECT_TRUE(passCulled(r.dot, "probes.tiles"));
  EXPECT_TRUE(passCulled(r.dot, "probes"));
  EXPECT_TRUE(passCulled(r.dot, "dnrt"));
  EXPECT_FALSE(passCulled(r.dot, "debug-view"));
  EXPECT_FALSE(hasPass(r.dot, "tonemap")) << "a debug view replaces tonemapping: the pass is never added";
}

TEST(RendererGraph, CullingOffRunsEveryPass) {
  render::FrameSettings s;
  s.debugView = render::DebugView::Albedo;
  s.culling = false;
  const Result debug = renderOnce(std::nullopt, s);  // direct, shadows, probes, dnrt
  EXPECT_EQ(debug.executed,
            (Passes{"shadow", "gbuffer", "lighting", "probes.relight", "probes.tiles", "probes", "dnrt.combine", "dnrt", "debug-view"}));
  EXPECT_FALSE(passCulled(debug.dot, "lighting"));

  s.debugView = render::DebugView::None;
  const Result lit = renderOnce(std::nullopt, s);
  EXPECT_EQ(lit.executed,
            (Passes{"shadow", "gbuffer", "lighting", "probes.relight", "probes.tiles", "probes", "dnrt.combine", "dnrt", "tonemap"}));
  // Nothing culled; the legend at the end shows what a culled (dashed) pass would look like.
  EXPECT_EQ(lit.dot.substr(0, lit.dot.find("subgraph cluster_legend")).find("dashed"), std::string::npos) << "nothing culled";
}

// The dnrt pass tests its boxes against the G-buffer's depth, read-only: exactly one DepthRead
// edge from a gbuffer.depth version into the pass, and DepthRead is the read-only depth layout at
// the depth-test stages. Without that edge (no depth test) the box would light every pixel it
// covers, and the graph would not keep the depth in a layout the depth test may read.
TEST(RendererGraph, DnrtPassTestsTheGBufferDepthReadOnly) {
  const Result r = renderOnce(std::nullopt, {});  // the level's own effects: direct, shadows, probes, dnrt
  const std::string passNode = [&] {
    const auto at = r.dot.find(" [label=\"dnrt\", shape=box");
    if (at == std::string::npos) return std::string();
    const auto start = r.dot.rfind("  p", at);
    return r.dot.substr(start + 2, at - start - 2);
  }();
  ASSERT_FALSE(passNode.empty()) << r.dot;
  std::size_t depthReads = 0, otherDepthReads = 0;
  for (std::size_t at = r.dot.find(" -> " + passNode + " [label=\"DepthRead\""); at != std::string::npos;
       at = r.dot.find(" -> " + passNode + " [label=\"DepthRead\"", at + 1)) {
    const std::size_t line = r.dot.rfind('\n', at) + 1;
    const std::string version = r.dot.substr(line + 2, at - line - 2);  // "  rX_vY -> pN"
    const bool gbufferDepth = r.dot.find("  " + version + " [label=\"gbuffer.depth\\nv") != std::string::npos;
    (gbufferDepth ? depthReads : otherDepthReads) += 1;
  }
  EXPECT_EQ(depthReads, 1u) << r.dot;
  EXPECT_EQ(otherDepthReads, 0u);
  EXPECT_EQ(rg::stateFor(rg::Usage::DepthRead, rg::ResourceKind::Texture, false),
            (rg::ResourceState{rg::Layout::DepthReadOnly, rg::Stage::EarlyFragmentTests | rg::Stage::LateFragmentTests,
                               rg::Access::DepthStencilRead}));
}

TEST(RendererGraph, TransientImagesArePooledAcrossFrames) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session(ctx, game::loadLevelWithEffects(kCornell, std::nullopt));
  gpu::OffscreenPresenter presenter(ctx, kExtent);
  const std::uint32_t slots = session.renderer().frames().framesInFlight();
  auto run = [&](int first, int count) {
    for (int f = first; f < first + count; ++f) {
      session.update(f / 60.0);  // props move: the graph is rebuilt from a new world every frame
      session.render(presenter, {});
    }
  };
  run(0, int(slots));
  const std::size_t afterEverySlot = session.renderer().backend().createdImages();
  // Transients per frame: five G-buffer targets (albedo, normal, emissive, entity, depth), the
  // shadow atlas, the probes' irradiance tiles (probes.tiles → probes, session 11; a size no other
  // transient has) and the prop's DNRT combined volume (dnrt.combine → dnrt, while the G-buffer is
  // still read); none is reused for another within a frame, and each frame slot owns its own pool.
  constexpr std::size_t kTransientsPerFrame = 8;
  EXPECT_EQ(afterEverySlot, kTransientsPerFrame * slots);
  run(int(slots), 10 - int(slots));
  EXPECT_EQ(session.renderer().backend().createdImages(), afterEverySlot) << "10 frames created more images than "
                                                                          << slots << " did";
  session.renderer().frames().waitIdle();
}

// Every GI effect the level names adds its node, in the order the Session sets them (AO, probes,
// DNRT), and none runs or is even built when its effect is absent.
TEST(RendererGraph, GiNodesExistOnlyForNamedEffects) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  {
    game::Session plain(ctx, game::loadLevelWithEffects(kCornell, std::vector<std::string>{"direct", "shadows"}));
    EXPECT_EQ(plain.probes(), nullptr);
    EXPECT_EQ(plain.dnrt(), nullptr);
    EXPECT_EQ(plain.ao(gi::ao::Kind::Ssao), nullptr);
  }
  const Result all = renderOnce(std::vector<std::string>{"direct", "shadows", "ssao", "probes", "dnrt"}, {});
  EXPECT_EQ(all.executed, (Passes{"shadow", "gbuffer", "lighting", "ssao", "probes.relight", "probes.tiles", "probes", "dnrt.combine",
                                   "dnrt", "tonemap"}));
  const Result probesOnly = renderOnce(std::vector<std::string>{"direct", "probes"}, {});
  EXPECT_EQ(probesOnly.executed, (Passes{"gbuffer", "lighting", "probes.relight", "probes.tiles", "probes", "tonemap"}));
  EXPECT_FALSE(hasPass(probesOnly.dot, "dnrt"));
  EXPECT_FALSE(hasPass(probesOnly.dot, "ssao"));
}

// A baked volume (relight off) does not change, so its irradiance tiles are built once when the node
// is made (ProbeNode::buildBakedTiles) and imported each frame: no probes.tiles pass, on the first
// frame or later ones, and the probes pass reads the import. Several frames, so the import's
// declared state (SHADER_READ_ONLY, nothing pending) is checked by the validation layers each time.
TEST(RendererGraph, BakedProbesBuildTheirTilesOnceWithoutAPass) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  scene::Level level = game::loadLevelWithEffects(kCornell, std::vector<std::string>{"direct", "shadows", "probes"});
  level.probes.relight = false;
  game::Session session(ctx, std::move(level));
  gpu::OffscreenPresenter presenter(ctx, kExtent);
  for (int f = 0; f < 4; ++f) {
    session.update(f / 60.0);
    session.render(presenter, {});
    EXPECT_EQ(session.renderer().executedPasses(), (Passes{"shadow", "gbuffer", "lighting", "probes", "tonemap"})) << f;
  }
  const std::string dot = session.renderer().graphDot(session.world(), kExtent, {});
  EXPECT_FALSE(hasPass(dot, "probes.tiles"));
  EXPECT_NE(dot.find("probes.tiles.baked"), std::string::npos) << "the import the probes pass reads";
  session.renderer().frames().waitIdle();
}
