#pragma once
// A loaded level ready to simulate and render: the ECS registry, the uploaded GPU scene and the
// renderer. play, capture and profile all drive one Session:
//   Session s(ctx, level);  for each frame: s.update(t); s.render(presenter, settings);
#include <filesystem>
#include <memory>
#include <optional>
#include <string_view>

#include "engine/ecs/registry.hpp"
#include "engine/gi/ao/node.hpp"
#include "engine/gi/dnrt/runtime.hpp"
#include "engine/gi/probes/node.hpp"
#include "engine/gi/technique.hpp"
#include "engine/gi/vlm/node.hpp"
#include "engine/gpu/context.hpp"
#include "engine/render/gpu_scene.hpp"
#include "engine/render/renderer.hpp"
#include "engine/scene/level.hpp"
#include "engine/scene/motion.hpp"

namespace bounce::game {

// Where cooked assets are cached: BOUNCE_COOK_CACHE, else <build dir>/cooked.
std::filesystem::path cookCacheDir();

// Loads a level and applies an optional --effects override (both validated; errors are InputError).
scene::Level loadLevelWithEffects(const std::filesystem::path& path, const std::optional<std::vector<std::string>>& effects);

class Session {
 public:
  // Builds, for every technique of the table (engine/gi/technique.hpp) whose effect the level names
  // AND in which an entity takes part, its runtime (baking through the cache what is missing) and
  // its renderer node, in table order. A named effect that cannot run (no entity takes part) gets
  // one note on stderr (once per process) and in notes().
  Session(gpu::Context& ctx, scene::Level level);
  // Waits for the GPU before the nodes, the scene and the renderer go (frames may still use them).
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Runs the systems for simulation time t (seconds): camera script, motion, transforms, then each
  // running technique's per-frame CPU update.
  void update(double t);
  // Extracts the RenderWorld for `extent` and renders it through `presenter`. Builds first the
  // techniques of effects named since the last frame (play keys).
  void render(gpu::Presenter& presenter, const render::FrameSettings& settings);
  // The world as extracted by the last render() or extractOnly().
  const render::RenderWorld& world() const { return world_; }
  void extractOnly(VkExtent2D extent, std::uint32_t shadowResolution = 1024);

  // A motion script for the active camera (capture scripts); its base is the camera's transform.
  void setCameraMotion(scene::Motion motion);

  scene::Level& level() { return level_; }
  ecs::Registry& registry() { return registry_; }
  render::Renderer& renderer() { return *renderer_; }
  render::GpuScene& gpuScene() { return *scene_; }

  // Builds the runtimes of techniques whose effect is named now and was not before (render() does).
  void syncTechniques();
  // True when effect `e` has what it needs to run: direct and shadows always (the renderer's own
  // passes), a technique when its runtime was built. The play overlay shows an effect as on only
  // when it is named AND runs.
  bool runs(scene::Effect e) const;
  // The level's named effects that run (runs()): what the play overlay shows as on.
  scene::EffectSet runningEffects() const;
  // Why effect `e` cannot run in this session, named or not — the technique table's note (no
  // entity takes part) — or empty when it can (direct and shadows always can). What the play
  // overlay's disabled effect checkboxes show as their tooltip.
  std::string whyCannotRun(scene::Effect e);
  // The notes printed for named effects that do not run, in table order.
  const std::vector<std::string>& notes() const { return notes_; }
  // The running technique of an effect name, or null.
  gi::TechniqueRuntime* technique(std::string_view name);
  template <class T>
  T* technique(std::string_view name) {
    return dynamic_cast<T*>(technique(name));
  }
  // `bounce profile`'s lines after the timings, from every running technique in table order.
  std::vector<std::string> profileLines() const;
  // Typed access to today's techniques (tests, play's VLM keys); null when not running.
  gi::probes::ProbeNode* probes() { return technique<gi::probes::ProbeNode>("probes"); }
  gi::dnrt::Runtime* dnrt();
  gi::vlm::Runtime* vlm() { return technique<gi::vlm::Runtime>("vlm"); }
  gi::ao::Node* ao(gi::ao::Kind kind) { return technique<gi::ao::Node>(gi::ao::kindName(kind)); }

 private:
  // InputError when the level has more lights or shadow layers than the lighting pass holds.
  void checkLightCapacity();
  struct Slot {
    const gi::Technique* technique = nullptr;
    bool tried = false;  // its effect was named once: built, or noted as not running
    std::unique_ptr<gi::TechniqueRuntime> runtime;
  };
  gpu::Context& ctx_;
  scene::Level level_;
  ecs::Registry registry_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<render::GpuScene> scene_;
  gi::Services services_;
  std::vector<Slot> slots_;  // one per row of gi::techniques(), same order
  std::vector<std::string> notes_;
  render::RenderWorld world_;
};

}  // namespace bounce::game
