#include "game/session.hpp"

#include <cstdlib>

#include "engine/gi/probes/bake.hpp"
#include "engine/gi/probes/node.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/systems.hpp"

namespace bounce::game {

std::filesystem::path cookCacheDir() {
  if (const char* env = std::getenv("BOUNCE_COOK_CACHE"); env && *env) return env;
  return std::filesystem::path(BOUNCE_BINARY_DIR) / "cooked";
}

scene::Level loadLevelWithEffects(const std::filesystem::path& path,
                                  const std::optional<std::vector<std::string>>& effects) {
  scene::Level level = scene::loadLevel(path);
  if (effects) {
    std::string list;
    for (const auto& e : *effects) list += (list.empty() ? "" : ",") + e;
    scene::overrideEffects(level, list);
  }
  return level;
}

Session::Session(gpu::Context& ctx, scene::Level level) : ctx_(ctx), level_(std::move(level)) {
  scene::instantiate(level_, registry_);
  renderer_ = std::make_unique<render::Renderer>(ctx_);
  scene_ = std::make_unique<render::GpuScene>(ctx_, renderer_->pipelines(), renderer_->samplers(), cookCacheDir());
  scene_->load(registry_);
  // Effect `probes`: bake (or load the cached bake of) the static scene, add the probes node.
  if (level_.effects.has(scene::Effect::Probes)) {
    auto baked = gi::probes::loadOrBake(level_, cookCacheDir(), std::filesystem::path(BOUNCE_BINARY_DIR) / "probes",
                                        gi::probes::ProbeSettings{});
    renderer_->addNode(std::make_shared<gi::probes::ProbeNode>(ctx_, renderer_->pipelines(), std::move(baked.volume)));
  }
}

void Session::setCameraMotion(scene::Motion motion) {
  ecs::Entity cam = scene::activeCamera(registry_);
  if (cam.isNull()) return;
  motion.base = registry_.get<scene::Transform>(cam);
  registry_.emplaceOrReplace<scene::Motion>(cam, std::move(motion));
}

void Session::update(double t) {
  scene::motionSystem(registry_, t);
  scene::transformSystem(registry_);
}

void Session::extractOnly(VkExtent2D extent, std::uint32_t shadowResolution) {
  scene_->extract(registry_, level_, {extent, shadowResolution}, world_);
}

void Session::render(gpu::Presenter& presenter, const render::FrameSettings& settings) {
  extractOnly(presenter.extent(), settings.shadowResolution);
  renderer_->render(world_, presenter, settings);
}

}  // namespace bounce::game
