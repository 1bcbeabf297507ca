#pragma once
// A loaded level ready to simulate and render: the ECS registry, the uploaded GPU scene and the
// renderer. play, capture and profile all drive one Session:
//   Session s(ctx, level);  for each frame: s.update(t); s.render(presenter, settings);
#include <filesystem>
#include <memory>
#include <optional>

#include "engine/ecs/registry.hpp"
#include "engine/gi/ao/ao.hpp"
#include "engine/gi/dnrt/probe_source.hpp"
#include "engine/gi/dnrt/runtime.hpp"
#include "engine/gi/probes/bake.hpp"
#include "engine/gi/probes/node.hpp"
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

// Where bakes are cached: <build dir>/probes and <build dir>/dnrt.
std::filesystem::path probeCacheDir();
std::filesystem::path dnrtCacheDir();
// The probe bake settings of a level's "probes" object (InputError when the baker rejects them).
gi::probes::ProbeSettings probeSettings(const scene::Level& level);

class Session {
 public:
  // Builds only what the level's effects name: probes (bake or cached), DNRT (fields baked or
  // cached for every `dnrt` entity), VLM (when an entity carries `vlm`), SSAO/HBAO; each becomes a
  // renderer node.
  Session(gpu::Context& ctx, scene::Level level);
  // Waits for the GPU before the nodes, the scene and the renderer go (frames may still use them).
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Runs the systems for simulation time t (seconds): camera script, motion, transforms.
  void update(double t);
  // Extracts the RenderWorld for `extent` and renders it through `presenter`.
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
  // The GI runtimes the effects asked for (null otherwise).
  gi::probes::ProbeNode* probes() { return probes_.get(); }
  gi::dnrt::Runtime* dnrt() { return dnrt_.get(); }
  vlm::Runtime* vlm() { return vlm_.get(); }
  gi::ao::Node* ao(gi::ao::Kind kind) { return ao_[int(kind)].get(); }

 private:
  gpu::Context& ctx_;
  scene::Level level_;
  ecs::Registry registry_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<render::GpuScene> scene_;
  std::unique_ptr<gi::ao::Node> ao_[2];
  std::unique_ptr<gi::probes::ProbeNode> probes_;
  std::unique_ptr<gi::dnrt::ProbeSource> probeSource_;
  std::unique_ptr<ref::ReferenceAssets> cpuAssets_;  // DNRT bakes from the CPU copies
  std::unique_ptr<gi::dnrt::Runtime> dnrt_;
  std::unique_ptr<vlm::Runtime> vlm_;
  render::RenderWorld world_;
};

}  // namespace bounce::game
