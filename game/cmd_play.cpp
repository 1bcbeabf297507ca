// bounce play LEVEL|FILE.glb: an interactive window (GLFW + Vulkan swapchain) with a fly/orbit camera, keys for
// effects, debug views, exposure, vsync and pause, and a GPU-timing overlay (overlay.hpp).
//
// Time: with --frames N the simulation steps a fixed 1/60 s per frame (frame f at t = f/60, as a
// capture script with dt = 1/60), so screenshots are reproducible and comparable with
// `bounce capture`; otherwise simulation time follows the wall clock. P stops it (motion scripts
// hold their pose) without stopping rendering or the fly camera.
#include <GLFW/glfw3.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <utility>
#include <chrono>
#include <cstdio>
#include <memory>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/paths.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/image_io.hpp"
#include "engine/gpu/presenter_swapchain.hpp"
#include "engine/scene/systems.hpp"
#include "game/commands.hpp"
#include "game/overlay.hpp"
#include "game/play_controls.hpp"
#include "game/play_stats.hpp"
#include "game/session.hpp"
#include "game/render_limits.hpp"

namespace bounce::game {

namespace {

constexpr double kFixedStep = 1.0 / 60.0;  // s per frame with --frames
constexpr double kMaxFrameDt = 0.1;        // s: a hitch (window drag, breakpoint) moves the camera at most this much

// The window and GLFW itself, released in reverse order whatever happens.
struct Window {
  GLFWwindow* handle = nullptr;
  ~Window() {
    if (handle) glfwDestroyWindow(handle);
    glfwTerminate();
  }
};

// Key presses and wheel steps since the last poll, in order (movement keys are polled, not queued).
struct KeyQueue {
  std::vector<int> pressed;
  double wheel = 0.0;
};

void onKey(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  if (action != GLFW_PRESS) return;
  static_cast<KeyQueue*>(glfwGetWindowUserPointer(window))->pressed.push_back(key);
}

void onScroll(GLFWwindow* window, double /*x*/, double y) {
  static_cast<KeyQueue*>(glfwGetWindowUserPointer(window))->wheel += y;
}

// Cursor motion while the left button is held (orbit); the cursor stays visible, as in viewers.
class MouseDrag {
 public:
  glm::vec2 poll(GLFWwindow* window) {
    const bool held = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    double x, y;
    glfwGetCursorPos(window, &x, &y);
    const glm::vec2 delta = held && held_ ? glm::vec2(float(x - x_), float(y - y_)) : glm::vec2(0.0f);
    held_ = held;
    x_ = x;
    y_ = y;
    return delta;
  }

 private:
  bool held_ = false;
  double x_ = 0.0, y_ = 0.0;
};

// The orbit pivot's distance: where the view ray passes the centre of everything drawn (for a
// glTF file's level, about the model's centre, which its camera looks at), at least 1 % of the
// scene's size ahead.
float orbitDistance(const render::RenderWorld& world, const scene::Transform& camera) {
  const glm::vec3 centre = 0.5f * (world.sceneMin + world.sceneMax);
  const float size = std::max(glm::length(world.sceneMax - world.sceneMin), 1e-3f);
  return std::max(glm::dot(centre - camera.translation, FlyCamera::forward(camera.rotation)), 0.01f * size);
}

// Mouse look while the right button is held: the cursor is hidden and captured meanwhile.
class MouseLook {
 public:
  glm::vec2 poll(GLFWwindow* window) {
    const bool held = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (held != held_) {
      held_ = held;
      glfwSetInputMode(window, GLFW_CURSOR, held ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
      if (held && glfwRawMouseMotionSupported()) glfwSetInputMode(window, GLFW_RAW_MOUSE_MOTION, GLFW_TRUE);
      glfwGetCursorPos(window, &x_, &y_);
      return glm::vec2(0.0f);
    }
    if (!held) return glm::vec2(0.0f);
    double x, y;
    glfwGetCursorPos(window, &x, &y);
    const glm::vec2 delta(float(x - x_), float(y - y_));
    x_ = x;
    y_ = y;
    return delta;
  }

 private:
  bool held_ = false;
  double x_ = 0.0, y_ = 0.0;
};

FlyInput pollMovement(GLFWwindow* w, glm::vec2 look, glm::vec2 orbit, float zoom) {
  auto down = [&](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.0f : 0.0f; };
  FlyInput in;
  in.move = {down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
             down(GLFW_KEY_W) - down(GLFW_KEY_S)};
  in.look = look;
  in.orbit = orbit;
  in.zoom = zoom;
  in.fast = down(GLFW_KEY_LEFT_SHIFT) + down(GLFW_KEY_RIGHT_SHIFT) > 0.0f;
  return in;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ",") + n;
  return s.empty() ? "(none)" : s;
}

std::string onOffArg(const cli::Args& args, const std::string& option, const std::string& fallback) {
  const std::string v = args.str(option, fallback);
  if (v != "on" && v != "off") throwInputError("bounce play", option, "'" + v + "'", "on or off");
  return v;
}

std::string dnrtModeText(const PlayState& state) {
  if (!state.dnrtMode) return "dnrt mode: each object's own (outer cube, or its level \"mode\")";
  return *state.dnrtMode == scene::DnrtMode::FullScreen
             ? "dnrt mode: full-screen pass per object (the paper's, for comparison)"
             : "dnrt mode: clustered (one pass, each pixel visits the objects over its 16x16 tile)";
}

// F12: the frame just rendered as <output root>/screenshots/<level>-<frame>.png (display, as
// shown without the overlay) and .pfm (linear HDR radiance, as `bounce capture` writes).
void writeScreenshot(gpu::Context& ctx, Session& session, const std::string& levelName, int frame) {
  session.renderer().frames().waitIdle();
  const std::filesystem::path dir = defaultOutputRoot() / "screenshots";
  std::filesystem::create_directories(dir);
  char name[64];
  std::snprintf(name, sizeof name, "-%06d", frame);
  const std::filesystem::path png = dir / (levelName + name + ".png"), pfm = dir / (levelName + name + ".pfm");
  auto& image = session.renderer().displayImage();
  gpu::writePng(png, image.desc().width, image.desc().height, 4, gpu::readback(ctx, image));
  gpu::writePfm(pfm, {image.desc().width, image.desc().height, session.renderer().readHdr()});
  std::printf("screenshot: %s %s\n", png.c_str(), pfm.c_str());
  std::fflush(stdout);
}

}  // namespace

int runPlay(const cli::Args& args) {
  const int frameLimit = args.has("--frames") ? args.positiveInt("--frames", 1) : 0;
  const auto res = args.resolution("--resolution").value_or(std::pair{1280, 720});
  PlayState state;
  state.vsync = onOffArg(args, "--vsync", "on") == "on";
  // Screenshots default to no overlay, so they compare with `bounce capture` pictures.
  state.overlay = onOffArg(args, "--overlay", args.has("--screenshot") ? "off" : "on") == "on";
  if (args.has("--screenshot") && !frameLimit)
    throwInputError("bounce play", "--screenshot", "needs --frames N", "--frames N --screenshot FILE");
  const std::vector<ScriptedKey> scripted = parseKeyScript(args.str("--keys"));
  if (frameLimit && !scripted.empty() && scripted.back().frame >= frameLimit)  // it would never be pressed
    throwInputError("bounce play", "--keys", "a key at frame " + std::to_string(scripted.back().frame) + " after the last frame (" +
                                                 std::to_string(frameLimit - 1) + ")",
                    "frames below --frames " + std::to_string(frameLimit));
  std::size_t nextScripted = 0;
  scene::Level level = loadLevelWithEffects(args.positional[0], args.list("--effects"));

  // GLFW first (the Vulkan instance needs its surface extensions), then the device, then the
  // render size checked against the device's limits and memory, and only then the window: a size
  // the device cannot hold is refused (exit 2, one line) before anything shows on the screen.
  if (!glfwInit()) throw InternalError("no display: GLFW could not initialise (use 'bounce capture' headless)");
  Window window;  // declared before the context: the context goes first, glfwTerminate() last

  int code = 0;
  gpu::ContextOptions options;
  options.deviceName = args.str("--device");
  options.windowed = true;
  gpu::Context ctx(options);
  checkRenderSize(ctx, {std::uint32_t(res.first), std::uint32_t(res.second)}, "bounce play", "--resolution");

  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window.handle = glfwCreateWindow(res.first, res.second, ("bounce — " + level.name).c_str(), nullptr, nullptr);
  if (!window.handle) throw InternalError("could not open a window");
  KeyQueue keys;
  glfwSetWindowUserPointer(window.handle, &keys);
  glfwSetKeyCallback(window.handle, onKey);
  glfwSetScrollCallback(window.handle, onScroll);
  if (!frameLimit && scripted.empty()) {  // a person at the window: tell them the keys
    std::fputs(keyMapText().c_str(), stdout);
    std::fflush(stdout);
  }
  {
    Session session(ctx, level);
    gpu::SwapchainPresenter swapchain(ctx, window.handle, state.vsync);
    OverlayPresenter presenter(swapchain);
    std::unique_ptr<Overlay> overlay;  // made when first shown: its pipeline costs start-up time
    RollingTimings timings;

    CameraDriver camera(session.registry(), scene::activeCamera(session.registry()));
    if (session.vlm()) {  // live per-tag VLM overrides start from the level's (T, ]/[, H)
      state.vlm.tags = session.vlm()->tags();
      state.vlm.overrides = session.level().vlm.overrides;
    }
    MouseLook mouse;
    MouseDrag drag;
    bool overlayWantsMouse = false;  // last frame's: the panel, not the camera, gets the mouse
    bool screenshotPending = false;  // F12 or the panel's button: the next frame is written

    auto last = std::chrono::steady_clock::now();
    double simTime = 0.0;
    std::uint64_t simSteps = 0;
    // Which effects this level can never run (no entity takes part), with the reason:
    // the overlay disables their checkboxes. Fixed for the session (entities do not change).
    std::array<std::string, scene::kEffectCount> effectWhyOff;
    for (int i = 0; i < scene::kEffectCount; ++i) effectWhyOff[std::size_t(i)] = session.whyCannotRun(scene::Effect(i));
    for (int frame = 0; !frameLimit || frame < frameLimit; ++frame) {
      glfwPollEvents();
      if (glfwWindowShouldClose(window.handle) || state.quit) break;
      const auto now = std::chrono::steady_clock::now();
      const double elapsed = std::chrono::duration<double>(now - last).count();
      const double wallDt = std::min(elapsed, kMaxFrameDt);
      last = now;
      if (frame > 0) timings.addCpuFrameMs(elapsed * 1000.0);
      const double dt = frameLimit ? kFixedStep : wallDt;

      while (nextScripted < scripted.size() && scripted[nextScripted].frame == frame)
        keys.pressed.push_back(scripted[nextScripted++].key);
      for (int key : keys.pressed) {
        switch (applyKey(key, state, session.level().effects)) {
          case KeyEffect::EffectsChanged:
            session.syncTechniques();  // builds what was just named; notes what cannot run
            log::info("effects: " + joined(session.level().effects.names()));
            break;
          case KeyEffect::VsyncChanged:
            swapchain.setVsync(state.vsync);
            log::info(std::string("vsync ") + (state.vsync ? "on" : "off"));
            break;
          case KeyEffect::ResetCamera: camera.reset(); break;
          case KeyEffect::VlmChanged:
            if (session.vlm()) session.vlm()->setOverrides(state.vlm.overrides);
            log::info(vlmControlText(state.vlm));
            break;
          case KeyEffect::Screenshot: screenshotPending = true; break;
          case KeyEffect::AnimationChanged:
            if (key == GLFW_KEY_K) cycleSelectedClip(session.registry(), state.character);
            log::info(animationText(session.registry(), state.character));
            break;
          case KeyEffect::DnrtModeChanged: log::info(dnrtModeText(state)); break;
          case KeyEffect::Handled:
          case KeyEffect::None: break;
        }
      }
      keys.pressed.clear();

      const glm::vec2 dragged = drag.poll(window.handle);
      camera.drive(pollMovement(window.handle, mouse.poll(window.handle), overlayWantsMouse ? glm::vec2(0.0f) : dragged,
                                overlayWantsMouse ? 0.0f : float(keys.wheel)),
                   float(dt));
      keys.wheel = 0.0;

      session.update(frameLimit ? double(simSteps) * kFixedStep : simTime);
      if (!state.paused) {
        ++simSteps;
        simTime += dt;
      }

      if (state.overlay) {
        if (!overlay)
          overlay = std::make_unique<Overlay>(ctx, VK_FORMAT_R8G8B8A8_UNORM, session.renderer().frames().framesInFlight(),
                                              window.handle);
        OverlayInfo info;
        info.title = level.name;
        info.cpuFrameMs = timings.cpuFrameMedianMs();
        info.passes = timings.passMedians();
        info.gpuTotalMs = timings.gpuTotalMedianMs();
        info.gpuWindow = timings.gpuFrames();
        info.effects = session.runningEffects();  // a named effect that cannot run is not shown as on
        info.effectWhyOff = effectWhyOff;
        info.debugView = state.settings.debugView;
        info.exposure = state.settings.exposure;
        info.vsync = state.vsync;
        info.paused = state.paused;
        info.culling = state.settings.culling;
        info.flying = camera.flying();
        info.extent = presenter.extent();
        info.vlm = vlmControlText(state.vlm);
        info.animation = animationText(session.registry(), state.character);
        info.dnrtRuns = session.runs(scene::Effect::Dnrt) && session.level().effects.has(scene::Effect::Dnrt);
        info.dnrtMode = state.dnrtMode ? 1 + int(*state.dnrtMode == scene::DnrtMode::Clustered) : 0;
        if (session.vlm() && session.level().effects.has(scene::Effect::Vlm)) info.vlmControl = state.vlm;
        if (session.vlm()) info.vlmOverflow = gi::vlm::formatOverflow(session.vlm()->overflow());
        const OverlayActions actions = overlay->build(info, dt);
        if (actions.exposure) state.settings.exposure = *actions.exposure;
        if (actions.debugView) state.settings.debugView = *actions.debugView;
        screenshotPending = screenshotPending || actions.screenshot;
        if (actions.toggleEffect &&  // a checkbox does what its key 1-9 does
            applyKey(GLFW_KEY_1 + int(*actions.toggleEffect), state, session.level().effects) == KeyEffect::EffectsChanged) {
          session.syncTechniques();
          log::info("effects: " + joined(session.level().effects.names()));
        }
        if (actions.dnrtMode && *actions.dnrtMode != info.dnrtMode) {  // as key M
          state.dnrtMode = *actions.dnrtMode == 0   ? std::nullopt
                           : *actions.dnrtMode == 1 ? std::optional(scene::DnrtMode::FullScreen)
                                                    : std::optional(scene::DnrtMode::Clustered);
          log::info(dnrtModeText(state));
        }
        if (actions.vlmOverride && setVlmOverride(state.vlm, actions.vlmOverride->first, actions.vlmOverride->second)) {
          if (session.vlm()) session.vlm()->setOverrides(state.vlm.overrides);  // as keys ]/[ and H
        }
        overlayWantsMouse = actions.wantsMouse;
      } else {
        overlayWantsMouse = false;
      }
      const bool shoot = std::exchange(screenshotPending, false);
      // DNRT's mode, whenever its runtime exists (it may be built by a key after start-up).
      if (gi::dnrt::Runtime* dnrt = session.dnrt()) dnrt->settings().mode = state.dnrtMode;
      render::FrameSettings settings = state.settings;
      settings.keepHdr = shoot;
      presenter.setOverlay(state.overlay && !shoot ? overlay.get() : nullptr);
      session.render(presenter, settings);
      if (shoot) writeScreenshot(ctx, session, level.source.stem().string(), frame);
      if (frame == 0) {  // the first extract knows the scene bounds
        const ecs::Entity cam = scene::activeCamera(session.registry());
        if (const auto* t = cam.isNull() ? nullptr : session.registry().tryGet<scene::Transform>(cam))
          camera.setOrbitDistance(orbitDistance(session.world(), *t));
      }
      timings.addGpuFrame(session.renderer().frames().lastTimings(), session.renderer().frames().lastTimingsFrame());
    }
    session.renderer().frames().waitIdle();
    if (args.has("--screenshot")) {
      auto& image = session.renderer().displayImage();
      const auto bytes = gpu::readback(ctx, image);
      gpu::writePng(args.str("--screenshot"), image.desc().width, image.desc().height, 4, bytes);
    }
  }
  if (ctx.validationEnabled() && ctx.validationErrorCount() > 0) {
    std::fprintf(stderr, "bounce play: %llu Vulkan validation error(s), printed above\n",
                 static_cast<unsigned long long>(ctx.validationErrorCount()));
    code = 1;
  }
  return code;
}

}  // namespace bounce::game
