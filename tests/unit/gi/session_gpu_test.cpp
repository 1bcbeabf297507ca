// Session builds the table's techniques (engine/gi/technique.hpp): only named effects in which an
// entity takes part run; unused ones are noted once and do not count as running (the
// play overlay shows them off); an effect named later (a play key) is built then, nodes kept in
// table order.
#include <gtest/gtest.h>

#include <fstream>

#include "engine/core/error.hpp"
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

TEST(SessionTechniques, ReservedAndUnusedEffectsAreNotedAndDoNotRun) {
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
TEST(SessionTechniques, WhyCannotRunNamesReservedAndUnusedEffectsOnly) {
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
