// SL in a session (lavapipe on CPU-only machines): on the characters level with `sl` named, the
// runtime is built (sphere sets through the cache), prints its one "no pass" note, and the frame's
// executed passes are exactly those of the same level without `sl` — nothing is drawn that the
// note does not announce. Without `sl` named, no SL runtime and no note.
#include <gtest/gtest.h>

#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "game/session.hpp"

using namespace bounce;

namespace {

const std::filesystem::path kCharacters = std::filesystem::path(BOUNCE_SOURCE_DIR) / "content/levels/characters.json";
constexpr VkExtent2D kExtent{64, 64};

std::vector<std::string> passesOfOneFrame(game::Session& session) {
  gpu::OffscreenPresenter presenter(gpu::testkit::sharedContext(), kExtent);
  session.update(0.25);
  session.render(presenter, {});
  auto passes = session.renderer().executedPasses();
  session.renderer().frames().waitIdle();
  return passes;
}

TEST(SlSession, BuiltWithItsNoteButNotShownAsRunningAndAddsNoPass) {
  // The runtime prints its note itself (gi::printNoteOnce, once per process: this is the first
  // session here); Session::notes() holds only the table's notes (effects that do not run).
  testing::internal::CaptureStderr();
  game::Session with(gpu::testkit::sharedContext(),
                     game::loadLevelWithEffects(kCharacters, std::vector<std::string>{"direct", "shadows", "sl"}));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("note: effect sl: 2 entities' sphere sets baked and posed each frame, but its GPU passes are not "
                     "implemented yet: no pass\n"),
            std::string::npos)
      << err;
  EXPECT_TRUE(with.notes().empty());
  // Built (bakes, poses) but drawing nothing: not "running" for the overlay and keys, and the
  // checkbox tooltip says why.
  EXPECT_FALSE(with.runs(scene::Effect::Sl));
  EXPECT_FALSE(with.runningEffects().has(scene::Effect::Sl));
  EXPECT_EQ(with.whyCannotRun(scene::Effect::Sl), "sl: its GPU passes are not implemented yet (no pass)");
  ASSERT_NE(with.technique("sl"), nullptr);
  const auto withPasses = passesOfOneFrame(with);

  game::Session without(gpu::testkit::sharedContext(),
                        game::loadLevelWithEffects(kCharacters, std::vector<std::string>{"direct", "shadows"}));
  EXPECT_TRUE(without.notes().empty());
  EXPECT_FALSE(without.runs(scene::Effect::Sl));
  EXPECT_EQ(withPasses, passesOfOneFrame(without));
}

}  // namespace
