#pragma once
// `bounce play` controls, free of GLFW and Vulkan so they can be tested on the CPU:
//   - the key map (one table: the window's key handler, the start-up print and `--help` all read it);
//   - PlayState, what the keys change (effects, debug view, exposure, vsync, pause, overlay);
//   - FlyCamera, the WASD + mouse-look camera that moves the active camera's scene::Transform, and
//     orbits a pivot ahead of it with the left mouse button and the wheel (as glTF viewers do).
// Key codes are GLFW's (GLFW_KEY_*), kept as plain ints here.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/ecs/registry.hpp"
#include "engine/render/renderer.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/effects.hpp"
#include "engine/scene/level.hpp"

namespace bounce::game {

enum class PlayAction {
  ToggleEffect,   // arg: scene::Effect
  SetDebugView,   // arg: render::DebugView
  CycleDebugView,
  ExposureUp,
  ExposureDown,
  ToggleVsync,
  TogglePause,
  ToggleOverlay,
  ToggleCulling,
  ResetCamera,
  Quit,
  VlmNextTag,        // select the next VLM tag (none → first → … → last → none)
  VlmIntensityUp,    // the selected tag's override intensity × kVlmIntensityStep
  VlmIntensityDown,  // ÷ kVlmIntensityStep
  VlmNextHue,        // its hue rotated by kVlmHueStepDeg (thesis Fig. 5.5)
  Screenshot,        // F12: the next frame as PNG (display) + PFM (linear HDR), no overlay
  AnimNextCharacter, // select the next animated entity (engine/anim Animator)
  AnimNextClip,      // the selected one plays its next clip (after the last: the rest pose)
  DnrtToggleMode,    // DNRT: each object's own mode -> full-screen for all -> clustered for all -> own
};

struct KeyBinding {
  int key;              // GLFW_KEY_*
  const char* keyName;  // as printed: "1", "F3", "Esc"
  PlayAction action;
  int arg;              // effect or debug view for the actions that take one
  std::string help;
};

// Every discrete key of `bounce play` (movement and mouse look are polled, see FlyCamera).
const std::vector<KeyBinding>& keyBindings();
// The full key map, one binding a line, for the start of `bounce play`.
std::string keyMapText();
// A compact key map: lines of at most ~90 characters, each prefixed by `indent` (the help text).
std::string keyMapSummary(const std::string& indent);

// `--keys` for scripted runs: "KEY@FRAME,KEY@FRAME,…" with KEY a key name of the key map ("2",
// "F5", "+", "P", "Esc") pressed at the start of frame FRAME (0-based). Sorted by frame, stable.
struct ScriptedKey {
  int frame;
  int key;
};
std::vector<ScriptedKey> parseKeyScript(const std::string& list);

// The live per-tag VLM overrides (§3.5, Fig. 5.5): which tag the keys act on and the overrides the
// VLM runtime applies (gi::vlm::Runtime::setOverrides). Starts from the level's "vlm.overrides".
struct VlmControl {
  std::vector<std::uint32_t> tags;  // the level's VLM tags, sorted (gi::vlm::Runtime::tags())
  int selected = -1;                // index into tags, -1 = none selected
  std::map<int, scene::VlmOverride> overrides;
};
inline constexpr float kVlmIntensityStep = 1.4142135f;  // half a stop per key press
inline constexpr float kVlmIntensityMin = 1.0f / 256.0f, kVlmIntensityMax = 256.0f;
inline constexpr float kVlmHueStepDeg = 30.0f;
// Sets tag `tag`'s override as the overlay's controls edit it (the same state the T, ]/[ and H
// keys change): intensity clamped to [kVlmIntensityMin, kVlmIntensityMax], hue wrapped into
// [0, 360) degrees, colour clamped to [0, 1] per channel (non-finite values keep the old one);
// `tag` becomes the selected one. False (nothing changes) when the level has no such tag.
bool setVlmOverride(VlmControl& vlm, int tag, const scene::VlmOverride& value);
// One overlay line: "VLM tag 1 of [1 2 3]: intensity 2.00, hue 30 deg", or the key hint when
// nothing is selected; empty when the level has no VLM.
std::string vlmControlText(const VlmControl& vlm);

// What the keys change. `settings` is passed to Session::render as is.
struct PlayState {
  VlmControl vlm;
  render::FrameSettings settings;
  bool vsync = true;
  bool paused = false;   // motion scripts and animation clips hold their pose (simulation time stops)
  int character = 0;     // the selected animated entity (in registry order) for AnimNextClip
  // DNRT's mode for every object (gi::dnrt::NodeSettings::mode): none = each object's own (its
  // level "mode", default the outer cube's draw), else that mode for all: the paper's full-screen
  // pass (§5.2, for comparison) or the clustered draw (issue 15). Key M cycles own → full-screen →
  // clustered → own; the overlay's "dnrt mode" combo sets it too.
  std::optional<scene::DnrtMode> dnrtMode;
  bool overlay = true;
  bool quit = false;
};

// What the caller must do after a key beyond updating PlayState.
enum class KeyEffect {
  None, Handled, EffectsChanged, VsyncChanged, ResetCamera, VlmChanged, Screenshot, AnimationChanged, DnrtModeChanged
};

// The animated entities of a registry in a stable order, the selected one's clip cycled, and the
// overlay line "fox: Run 0.42 s (L selects, K next clip)"; empty when nothing is animated.
std::vector<ecs::Entity> animatedEntities(ecs::Registry& registry);
void cycleSelectedClip(ecs::Registry& registry, int character);
std::string animationText(ecs::Registry& registry, int character);

// Applies a key press to `state` and `effects`. Unbound keys return None and change nothing.
KeyEffect applyKey(int key, PlayState& state, scene::EffectSet& effects);

// `effects` with `e` switched on if it was off and off if it was on; the others unchanged.
scene::EffectSet toggled(scene::EffectSet effects, scene::Effect e);

// Exposure steps: a quarter stop per key press, clamped to [2^-10, 2^10].
inline constexpr float kExposureStepStops = 0.25f;
inline constexpr float kExposureMinStops = -10.0f;
inline constexpr float kExposureMaxStops = 10.0f;

// One frame of fly-camera input.
struct FlyInput {
  glm::vec3 move{0.0f};   // x: right (D − A), y: world up (E − Q), z: forward (W − S); each −1..1
  glm::vec2 look{0.0f};   // mouse motion in pixels while looking (x right, y down)
  bool fast = false;      // Shift
  glm::vec2 orbit{0.0f};  // mouse motion in pixels while the left button is held: orbit the pivot
  float zoom = 0.0f;      // mouse-wheel steps (positive: towards the pivot)
};

// A yaw/pitch fly camera (no roll, as games do). Looking down the camera's local −Z (glTF):
// yaw turns about world +Y, pitch about the camera's +X, clamped short of straight up/down so
// the view never flips. Moving is along the view direction and its right vector; Q/E move along
// world Y. Speeds are in metres per second (the Cornell box is 0.55 m wide).
class FlyCamera {
 public:
  static constexpr float kSpeed = 0.5f;            // m/s
  static constexpr float kFastFactor = 4.0f;       // with Shift
  static constexpr float kRadiansPerPixel = 0.0025f;
  static constexpr float kMaxPitch = 1.5533430f;   // 89 degrees

  // Starts from a transform (its roll is dropped on the first step()).
  explicit FlyCamera(const scene::Transform& start);
  // Advances by `dt` seconds and returns the new transform (scale kept from `current`).
  scene::Transform step(const scene::Transform& current, const FlyInput& input, float dt);
  // Orbit, as glTF viewers do: the pivot is the point `distance` metres ahead of `current`; a drag
  // of `drag` pixels turns yaw/pitch by kOrbitRadiansPerPixel each (drag right: the model turns
  // right) and the camera moves so that it still looks at the pivot from `distance`; `zoomSteps`
  // scale the distance by kZoomStep each (positive: closer), never below kMinOrbitDistance.
  static constexpr float kOrbitRadiansPerPixel = 0.005f;
  static constexpr float kZoomStep = 0.9f;
  static constexpr float kMinOrbitDistance = 1e-3f;  // metres
  scene::Transform orbit(const scene::Transform& current, glm::vec2 drag, float zoomSteps, float& distance);

  float yaw() const { return yaw_; }
  float pitch() const { return pitch_; }

  // The unit view direction (local −Z) of a rotation, and the yaw/pitch that reproduce it.
  static glm::vec3 forward(const glm::quat& rotation);
  static glm::quat rotationFromYawPitch(float yaw, float pitch);

 private:
  float yaw_ = 0.0f, pitch_ = 0.0f;
};

// The active camera under user control. The first frame with any fly input takes the camera over
// for good: its motion script (if any) is removed, so the script and the user never fight over
// the transform, while every other entity's script keeps running. reset() gives the camera back
// its start transform and script.
class CameraDriver {
 public:
  // Remembers `camera`'s transform and motion script (a null entity: nothing to drive).
  CameraDriver(ecs::Registry& registry, ecs::Entity camera);
  // Applies one frame of input; returns true when the user drives the camera (now or before).
  bool drive(const FlyInput& input, float dt);
  void reset();
  bool flying() const { return fly_.has_value(); }
  // The orbit pivot's distance ahead of the camera (metres); reset() restores the value set here.
  void setOrbitDistance(float metres) { orbitDistance_ = startOrbitDistance_ = metres; }
  float orbitDistance() const { return orbitDistance_; }

 private:
  ecs::Registry& registry_;
  ecs::Entity camera_;
  scene::Transform startTransform_;
  std::optional<scene::Motion> startMotion_;
  std::optional<FlyCamera> fly_;
  float orbitDistance_ = 1.0f, startOrbitDistance_ = 1.0f;
};

}  // namespace bounce::game
