// The DNRT node on the GPU (lavapipe on CPU-only machines): cornell-1 with its prop's field, lit by
// a constant environment, rendered with and without the node. Under uniform light the object only
// removes light (L_DNRT = ρ_r L (R/d)² (ρ_s − 1) ≤ 0 for ρ_s ≤ 1), so the lack-of-light effect
// must darken the surfaces near the prop and brighten nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/irradiance_source.hpp"
#include "engine/gi/dnrt/node.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "game/session.hpp"

namespace bounce::gi::dnrt {
namespace {

namespace fs = std::filesystem;

// fp16 rounding of the HDR target (11-bit mantissa: 5e-4 relative) on values ≲ 1.
constexpr float kHalfTol = 2e-3f;
// The ambient radiance of the constant environment (W/(m²·sr)).
constexpr float kAmbient = 2.0f;

struct Frame {
  std::vector<float> rgb;
  std::vector<std::string> passes;
};

Frame renderOnce(game::Session& session, gpu::Context& ctx) {
  gpu::OffscreenPresenter presenter(ctx, {160, 120});
  render::FrameSettings settings;
  settings.keepHdr = true;
  session.render(presenter, settings);
  return {session.renderer().readHdr(), session.renderer().executedPasses()};
}

TEST(DnrtGpu, PropDarkensItsSurroundingsAndBrightensNothing) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session(ctx, game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json",
                                                        std::vector<std::string>{"direct", "dnrt"}));
  session.update(0.0);
  ecs::Registry& reg = session.registry();
  ref::ReferenceAssets assets;
  assets.load(reg, fs::path(BOUNCE_TEST_OUT) / "dnrt" / "cooked");
  ecs::Entity prop;
  reg.view<scene::Dnrt>().each([&](ecs::Entity e, scene::Dnrt&) { prop = e; });
  ASSERT_FALSE(prop.isNull());
  FieldSettings fs = settingsFrom(reg.get<scene::Dnrt>(prop));
  fs.grid = 16;  // CI-sized bake
  fs.samplesPerAxis = 8;
  const BakeResult baked = bake(objectScene(reg, prop, assets), fs);
  const FieldTextures textures(ctx, baked.field, "prop");
  Node node(ctx, session.renderer().pipelines(), gpu::FrameRing::kDefaultFramesInFlight);
  const ConstantEnvironment env{glm::vec3(kAmbient)};
  bool fullScreen = false;
  session.renderer().setNode("dnrt", [&](rg::RenderGraph& graph, render::PassContext& pc) {
    const glm::mat4 world = reg.get<scene::WorldTransform>(prop).matrix;
    const glm::vec3 o = glm::vec3(world * glm::vec4(baked.field.centre, 1.0f));
    NodeObject obj{&textures, packObject(baked.field, world, env.radianceSH(o)), "prop"};
    node.addTo(graph, pc, {obj}, NodeSettings{fullScreen});
  });
  const Frame with = renderOnce(session, ctx);
  fullScreen = true;
  const Frame withFull = renderOnce(session, ctx);
  session.renderer().setNode("dnrt", {});
  const Frame without = renderOnce(session, ctx);

  EXPECT_NE(std::find(with.passes.begin(), with.passes.end(), "dnrt"), with.passes.end());
  EXPECT_EQ(std::find(without.passes.begin(), without.passes.end(), "dnrt"), without.passes.end());
  ASSERT_EQ(with.rgb.size(), without.rgb.size());
  std::size_t darkened = 0, brightened = 0;
  double removed = 0.0, modeDiff = 0.0;
  for (std::size_t i = 0; i < with.rgb.size(); ++i) {
    const float d = with.rgb[i] - without.rgb[i];
    const float tol = kHalfTol * std::max(1.0f, std::abs(without.rgb[i]));
    if (d < -tol) ++darkened, removed -= d;
    if (d > tol) ++brightened;
    modeDiff = std::max(modeDiff, double(std::abs(withFull.rgb[i] - with.rgb[i])));
  }
  std::printf("dnrt: %zu of %zu channel values darkened (total %.3f), %zu brightened; box vs full screen max diff %.2g\n",
              darkened, with.rgb.size(), removed, brightened, modeDiff);
  EXPECT_GT(darkened, 300u);  // the prop's neighbourhood covers hundreds of pixels at 160×120
  EXPECT_EQ(brightened, 0u);
  // The box covers every pixel with a non-zero term: both modes give the same image.
  EXPECT_LT(modeDiff, kHalfTol);
}

}  // namespace
}  // namespace bounce::gi::dnrt
