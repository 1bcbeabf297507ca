// SL in a session (lavapipe on CPU-only machines): on the characters level with `sl` named, the
// runtime is built (sphere sets through the cache) and runs: the frame's executed passes are those
// of the same level without `sl` plus "sl.intensity" (pass 1) and "sl" (pass 2), once each, pass 1
// before pass 2 and pass 2 after the lighting it adds to; the image only gains light (pass 2 adds
// ρ/π·E ≥ 0) and gains some. Without `sl` named, no SL runtime.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "game/session.hpp"

using namespace bounce;

namespace {

const std::filesystem::path kCharacters = std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/levels/characters.json";
constexpr VkExtent2D kExtent{96, 96};

struct Frame {
  std::vector<std::string> passes;
  std::vector<float> rgb;
};

Frame oneFrame(game::Session& session) {
  gpu::OffscreenPresenter presenter(gpu::testkit::sharedContext(), kExtent);
  session.update(0.25);
  presenter.requestCapture();
  session.render(presenter, {});
  Frame f{session.renderer().executedPasses(), {}};
  session.renderer().frames().waitIdle();
  f.rgb = presenter.capture().rgbFloat();
  return f;
}

}  // namespace

TEST(SlSession, RunsItsTwoPassesAndOnlyAddsLight) {
  game::Session with(gpu::testkit::sharedContext(),
                     game::loadLevelWithEffects(kCharacters, std::vector<std::string>{"direct", "shadows", "sl"}));
  EXPECT_TRUE(with.notes().empty());
  EXPECT_TRUE(with.runs(scene::Effect::Sl));
  EXPECT_TRUE(with.runningEffects().has(scene::Effect::Sl));
  EXPECT_EQ(with.whyCannotRun(scene::Effect::Sl), "");
  ASSERT_NE(with.technique("sl"), nullptr);
  const Frame a = oneFrame(with);

  game::Session without(gpu::testkit::sharedContext(),
                        game::loadLevelWithEffects(kCharacters, std::vector<std::string>{"direct", "shadows"}));
  EXPECT_FALSE(without.runs(scene::Effect::Sl));
  const Frame b = oneFrame(without);

  ASSERT_EQ(std::count(a.passes.begin(), a.passes.end(), "sl.intensity"), 1);
  ASSERT_EQ(std::count(a.passes.begin(), a.passes.end(), "sl"), 1);
  const auto at = [&](const std::string& name) { return std::find(a.passes.begin(), a.passes.end(), name) - a.passes.begin(); };
  EXPECT_LT(at("sl.intensity"), at("sl"));
  EXPECT_LT(at("lighting"), at("sl"));
  std::vector<std::string> rest;
  for (const std::string& p : a.passes)
    if (p != "sl" && p != "sl.intensity") rest.push_back(p);
  EXPECT_EQ(rest, b.passes);

  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  ASSERT_EQ(a.rgb.size(), std::size_t(kExtent.width) * kExtent.height * 3);
  int darker = 0, brighter = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) {
    darker += a.rgb[i] < b.rgb[i] - 1.5f / 255.0f;  // 8-bit output: one step of rounding either way
    brighter += a.rgb[i] > b.rgb[i] + 1.5f / 255.0f;
  }
  EXPECT_EQ(darker, 0);
  EXPECT_GT(brighter, 0);
  std::printf("sl on the characters level at %ux%u: %d of %zu channel values brighter, none darker\n", kExtent.width,
              kExtent.height, brighter, a.rgb.size());
}
