#include "game/play_controls.hpp"

#include <GLFW/glfw3.h>

#include "engine/anim/animator.hpp"
#include "engine/core/error.hpp"
#include "engine/core/suggest.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace bounce::game {

using scene::Effect;
using render::DebugView;

namespace {

KeyBinding effectKey(int index) {
  const Effect e = Effect(index);
  return {GLFW_KEY_1 + index, nullptr, PlayAction::ToggleEffect, index,
          "toggle effect '" + std::string(scene::effectName(e)) + "'"};
}

KeyBinding viewKey(int index) {
  return {GLFW_KEY_F1 + index, nullptr, PlayAction::SetDebugView, index,
          std::string("debug view: ") + render::debugViewName(DebugView(index))};
}

std::vector<KeyBinding> makeBindings() {
  static const char* const kDigits[] = {"1", "2", "3", "4", "5", "6", "7", "8", "9"};
  static const char* const kFKeys[] = {"F1", "F2", "F3", "F4", "F5", "F6"};
  std::vector<KeyBinding> b;
  for (int i = 0; i < scene::kEffectCount; ++i) {
    b.push_back(effectKey(i));
    b.back().keyName = kDigits[i];
  }
  for (int i = 0; i <= int(DebugView::EntityId); ++i) {
    b.push_back(viewKey(i));
    b.back().keyName = kFKeys[i];
  }
  b.push_back({GLFW_KEY_0, "0", PlayAction::CycleDebugView, 0, "next debug view"});
  b.push_back({GLFW_KEY_EQUAL, "+", PlayAction::ExposureUp, 0, "exposure +1/4 stop"});
  b.push_back({GLFW_KEY_KP_ADD, "keypad +", PlayAction::ExposureUp, 0, "exposure +1/4 stop"});
  b.push_back({GLFW_KEY_MINUS, "-", PlayAction::ExposureDown, 0, "exposure -1/4 stop"});
  b.push_back({GLFW_KEY_KP_SUBTRACT, "keypad -", PlayAction::ExposureDown, 0, "exposure -1/4 stop"});
  b.push_back({GLFW_KEY_V, "V", PlayAction::ToggleVsync, 0, "vsync on/off (rebuilds the swapchain)"});
  b.push_back({GLFW_KEY_P, "P", PlayAction::TogglePause, 0, "pause/resume motion scripts and animation clips"});
  b.push_back({GLFW_KEY_O, "O", PlayAction::ToggleOverlay, 0, "overlay on/off"});
  b.push_back({GLFW_KEY_C, "C", PlayAction::ToggleCulling, 0, "render-graph culling on/off"});
  b.push_back({GLFW_KEY_R, "R", PlayAction::ResetCamera, 0, "reset the camera (and its motion script)"});
  b.push_back({GLFW_KEY_T, "T", PlayAction::VlmNextTag, 0, "VLM: select the next tag (none, then each tag)"});
  b.push_back({GLFW_KEY_RIGHT_BRACKET, "]", PlayAction::VlmIntensityUp, 0, "VLM: selected tag's intensity x1.41"});
  b.push_back({GLFW_KEY_LEFT_BRACKET, "[", PlayAction::VlmIntensityDown, 0, "VLM: selected tag's intensity /1.41"});
  b.push_back({GLFW_KEY_H, "H", PlayAction::VlmNextHue, 0, "VLM: rotate the selected tag's hue by 30 degrees"});
  b.push_back({GLFW_KEY_M, "M", PlayAction::DnrtToggleMode, 0,
               "DNRT mode: each object's own -> full-screen (paper) -> clustered -> own"});
  b.push_back({GLFW_KEY_F12, "F12", PlayAction::Screenshot, 0, "screenshot: PNG + PFM of the next frame (no overlay)"});
  b.push_back({GLFW_KEY_L, "L", PlayAction::AnimNextCharacter, 0, "animation: select the next animated character"});
  b.push_back({GLFW_KEY_K, "K", PlayAction::AnimNextClip, 0, "animation: the selected character's next clip"});
  b.push_back({GLFW_KEY_ESCAPE, "Esc", PlayAction::Quit, 0, "quit"});
  return b;
}

}  // namespace

const std::vector<KeyBinding>& keyBindings() {
  static const std::vector<KeyBinding> bindings = makeBindings();
  return bindings;
}

std::string keyMapText() {
  std::ostringstream out;
  out << "keys:\n"
      << "  W/A/S/D       move forward/left/back/right (0.5 m/s; Shift: x4)\n"
      << "  Q/E           move down/up\n"
      << "  right mouse   hold and move the mouse to look around\n"
      << "  left mouse    drag to orbit the point ahead (a glTF file: the model's centre); wheel zooms\n";
  for (const auto& b : keyBindings()) {
    const std::string name = b.keyName;
    out << "  " << name << std::string(name.size() < 14 ? 14 - name.size() : 1, ' ') << b.help << "\n";
  }
  return out.str();
}

std::string keyMapSummary(const std::string& indent) {
  std::string effects;
  for (int i = 0; i < scene::kEffectCount; ++i)
    effects += std::string(i ? " " : "") + std::to_string(i + 1) + "=" + std::string(scene::effectName(Effect(i)));
  std::string views;
  for (int i = 0; i <= int(DebugView::EntityId); ++i)
    views += std::string(i ? " " : "") + "F" + std::to_string(i + 1) + "=" + render::debugViewName(DebugView(i));
  return indent + "keys: W/A/S/D move, Q/E down/up, Shift faster, hold right mouse to look\n" +
         indent + "  left-drag orbits, wheel zooms\n" +
         indent + "  effects: " + effects + "\n" +
         indent + "  views: " + views + ", 0 cycles\n" +
         indent + "  +/- exposure, V vsync, P pause, O overlay, C culling, R reset camera, Esc quit\n" +
         indent + "  F12 screenshot (PNG + PFM)\n" +
         indent + "  VLM: T selects a tag, ]/[ its intensity up/down, H rotates its hue\n" +
         indent + "  DNRT: M cycles every object's mode: own -> full-screen (paper) -> clustered\n" +
         indent + "  animation: L selects a character, K plays its next clip";
}

std::vector<ScriptedKey> parseKeyScript(const std::string& list) {
  std::vector<ScriptedKey> out;
  if (list.empty()) return out;
  std::string names;
  for (const auto& b : keyBindings()) {
    if (!names.empty()) names += ' ';
    names += b.keyName;
  }
  const std::string expected = "KEY@FRAME items separated by commas, KEY one of: " + names;
  std::size_t pos = 0;
  while (pos <= list.size()) {
    const std::size_t comma = std::min(list.find(',', pos), list.size());
    const std::string item = list.substr(pos, comma - pos);
    pos = comma + 1;
    const std::size_t at = item.rfind('@');
    if (at == std::string::npos || at == 0 || at + 1 == item.size())
      throwInputError("bounce play", "--keys", "'" + item + "'", expected);
    const std::string name = item.substr(0, at), frame = item.substr(at + 1);
    if (frame.size() > 9 || frame.find_first_not_of("0123456789") != std::string::npos)
      throwInputError("bounce play", "--keys", "'" + item + "': bad frame", "a frame index 0..999999999");
    const auto& bindings = keyBindings();
    auto it = std::find_if(bindings.begin(), bindings.end(), [&](const KeyBinding& b) { return name == b.keyName; });
    if (it == bindings.end()) {
      std::vector<std::string> names;
      for (const auto& b : bindings) names.emplace_back(b.keyName);
      throwInputError("bounce play", "--keys", "'" + item + "': unknown key" + didYouMean(name, names), expected);
    }
    out.push_back({std::stoi(frame), it->key});
  }
  std::stable_sort(out.begin(), out.end(), [](const ScriptedKey& a, const ScriptedKey& b) { return a.frame < b.frame; });
  return out;
}

scene::EffectSet toggled(scene::EffectSet effects, Effect e) {
  scene::EffectSet out;  // EffectSet can only add: rebuild it without (or with) `e`
  for (int i = 0; i < scene::kEffectCount; ++i) {
    const Effect x = Effect(i);
    if (x == e ? !effects.has(x) : effects.has(x)) out.add(x);
  }
  return out;
}

KeyEffect applyKey(int key, PlayState& state, scene::EffectSet& effects) {
  const auto& bindings = keyBindings();
  auto it = std::find_if(bindings.begin(), bindings.end(), [&](const KeyBinding& b) { return b.key == key; });
  if (it == bindings.end()) return KeyEffect::None;
  auto exposureStops = [&](float delta) {
    const float stops = std::clamp(std::log2(state.settings.exposure) + delta, kExposureMinStops, kExposureMaxStops);
    state.settings.exposure = std::exp2(stops);
  };
  switch (it->action) {
    case PlayAction::ToggleEffect: effects = toggled(effects, Effect(it->arg)); return KeyEffect::EffectsChanged;
    case PlayAction::SetDebugView: state.settings.debugView = DebugView(it->arg); return KeyEffect::Handled;
    case PlayAction::CycleDebugView:
      state.settings.debugView = DebugView((int(state.settings.debugView) + 1) % (int(DebugView::EntityId) + 1));
      return KeyEffect::Handled;
    case PlayAction::ExposureUp: exposureStops(kExposureStepStops); return KeyEffect::Handled;
    case PlayAction::ExposureDown: exposureStops(-kExposureStepStops); return KeyEffect::Handled;
    case PlayAction::ToggleVsync: state.vsync = !state.vsync; return KeyEffect::VsyncChanged;
    case PlayAction::TogglePause: state.paused = !state.paused; return KeyEffect::Handled;
    case PlayAction::ToggleOverlay: state.overlay = !state.overlay; return KeyEffect::Handled;
    case PlayAction::ToggleCulling: state.settings.culling = !state.settings.culling; return KeyEffect::Handled;
    case PlayAction::ResetCamera: return KeyEffect::ResetCamera;
    case PlayAction::Screenshot: return KeyEffect::Screenshot;
    case PlayAction::Quit: state.quit = true; return KeyEffect::Handled;
    case PlayAction::AnimNextCharacter: ++state.character; return KeyEffect::AnimationChanged;
    case PlayAction::AnimNextClip: return KeyEffect::AnimationChanged;
    case PlayAction::DnrtToggleMode:
      state.dnrtMode = !state.dnrtMode                                    ? std::optional(scene::DnrtMode::FullScreen)
                       : *state.dnrtMode == scene::DnrtMode::FullScreen ? std::optional(scene::DnrtMode::Clustered)
                                                                        : std::nullopt;
      return KeyEffect::DnrtModeChanged;
    case PlayAction::VlmNextTag: {
      VlmControl& v = state.vlm;
      if (v.tags.empty()) return KeyEffect::Handled;
      v.selected = v.selected + 1 >= int(v.tags.size()) ? -1 : v.selected + 1;
      return KeyEffect::Handled;
    }
    case PlayAction::VlmIntensityUp:
    case PlayAction::VlmIntensityDown:
    case PlayAction::VlmNextHue: {
      VlmControl& v = state.vlm;
      if (v.selected < 0 || v.selected >= int(v.tags.size())) return KeyEffect::Handled;  // nothing selected
      scene::VlmOverride& o = v.overrides[int(v.tags[std::size_t(v.selected)])];
      if (it->action == PlayAction::VlmNextHue) {
        o.hueDeg = std::fmod(o.hueDeg + kVlmHueStepDeg + 360.0f, 360.0f);
      } else {
        const float f = it->action == PlayAction::VlmIntensityUp ? kVlmIntensityStep : 1.0f / kVlmIntensityStep;
        o.intensity = std::clamp(o.intensity * f, kVlmIntensityMin, kVlmIntensityMax);
      }
      return KeyEffect::VlmChanged;
    }
  }
  return KeyEffect::None;
}

bool setVlmOverride(VlmControl& vlm, int tag, const scene::VlmOverride& value) {
  const auto at = std::find(vlm.tags.begin(), vlm.tags.end(), std::uint32_t(tag));
  if (tag < 0 || at == vlm.tags.end()) return false;
  vlm.selected = int(at - vlm.tags.begin());
  scene::VlmOverride& o = vlm.overrides[tag];
  if (std::isfinite(value.intensity)) o.intensity = std::clamp(value.intensity, kVlmIntensityMin, kVlmIntensityMax);
  if (std::isfinite(value.hueDeg)) o.hueDeg = std::fmod(std::fmod(value.hueDeg, 360.0f) + 360.0f, 360.0f);
  for (int c = 0; c < 3; ++c)
    if (std::isfinite(value.color[c])) o.color[c] = std::clamp(value.color[c], 0.0f, 1.0f);
  return true;
}

std::string vlmControlText(const VlmControl& vlm) {
  if (vlm.tags.empty()) return {};
  std::string list;
  for (std::uint32_t t : vlm.tags) list += (list.empty() ? "" : " ") + std::to_string(t);
  if (vlm.selected < 0 || vlm.selected >= int(vlm.tags.size()))
    return "VLM tags [" + list + "]: T selects one, ]/[ intensity, H hue";
  const int tag = int(vlm.tags[std::size_t(vlm.selected)]);
  scene::VlmOverride o;
  if (auto it = vlm.overrides.find(tag); it != vlm.overrides.end()) o = it->second;
  char text[160];
  std::snprintf(text, sizeof text, "VLM tag %d of [%s]: intensity %.2f, hue %.0f deg", tag, list.c_str(),
                double(o.intensity), double(o.hueDeg));
  return text;
}

// --- FlyCamera ---

glm::vec3 FlyCamera::forward(const glm::quat& rotation) { return rotation * glm::vec3(0.0f, 0.0f, -1.0f); }

glm::quat FlyCamera::rotationFromYawPitch(float yaw, float pitch) {
  // R = Ry(yaw) · Rx(pitch): forward = (−sin yaw · cos pitch, sin pitch, −cos yaw · cos pitch).
  return glm::angleAxis(yaw, glm::vec3(0, 1, 0)) * glm::angleAxis(pitch, glm::vec3(1, 0, 0));
}

FlyCamera::FlyCamera(const scene::Transform& start) {
  const glm::vec3 f = glm::normalize(forward(start.rotation));
  yaw_ = std::atan2(-f.x, -f.z);
  pitch_ = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
}

scene::Transform FlyCamera::step(const scene::Transform& current, const FlyInput& input, float dt) {
  // Mouse right turns right (yaw decreases: −Z turns towards +X); mouse down looks down.
  yaw_ -= input.look.x * kRadiansPerPixel;
  pitch_ = std::clamp(pitch_ - input.look.y * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
  yaw_ = std::remainder(yaw_, 2.0f * glm::pi<float>());

  scene::Transform t = current;
  t.rotation = rotationFromYawPitch(yaw_, pitch_);
  glm::vec3 move = input.move;
  if (glm::length(move) > 1.0f) move = glm::normalize(move);  // diagonals are not faster
  const float speed = kSpeed * (input.fast ? kFastFactor : 1.0f);
  const glm::vec3 right = t.rotation * glm::vec3(1, 0, 0);
  t.translation += (right * move.x + glm::vec3(0, 1, 0) * move.y + forward(t.rotation) * move.z) * speed * dt;
  return t;
}

scene::Transform FlyCamera::orbit(const scene::Transform& current, glm::vec2 drag, float zoomSteps, float& distance) {
  const glm::vec3 pivot = current.translation + forward(rotationFromYawPitch(yaw_, pitch_)) * distance;
  yaw_ = std::remainder(yaw_ - drag.x * kOrbitRadiansPerPixel, 2.0f * glm::pi<float>());
  pitch_ = std::clamp(pitch_ - drag.y * kOrbitRadiansPerPixel, -kMaxPitch, kMaxPitch);
  distance = std::max(distance * std::pow(kZoomStep, zoomSteps), kMinOrbitDistance);
  scene::Transform t = current;
  t.rotation = rotationFromYawPitch(yaw_, pitch_);
  t.translation = pivot - forward(t.rotation) * distance;
  return t;
}

// --- CameraDriver ---

CameraDriver::CameraDriver(ecs::Registry& registry, ecs::Entity camera) : registry_(registry), camera_(camera) {
  if (camera_.isNull()) return;
  if (const auto* t = registry_.tryGet<scene::Transform>(camera_)) startTransform_ = *t;
  if (const auto* m = registry_.tryGet<scene::Motion>(camera_)) startMotion_ = *m;
}

bool CameraDriver::drive(const FlyInput& input, float dt) {
  if (camera_.isNull()) return false;
  if (input.move == glm::vec3(0.0f) && input.look == glm::vec2(0.0f) && input.orbit == glm::vec2(0.0f) &&
      input.zoom == 0.0f)
    return flying();
  scene::Transform* transform = registry_.tryGet<scene::Transform>(camera_);
  if (!transform) transform = &registry_.emplace<scene::Transform>(camera_, startTransform_);
  if (!fly_) {
    registry_.remove<scene::Motion>(camera_);
    fly_.emplace(*transform);
  }
  *transform = fly_->step(*transform, input, dt);
  if (input.orbit != glm::vec2(0.0f) || input.zoom != 0.0f)
    *transform = fly_->orbit(*transform, input.orbit, input.zoom, orbitDistance_);
  return true;
}

void CameraDriver::reset() {
  if (camera_.isNull()) return;
  registry_.emplaceOrReplace<scene::Transform>(camera_, startTransform_);
  if (startMotion_) registry_.emplaceOrReplace<scene::Motion>(camera_, *startMotion_);
  fly_.reset();
  orbitDistance_ = startOrbitDistance_;
}

std::vector<ecs::Entity> animatedEntities(ecs::Registry& registry) {
  std::vector<ecs::Entity> out;
  registry.view<anim::Animator>().each([&](ecs::Entity e, anim::Animator& a) {
    if (a.clipCount() > 0) out.push_back(e);
  });
  std::sort(out.begin(), out.end(), [](ecs::Entity a, ecs::Entity b) { return a.index() < b.index(); });
  return out;
}

void cycleSelectedClip(ecs::Registry& registry, int character) {
  const auto es = animatedEntities(registry);
  if (!es.empty()) anim::cycleClip(registry.get<anim::Animator>(es[std::size_t(character) % es.size()]));
}

std::string animationText(ecs::Registry& registry, int character) {
  const auto es = animatedEntities(registry);
  if (es.empty()) return {};
  const ecs::Entity e = es[std::size_t(character) % es.size()];
  const anim::Animator& a = registry.get<anim::Animator>(e);
  const auto* name = registry.tryGet<scene::Name>(e);
  char time[32];
  std::snprintf(time, sizeof time, "%.2f s", double(a.clipTime));
  return (name ? name->id : "entity") + ": " + a.clipName() + " " + time + " (L selects, K next clip)";
}

}  // namespace bounce::game
