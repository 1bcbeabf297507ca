// The play keys of animated characters: L selects the next animated entity, K cycles its clip
// (after the last clip, the rest pose), and the overlay line names the entity, clip and clip time.
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include "engine/anim/animator.hpp"
#include "engine/core/file.hpp"
#include "engine/scene/level.hpp"
#include "game/play_controls.hpp"

using namespace bounce;
using namespace bounce::game;
namespace fs = std::filesystem;

TEST(AnimationKeys, SelectCycleAndDescribe) {
  const char* env = std::getenv("BOUNCE_SHARED_DIR");
  const fs::path fox = fs::path(env && *env ? env : BOUNCE_SHARED_DIR) / "assets/Fox/glTF-Binary/Fox.glb";
  const fs::path level = fs::path(BOUNCE_TEST_OUT) / "play" / "animation-keys.json";
  writeFileAtomic(level, R"({"bounce_level": 1, "effects": ["direct"], "entities": [
      {"id": "a", "mesh": {"asset": ")" + fox.string() + R"("}},
      {"id": "b", "mesh": {"asset": ")" + fox.string() + R"("}, "animation": {"clip": "Walk"}}]})");
  ecs::Registry r;
  scene::instantiate(scene::loadLevel(level), r);
  anim::attachAnimators(r, fs::path(BOUNCE_TEST_OUT) / "play-cook");
  anim::animationSystem(r, 0.25);
  ASSERT_EQ(animatedEntities(r).size(), 2u);

  PlayState state;
  scene::EffectSet effects;
  EXPECT_EQ(animationText(r, state.character), "a: Survey 0.25 s (L selects, K next clip)");
  EXPECT_EQ(applyKey(GLFW_KEY_L, state, effects), KeyEffect::AnimationChanged);
  EXPECT_EQ(animationText(r, state.character), "b: Walk 0.25 s (L selects, K next clip)");
  EXPECT_EQ(applyKey(GLFW_KEY_K, state, effects), KeyEffect::AnimationChanged);
  cycleSelectedClip(r, state.character);
  anim::animationSystem(r, 0.25);
  EXPECT_EQ(animationText(r, state.character), "b: Run 0.25 s (L selects, K next clip)");
  cycleSelectedClip(r, state.character);
  EXPECT_EQ(animationText(r, state.character).substr(0, 12), "b: rest pose");
  applyKey(GLFW_KEY_L, state, effects);  // wraps to the first
  EXPECT_EQ(animationText(r, state.character).substr(0, 9), "a: Survey");
}
