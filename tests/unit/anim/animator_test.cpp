// The level key "animation", clip times per mode, clip selection by name and index, the one-line
// error for an unknown clip, and the animation system writing poses on simulation time.
#include <gtest/gtest.h>

#include "engine/anim/animator.hpp"
#include "engine/anim/sampling.hpp"
#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/scene/level.hpp"
#include "engine/scene/systems.hpp"

namespace bounce::anim {
namespace {

namespace fs = std::filesystem;

fs::path assets() {
  const char* env = std::getenv("BOUNCE_SHARED_DIR");
  return fs::path(env && *env ? env : BOUNCE_SHARED_DIR) / "assets";
}
fs::path cookCache() { return fs::path(BOUNCE_TEST_OUT) / "anim-cook"; }

fs::path writeLevel(const std::string& name, const std::string& entityKeys) {
  const fs::path p = fs::path(BOUNCE_TEST_OUT) / "anim" / name;
  writeFileAtomic(p, R"({"bounce_level": 1, "effects": ["direct"], "entities": [
    {"id": "fox", "mesh": {"asset": ")" + (assets() / "Fox/glTF/Fox.gltf").string() + R"("})" + entityKeys + "}]}");
  return p;
}

std::string inputErrorOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Animator, ClipTimePerMode) {
  using scene::PlayMode;
  EXPECT_FLOAT_EQ(clipTime(PlayMode::Loop, 2.0f, 5.5), 1.5f);
  EXPECT_FLOAT_EQ(clipTime(PlayMode::Loop, 2.0f, -0.5), 1.5f);
  EXPECT_FLOAT_EQ(clipTime(PlayMode::PingPong, 2.0f, 2.5), 1.5f);
  EXPECT_FLOAT_EQ(clipTime(PlayMode::PingPong, 2.0f, 4.5), 0.5f);
  EXPECT_FLOAT_EQ(clipTime(PlayMode::Once, 2.0f, 7.0), 2.0f);
  EXPECT_FLOAT_EQ(clipTime(PlayMode::Once, 2.0f, -1.0), 0.0f);
  EXPECT_FLOAT_EQ(clipTime(PlayMode::Loop, 0.0f, 3.0), 0.0f);
}

TEST(Animator, LevelKeyParsesEveryField) {
  const auto level = scene::loadLevel(
      writeLevel("keys.json", R"(, "animation": {"clip": "Run", "speed": 0.5, "mode": "ping-pong", "phase_s": 0.25})"));
  ASSERT_TRUE(level.entities[0].animation);
  const auto& a = *level.entities[0].animation;
  EXPECT_TRUE(a.enabled);
  EXPECT_EQ(std::get<std::string>(*a.clip), "Run");
  EXPECT_EQ(a.speed, 0.5f);
  EXPECT_EQ(a.mode, scene::PlayMode::PingPong);
  EXPECT_EQ(a.phaseS, 0.25f);
  EXPECT_EQ(a.pointer, "/entities/0/animation");
  const auto off = scene::loadLevel(writeLevel("off.json", R"(, "animation": false)"));
  EXPECT_FALSE(off.entities[0].animation->enabled);
}

TEST(Animator, BadLevelKeysAreOneLineErrors) {
  const fs::path p1 = writeLevel("bad-mode.json", R"(, "animation": {"mode": "bounce"})");
  EXPECT_EQ(inputErrorOf([&] { scene::loadLevel(p1); }),
            p1.string() + ": /entities/0/animation/mode: unknown mode \"bounce\" (expected one of: loop, ping-pong, once)");
  const fs::path p2 = writeLevel("true.json", R"(, "animation": true)");
  EXPECT_NE(inputErrorOf([&] { scene::loadLevel(p2); }).find(": /entities/0/animation: "), std::string::npos);
  const fs::path p3 = writeLevel("clip-type.json", R"(, "animation": {"clip": 1.5})");
  EXPECT_NE(inputErrorOf([&] { scene::loadLevel(p3); }).find(": /entities/0/animation/clip: "), std::string::npos);
}

TEST(Animator, UnknownClipNameListsTheClips) {
  const fs::path p = writeLevel("unknown.json", R"(, "animation": {"clip": "Gallop"})");
  ecs::Registry r;
  scene::instantiate(scene::loadLevel(p), r);
  EXPECT_EQ(inputErrorOf([&] { attachAnimators(r, cookCache()); }),
            p.string() + ": /entities/0/animation/clip: no clip named \"Gallop\" in Fox.gltf (expected one of: Survey, Walk, Run)");
  const fs::path q = writeLevel("index.json", R"(, "animation": {"clip": 3})");
  ecs::Registry r2;
  scene::instantiate(scene::loadLevel(q), r2);
  EXPECT_EQ(inputErrorOf([&] { attachAnimators(r2, cookCache()); }),
            q.string() + ": /entities/0/animation/clip: clip 3 does not exist in Fox.gltf (expected an index below 3 "
                         "(clips: Survey, Walk, Run))");
}

TEST(Animator, DefaultIsTheFirstClipAndPosesFollowSimulationTime) {
  ecs::Registry r;
  const auto es = scene::instantiate(scene::loadLevel(writeLevel("default.json", "")), r);
  attachAnimators(r, cookCache());
  Animator& an = r.get<Animator>(es[0]);
  EXPECT_EQ(an.clip, 0);
  EXPECT_EQ(an.clipName(), "Survey");
  animationSystem(r, 0.5);
  const Pose p05 = r.get<Pose>(es[0]);
  EXPECT_FLOAT_EQ(an.clipTime, 0.5f);
  animationSystem(r, 1.0);
  const Pose p10 = r.get<Pose>(es[0]);
  EXPECT_NE(p05.joints[0], p10.joints[0]);  // the fox moves
  animationSystem(r, 0.5);
  EXPECT_EQ(r.get<Pose>(es[0]).joints[0], p05.joints[0]);  // a pure function of time
  cycleClip(an);
  EXPECT_EQ(an.clipName(), "Walk");
  cycleClip(an);
  cycleClip(an);
  EXPECT_EQ(an.clip, -1);  // after the last clip: the rest pose
  EXPECT_EQ(an.clipName(), "rest pose");
}

TEST(Animator, ClipByIndexSpeedAndPhase) {
  ecs::Registry r;
  const auto es = scene::instantiate(
      scene::loadLevel(writeLevel("index-ok.json", R"(, "animation": {"clip": 2, "speed": 2, "phase_s": 0.1, "mode": "once"})")), r);
  attachAnimators(r, cookCache());
  Animator& an = r.get<Animator>(es[0]);
  EXPECT_EQ(an.clipName(), "Run");
  animationSystem(r, 0.2);
  EXPECT_FLOAT_EQ(an.clipTime, 0.5f);  // 0.1 + 2 · 0.2
  animationSystem(r, 100.0);
  EXPECT_FLOAT_EQ(an.clipTime, clipDuration(an.asset->animations[2]));  // once: held at the end
}

}  // namespace
}  // namespace bounce::anim
