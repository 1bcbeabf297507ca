// bounce play's key map, key handling and fly camera (CPU only: no window, no GPU).
#include <gtest/gtest.h>

#include <GLFW/glfw3.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/scene/systems.hpp"
#include "game/play_controls.hpp"

using namespace bounce;
using namespace bounce::game;
using render::DebugView;
using scene::Effect;

namespace {
// Float round-off of a few quaternion products and trigonometric round trips (unit vectors).
constexpr float kDirectionTolerance = 1e-5f;
// Positions after one step of at most 2 m: a few ulps of the translation sums.
constexpr float kPositionTolerance = 1e-5f;
constexpr float kDegToRad = 0.017453292519943295f;

scene::Transform cameraAt(glm::vec3 eulerDeg) {
  scene::Transform t;
  t.translation = {0.0f, 0.38f, 0.27f};
  t.rotation = glm::quat(eulerDeg * kDegToRad);
  return t;
}
}  // namespace

TEST(PlayKeys, EveryKeyBoundOnceAndListed) {
  std::set<int> keys;
  const std::string text = keyMapText();
  const std::string summary = keyMapSummary("");
  for (const auto& b : keyBindings()) {
    EXPECT_TRUE(keys.insert(b.key).second) << "key bound twice: " << b.keyName;
    EXPECT_NE(text.find("\n  " + std::string(b.keyName) + " "), std::string::npos) << b.keyName;
  }
  for (int i = 0; i < scene::kEffectCount; ++i) {
    std::string needle = std::to_string(i + 1);  // appended piecewise, see below
    needle += '=';
    needle += scene::effectName(Effect(i));
    EXPECT_NE(summary.find(needle), std::string::npos) << needle;
  }
  for (int v = 0; v <= int(DebugView::EntityId); ++v) {
    std::string needle = "F";  // appended piecewise: GCC 12 misreports "literal" + string (-Wrestrict)
    needle += std::to_string(v + 1);
    needle += '=';
    needle += render::debugViewName(DebugView(v));
    EXPECT_NE(summary.find(needle), std::string::npos) << needle;
  }
  // The summary continues a help line: every line fits a terminal.
  std::istringstream lines(keyMapSummary(std::string(14, ' ')));
  for (std::string line; std::getline(lines, line);) EXPECT_LE(line.size(), 100u) << line;
}

TEST(PlayKeys, DigitsToggleEffectsInEnumOrder) {
  for (int i = 0; i < scene::kEffectCount; ++i) {
    PlayState state;
    scene::EffectSet effects;
    effects.add(Effect::Direct);
    const scene::EffectSet before = effects;
    EXPECT_EQ(applyKey(GLFW_KEY_1 + i, state, effects), KeyEffect::EffectsChanged);
    for (int j = 0; j < scene::kEffectCount; ++j)
      EXPECT_EQ(effects.has(Effect(j)), (i == j) ? !before.has(Effect(j)) : before.has(Effect(j))) << i << " " << j;
    applyKey(GLFW_KEY_1 + i, state, effects);
    EXPECT_EQ(effects, before) << "toggling twice restores the set";
  }
}

TEST(PlayKeys, FunctionKeysPickDebugViewsAndZeroCycles) {
  PlayState state;
  scene::EffectSet effects;
  for (int v = 0; v <= int(DebugView::EntityId); ++v) {
    EXPECT_EQ(applyKey(GLFW_KEY_F1 + v, state, effects), KeyEffect::Handled);
    EXPECT_EQ(state.settings.debugView, DebugView(v));
  }
  applyKey(GLFW_KEY_0, state, effects);  // entity-id wraps to lit
  EXPECT_EQ(state.settings.debugView, DebugView::None);
  applyKey(GLFW_KEY_0, state, effects);
  EXPECT_EQ(state.settings.debugView, DebugView::Albedo);
}

TEST(PlayKeys, ExposureQuarterStopsClamped) {
  PlayState state;
  scene::EffectSet effects;
  for (int i = 0; i < 4; ++i) applyKey(GLFW_KEY_EQUAL, state, effects);
  EXPECT_FLOAT_EQ(state.settings.exposure, 2.0f);  // four quarter stops: one stop
  for (int i = 0; i < 8; ++i) applyKey(GLFW_KEY_KP_SUBTRACT, state, effects);
  EXPECT_FLOAT_EQ(state.settings.exposure, 0.5f);
  for (int i = 0; i < 200; ++i) applyKey(GLFW_KEY_MINUS, state, effects);
  EXPECT_FLOAT_EQ(state.settings.exposure, std::exp2(kExposureMinStops));
}

TEST(PlayKeys, TogglesAndUnboundKeys) {
  PlayState state;
  scene::EffectSet effects;
  effects.add(Effect::Shadows);
  EXPECT_EQ(applyKey(GLFW_KEY_V, state, effects), KeyEffect::VsyncChanged);
  EXPECT_FALSE(state.vsync);
  EXPECT_EQ(applyKey(GLFW_KEY_P, state, effects), KeyEffect::Handled);
  EXPECT_TRUE(state.paused);
  applyKey(GLFW_KEY_O, state, effects);
  EXPECT_FALSE(state.overlay);
  applyKey(GLFW_KEY_C, state, effects);
  EXPECT_FALSE(state.settings.culling);
  EXPECT_EQ(applyKey(GLFW_KEY_R, state, effects), KeyEffect::ResetCamera);
  EXPECT_FALSE(state.quit);
  applyKey(GLFW_KEY_ESCAPE, state, effects);
  EXPECT_TRUE(state.quit);

  PlayState fresh;
  const PlayState copy = fresh;
  EXPECT_EQ(applyKey(GLFW_KEY_Z, fresh, effects), KeyEffect::None);
  EXPECT_EQ(fresh.settings.exposure, copy.settings.exposure);
  EXPECT_EQ(fresh.settings.debugView, copy.settings.debugView);
  EXPECT_EQ(effects.names(), std::vector<std::string>{"shadows"});
}

// Per-tag VLM overrides (thesis Fig. 5.5): T walks none → each tag → none; ]/[ scale the selected
// tag's intensity by exactly kVlmIntensityStep; H turns its hue by 30° modulo 360. Without a
// selection (or without VLMs) the keys change nothing.
TEST(PlayKeys, VlmKeysSelectATagAndChangeItsOverride) {
  PlayState state;
  scene::EffectSet effects;
  EXPECT_EQ(applyKey(GLFW_KEY_T, state, effects), KeyEffect::Handled);
  EXPECT_EQ(state.vlm.selected, -1) << "no VLM in the level: nothing to select";
  EXPECT_EQ(vlmControlText(state.vlm), "");

  state.vlm.tags = {1, 3};
  state.vlm.overrides[3] = {2.0f, glm::vec3(1.0f), 0.0f};  // as the level's "vlm.overrides" gave it
  EXPECT_EQ(applyKey(GLFW_KEY_RIGHT_BRACKET, state, effects), KeyEffect::Handled);
  EXPECT_TRUE(state.vlm.overrides.count(1) == 0) << "nothing selected: no override made";
  EXPECT_EQ(vlmControlText(state.vlm), "VLM tags [1 3]: T selects one, ]/[ intensity, H hue");

  applyKey(GLFW_KEY_T, state, effects);
  EXPECT_EQ(state.vlm.selected, 0);
  EXPECT_EQ(applyKey(GLFW_KEY_RIGHT_BRACKET, state, effects), KeyEffect::VlmChanged);
  EXPECT_EQ(applyKey(GLFW_KEY_RIGHT_BRACKET, state, effects), KeyEffect::VlmChanged);
  EXPECT_FLOAT_EQ(state.vlm.overrides.at(1).intensity, kVlmIntensityStep * kVlmIntensityStep);  // = 2
  applyKey(GLFW_KEY_LEFT_BRACKET, state, effects);
  EXPECT_FLOAT_EQ(state.vlm.overrides.at(1).intensity, kVlmIntensityStep);
  for (int i = 0; i < 13; ++i) EXPECT_EQ(applyKey(GLFW_KEY_H, state, effects), KeyEffect::VlmChanged);
  EXPECT_FLOAT_EQ(state.vlm.overrides.at(1).hueDeg, 30.0f) << "13 × 30° = 390° = 30°";
  EXPECT_EQ(vlmControlText(state.vlm), "VLM tag 1 of [1 3]: intensity 1.41, hue 30 deg");

  applyKey(GLFW_KEY_T, state, effects);  // tag 3 keeps the level's override and builds on it
  applyKey(GLFW_KEY_LEFT_BRACKET, state, effects);
  EXPECT_FLOAT_EQ(state.vlm.overrides.at(3).intensity, 2.0f / kVlmIntensityStep);
  for (int i = 0; i < 40; ++i) applyKey(GLFW_KEY_RIGHT_BRACKET, state, effects);
  EXPECT_FLOAT_EQ(state.vlm.overrides.at(3).intensity, kVlmIntensityMax) << "clamped";
  applyKey(GLFW_KEY_T, state, effects);
  EXPECT_EQ(state.vlm.selected, -1) << "past the last tag: none again";
}

TEST(FlyCameraTest, StartsWhereTheLevelPointsIt) {
  // cornell-1's camera: pitched 18° down, no yaw.
  const scene::Transform start = cameraAt({-18.0f, 0.0f, 0.0f});
  FlyCamera fly(start);
  EXPECT_NEAR(fly.pitch(), -18.0f * kDegToRad, kDirectionTolerance);
  EXPECT_NEAR(fly.yaw(), 0.0f, kDirectionTolerance);
  const scene::Transform t = fly.step(start, {}, 1.0f / 60.0f);
  EXPECT_EQ(t.translation, start.translation);
  const glm::vec3 a = FlyCamera::forward(start.rotation), b = FlyCamera::forward(t.rotation);
  EXPECT_NEAR(glm::length(a - b), 0.0f, kDirectionTolerance);

  // Any yaw/pitch (no roll) survives the round trip rotation → yaw/pitch → rotation.
  for (float yawDeg : {-170.0f, -45.0f, 30.0f, 120.0f})
    for (float pitchDeg : {-60.0f, 0.0f, 45.0f}) {
      const glm::quat q = FlyCamera::rotationFromYawPitch(yawDeg * kDegToRad, pitchDeg * kDegToRad);
      scene::Transform s;
      s.rotation = q;
      FlyCamera f(s);
      EXPECT_NEAR(f.yaw(), yawDeg * kDegToRad, kDirectionTolerance) << yawDeg << " " << pitchDeg;
      EXPECT_NEAR(f.pitch(), pitchDeg * kDegToRad, kDirectionTolerance) << yawDeg << " " << pitchDeg;
    }
}

TEST(FlyCameraTest, MovesAtItsSpeedAlongTheView) {
  const scene::Transform start = cameraAt({-18.0f, 30.0f, 0.0f});
  FlyCamera fly(start);
  const glm::vec3 forward = FlyCamera::forward(FlyCamera::rotationFromYawPitch(fly.yaw(), fly.pitch()));
  FlyInput w;
  w.move.z = 1.0f;
  scene::Transform t = fly.step(start, w, 1.0f);
  EXPECT_NEAR(glm::length(t.translation - (start.translation + forward * FlyCamera::kSpeed)), 0.0f,
              kPositionTolerance);
  w.fast = true;
  t = fly.step(start, w, 1.0f);
  EXPECT_NEAR(glm::length(t.translation - start.translation), FlyCamera::kSpeed * FlyCamera::kFastFactor,
              kPositionTolerance);
  // Diagonals are no faster; E goes straight up in the world whatever the pitch.
  FlyInput diag;
  diag.move = {1.0f, 0.0f, 1.0f};
  t = fly.step(start, diag, 1.0f);
  EXPECT_NEAR(glm::length(t.translation - start.translation), FlyCamera::kSpeed, kPositionTolerance);
  FlyInput up;
  up.move.y = 1.0f;
  t = fly.step(start, up, 2.0f);
  EXPECT_NEAR(glm::length(t.translation - (start.translation + glm::vec3(0, 2 * FlyCamera::kSpeed, 0))), 0.0f,
              kPositionTolerance);
  EXPECT_EQ(t.scale, start.scale);
}

TEST(FlyCameraTest, MouseTurnsAndPitchStopsShortOfVertical) {
  const scene::Transform start = cameraAt({0.0f, 0.0f, 0.0f});
  FlyCamera fly(start);
  FlyInput look;
  look.look = {100.0f, 0.0f};  // mouse right
  scene::Transform t = fly.step(start, look, 0.016f);
  const glm::vec3 f = FlyCamera::forward(t.rotation);
  EXPECT_GT(f.x, 0.0f) << "moving the mouse right turns right (towards +X from -Z)";
  EXPECT_NEAR(f.x, std::sin(100.0f * FlyCamera::kRadiansPerPixel), kDirectionTolerance);
  look.look = {0.0f, -1.0e6f};  // far up
  t = fly.step(t, look, 0.016f);
  EXPECT_FLOAT_EQ(fly.pitch(), FlyCamera::kMaxPitch);
  EXPECT_NEAR(FlyCamera::forward(t.rotation).y, std::sin(FlyCamera::kMaxPitch), kDirectionTolerance);
  // No roll: the camera's right vector stays horizontal.
  EXPECT_NEAR((t.rotation * glm::vec3(1, 0, 0)).y, 0.0f, kDirectionTolerance);
}

TEST(PlayKeyScript, ParsesNamesAndFramesInFrameOrder) {
  const auto keys = parseKeyScript("F3@30,2@0,+@30,Esc@99,P@0");
  ASSERT_EQ(keys.size(), 5u);
  const std::vector<std::pair<int, int>> expected = {
      {0, GLFW_KEY_2}, {0, GLFW_KEY_P}, {30, GLFW_KEY_F3}, {30, GLFW_KEY_EQUAL}, {99, GLFW_KEY_ESCAPE}};
  for (std::size_t i = 0; i < keys.size(); ++i) {
    EXPECT_EQ(keys[i].frame, expected[i].first) << i;
    EXPECT_EQ(keys[i].key, expected[i].second) << i;
  }
  EXPECT_TRUE(parseKeyScript("").empty());
}

TEST(PlayKeyScript, BadItemsAreOneLineInputErrors) {
  for (const char* bad : {"2", "@3", "2@", "Q@1", "2@-1", "2@x", "2@1,,3@2", "2@1234567890"}) {
    try {
      parseKeyScript(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("bounce play: --keys: ", 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(CameraDriverTest, TakesOverOnlyTheCameraAndOnlyOnInput) {
  ecs::Registry reg;
  auto withOrbit = [&](ecs::Entity e, const scene::Transform& t) {
    reg.emplace<scene::Transform>(e, t);
    scene::Motion m;
    m.orbit = scene::Orbit{t.translation, glm::vec3(0, 1, 0), 0.1f, 4.0f, 0.0f};
    m.base = t;
    reg.emplace<scene::Motion>(e, m);
  };
  const ecs::Entity cam = reg.create(), prop = reg.create();
  const scene::Transform start = cameraAt({-18.0f, 0.0f, 0.0f});
  withOrbit(cam, start);
  reg.emplace<scene::Camera>(cam);
  scene::Transform propStart;
  propStart.translation = {0.0f, 0.1f, 0.0f};
  withOrbit(prop, propStart);

  CameraDriver driver(reg, cam);
  EXPECT_FALSE(driver.drive({}, 0.1f)) << "no input: the script keeps the camera";
  EXPECT_NE(reg.tryGet<scene::Motion>(cam), nullptr);
  scene::motionSystem(reg, 1.0);
  EXPECT_NE(reg.get<scene::Transform>(cam).translation, start.translation);

  FlyInput forward;
  forward.move.z = 1.0f;
  EXPECT_TRUE(driver.drive(forward, 0.5f));
  EXPECT_TRUE(driver.flying());
  EXPECT_EQ(reg.tryGet<scene::Motion>(cam), nullptr) << "the camera's script is dropped";
  EXPECT_NE(reg.tryGet<scene::Motion>(prop), nullptr) << "the props' scripts are not";
  const scene::Transform flown = reg.get<scene::Transform>(cam);
  const glm::vec3 propAt1 = reg.get<scene::Transform>(prop).translation;
  scene::motionSystem(reg, 2.0);
  EXPECT_EQ(reg.get<scene::Transform>(cam), flown) << "scripts no longer move the camera";
  EXPECT_NE(reg.get<scene::Transform>(prop).translation, propAt1) << "props keep moving";

  driver.reset();
  EXPECT_FALSE(driver.flying());
  EXPECT_EQ(reg.get<scene::Transform>(cam), start);
  ASSERT_NE(reg.tryGet<scene::Motion>(cam), nullptr);
  EXPECT_EQ(reg.tryGet<scene::Motion>(cam)->base, start);
}

TEST(CameraDriverTest, NoCameraDoesNothing) {
  ecs::Registry reg;
  CameraDriver driver(reg, ecs::Entity::null());
  FlyInput forward;
  forward.move.z = 1.0f;
  EXPECT_FALSE(driver.drive(forward, 1.0f));
  driver.reset();
  EXPECT_FALSE(driver.flying());
}

// README "Playing" quotes the key map: the block must be keyMapSummary("") verbatim (issue 16:
// the README's list had lost the VLM keys).
TEST(PlayKeys, ReadmeQuotesTheKeyMap) {
  std::ifstream in(std::string(BOUNCE_SOURCE_DIR) + "/README.md");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("```\n" + keyMapSummary("") + "\n```"), std::string::npos) << keyMapSummary("");
}

TEST(PlayKeys, F12TakesAScreenshot) {
  PlayState state;
  scene::EffectSet effects;
  EXPECT_EQ(applyKey(GLFW_KEY_F12, state, effects), KeyEffect::Screenshot);
  EXPECT_EQ(parseKeyScript("F12@3").at(0).key, GLFW_KEY_F12);
}

TEST(PlayKeys, MisspeltKeySuggestsTheNearest) {
  try {
    parseKeyScript("esc@3");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'esc@3': unknown key, did you mean \"Esc\"?"), std::string::npos) << e.what();
  }
}

TEST(PlayKeys, MisspeltEffectSuggestsTheNearest) {
  scene::Level level;
  level.source = "L.json";
  try {
    scene::overrideEffects(level, "direct,shadow");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown effect \"shadow\", did you mean \"shadows\"?"), std::string::npos) << e.what();
  }
}

// Issue 16: DNRT's mode as a run-time setting. M switches every object to the paper's full-screen
// pass, then (issue 15) to the clustered draw (gi::dnrt::NodeSettings::mode), then back to each
// object's own; the overlay's combo does the same.
TEST(PlayKeys, MSwitchesTheDnrtMode) {
  PlayState state;
  scene::EffectSet effects;
  EXPECT_EQ(state.dnrtMode, std::nullopt) << "starts in each object's own mode";
  EXPECT_EQ(applyKey(GLFW_KEY_M, state, effects), KeyEffect::DnrtModeChanged);
  EXPECT_EQ(state.dnrtMode, scene::DnrtMode::FullScreen);
  EXPECT_EQ(applyKey(GLFW_KEY_M, state, effects), KeyEffect::DnrtModeChanged);
  EXPECT_EQ(state.dnrtMode, scene::DnrtMode::Clustered);
  EXPECT_EQ(applyKey(GLFW_KEY_M, state, effects), KeyEffect::DnrtModeChanged);
  EXPECT_EQ(state.dnrtMode, std::nullopt);
  EXPECT_EQ(parseKeyScript("M@2").at(0).key, GLFW_KEY_M);
}

// Issue 16: the overlay's VLM controls edit the same per-tag overrides as the keys, within the
// keys' bounds: intensity clamped to [1/256, 256], hue wrapped into [0, 360), colour into [0, 1],
// non-finite values ignored; the edited tag becomes the selected one; an unknown tag is refused.
TEST(PlayKeys, OverlayVlmEditsAreBoundedLikeTheKeys) {
  VlmControl vlm;
  vlm.tags = {2, 5};
  EXPECT_FALSE(setVlmOverride(vlm, 4, {}));
  EXPECT_TRUE(vlm.overrides.empty());
  EXPECT_EQ(vlm.selected, -1);

  ASSERT_TRUE(setVlmOverride(vlm, 5, {1000.0f, glm::vec3(1.5f, -0.25f, 0.5f), -30.0f}));
  EXPECT_EQ(vlm.selected, 1);
  const scene::VlmOverride& o = vlm.overrides.at(5);
  EXPECT_FLOAT_EQ(o.intensity, kVlmIntensityMax);
  EXPECT_FLOAT_EQ(o.hueDeg, 330.0f);
  EXPECT_EQ(o.color, glm::vec3(1.0f, 0.0f, 0.5f));

  const float nan = std::numeric_limits<float>::quiet_NaN();
  ASSERT_TRUE(setVlmOverride(vlm, 5, {nan, glm::vec3(nan, 0.25f, nan), 725.0f}));
  EXPECT_FLOAT_EQ(vlm.overrides.at(5).intensity, kVlmIntensityMax) << "NaN keeps the old value";
  EXPECT_EQ(vlm.overrides.at(5).color, glm::vec3(1.0f, 0.25f, 0.5f));
  EXPECT_FLOAT_EQ(vlm.overrides.at(5).hueDeg, 5.0f);
  ASSERT_TRUE(setVlmOverride(vlm, 2, {1e-9f, glm::vec3(1.0f), 0.0f}));
  EXPECT_FLOAT_EQ(vlm.overrides.at(2).intensity, kVlmIntensityMin);
  EXPECT_EQ(vlmControlText(vlm), "VLM tag 2 of [2 5]: intensity 0.00, hue 0 deg");
}
