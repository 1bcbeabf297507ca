#include "game/session.hpp"

#include <cstdlib>

#include "engine/anim/animator.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/probes/bake.hpp"
#include "engine/scene/components.hpp"
#include "engine/scene/systems.hpp"
#include "game/viewer_level.hpp"

namespace bounce::game {

std::filesystem::path cookCacheDir() {
  if (const char* env = std::getenv("BOUNCE_COOK_CACHE"); env && *env) return env;
  return cacheDir("cooked");
}

scene::Level loadLevelWithEffects(const std::filesystem::path& path,
                                  const std::optional<std::vector<std::string>>& effects) {
  scene::Level level = scene::loadLevel(levelPathFor(path));  // a glTF file: its viewer level
  if (effects) {
    std::string list;
    for (const auto& e : *effects) list += (list.empty() ? "" : ",") + e;
    scene::overrideEffects(level, list);
  }
  return level;
}

std::filesystem::path probeCacheDir() { return cacheDir("probes"); }
std::filesystem::path dnrtCacheDir() { return cacheDir("dnrt"); }

gi::probes::ProbeSettings probeSettings(const scene::Level& level) {
  gi::probes::ProbeSettings s;
  s.spacing = level.probes.spacing;
  s.order = level.probes.order;
  s.rays = level.probes.rays;
  gi::probes::validate(s, level.source.string(), "/probes");
  return s;
}

Session::Session(gpu::Context& ctx, scene::Level level) : ctx_(ctx), level_(std::move(level)) {
  scene::instantiate(level_, registry_);
  anim::attachAnimators(registry_, cookCacheDir());  // clips resolved (InputError) before anything is built
  renderer_ = std::make_unique<render::Renderer>(ctx_);
  scene_ = std::make_unique<render::GpuScene>(ctx_, renderer_->pipelines(), renderer_->samplers(), cookCacheDir());
  scene_->load(registry_);
  // Nodes run in the order set: AO first (a later node may read "ao.term"), then the static
  // indirect light (probes), then what the dynamic objects change (DNRT), then the virtual lights.
  for (gi::ao::Kind kind : {gi::ao::Kind::Ssao, gi::ao::Kind::Hbao}) {
    if (!level_.effects.has(kind == gi::ao::Kind::Ssao ? scene::Effect::Ssao : scene::Effect::Hbao)) continue;
    auto& node = ao_[int(kind)];
    node = std::make_unique<gi::ao::Node>(ctx_, renderer_->pipelines(), kind);
    renderer_->setNode(gi::ao::kindName(kind), node->node());
  }
  // Effect `probes`: bake (or load the cached bake of) the static scene.
  if (level_.effects.has(scene::Effect::Probes)) {
    auto baked = gi::probes::loadOrBake(level_, cookCacheDir(), probeCacheDir(),
                                        probeSettings(level_));
    probes_ = std::make_unique<gi::probes::ProbeNode>(ctx_, renderer_->pipelines(), std::move(baked.volume));
    renderer_->setNode("probes", probes_->node());
  }
  // Effect `dnrt`: a field per `dnrt` entity; c_j from the probes when the level has them.
  if (level_.effects.has(scene::Effect::Dnrt)) {
    cpuAssets_ = std::make_unique<ref::ReferenceAssets>();
    cpuAssets_->load(registry_, cookCacheDir());
    dnrt_ = std::make_unique<gi::dnrt::Runtime>(ctx_, renderer_->pipelines(), registry_, *cpuAssets_,
                                                dnrtCacheDir(),
                                                renderer_->frames().framesInFlight(), level_.background);
    if (probes_) {
      probeSource_ = std::make_unique<gi::dnrt::ProbeSource>(probes_->volume());
      dnrt_->setIrradianceSource(probeSource_.get());
    }
    renderer_->setNode("dnrt", dnrt_->node());
  }
  // Effect `vlm`: only when some entity carries virtual lights (issue 5): a `vlm` component, or a
  // mesh whose glTF nodes say extras.bounce_vlm.
  if (level_.effects.has(scene::Effect::Vlm) && !vlm::collectVlms(registry_, cookCacheDir()).empty()) {
    vlm_ = std::make_unique<vlm::Runtime>(ctx_, renderer_->pipelines(), registry_, vlm::settingsFrom(level_.vlm),
                                          cookCacheDir(), renderer_->frames().framesInFlight());
    renderer_->setNode("vlm", vlm_->node());
  }
}

Session::~Session() {
  if (renderer_) renderer_->frames().waitIdle();
}

void Session::setCameraMotion(scene::Motion motion) {
  ecs::Entity cam = scene::activeCamera(registry_);
  if (cam.isNull()) return;
  motion.base = registry_.get<scene::Transform>(cam);
  registry_.emplaceOrReplace<scene::Motion>(cam, std::move(motion));
}

void Session::update(double t) {
  scene::motionSystem(registry_, t);
  anim::animationSystem(registry_, t);
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
