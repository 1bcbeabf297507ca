#include "game/session.hpp"

#include <cstdlib>

#include "engine/anim/animator.hpp"
#include "engine/core/error.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/dnrt/technique.hpp"
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

Session::Session(gpu::Context& ctx, scene::Level level) : ctx_(ctx), level_(std::move(level)) {
  scene::instantiate(level_, registry_);
  anim::attachAnimators(registry_, cookCacheDir());  // clips resolved (InputError) before anything is built
  renderer_ = std::make_unique<render::Renderer>(ctx_);
  scene_ = std::make_unique<render::GpuScene>(ctx_, renderer_->pipelines(), renderer_->samplers(), cookCacheDir());
  scene_->load(registry_);
  checkLightCapacity();
  for (const gi::Technique* t : gi::techniques()) slots_.push_back({t, false, nullptr});
  syncTechniques();
}

// The lighting pass holds the frame's lights and shadow matrices in uniform blocks of fixed size
// (engine/render/gpu_types.hpp: kMaxLights, kMaxShadowLayers; a point light with shadows takes 6
// layers). A level over that is bad input, said here, before anything renders (extract() is const:
// this frame-0 world is thrown away).
void Session::checkLightCapacity() {
  scene::transformSystem(registry_);
  render::RenderWorld first;
  scene_->extract(registry_, level_, {}, first);
  if (first.lights.size() <= render::kMaxLights && first.shadowLayers.size() <= render::kMaxShadowLayers) return;
  throw InputError(level_.source.string() + ": /entities: " + std::to_string(first.lights.size()) + " lights with " +
                   std::to_string(first.shadowLayers.size()) + " shadow layers (expected at most " +
                   std::to_string(render::kMaxLights) + " lights and " + std::to_string(render::kMaxShadowLayers) +
                   " shadow layers; a point light with shadows takes 6, a spot 1)");
}

void Session::syncTechniques() {
  bool built = false;
  for (Slot& slot : slots_) {
    if (slot.tried || !level_.effects.has(slot.technique->effect())) continue;
    slot.tried = true;
    const gi::LevelContext lc{level_, registry_, cookCacheDir()};
    if (const auto note = gi::effectNote(*slot.technique, lc)) {
      notes_.push_back(*note);
      gi::printNoteOnce(*note);
      continue;
    }
    gi::SessionContext sc{ctx_, *renderer_, registry_, level_, cookCacheDir(), services_};
    slot.runtime = slot.technique->create(sc);
    built = built || slot.runtime;
  }
  if (!built) return;
  // Nodes run in table order (a later node may read what an earlier one published): re-register
  // them all when one is added after others.
  for (const Slot& slot : slots_)
    if (slot.runtime) renderer_->setNode(std::string(slot.technique->name()), {});
  for (const Slot& slot : slots_)
    if (slot.runtime) renderer_->setNode(std::string(slot.technique->name()), slot.runtime->node());
}

std::string Session::whyCannotRun(scene::Effect e) {
  const gi::Technique* technique = gi::findTechnique(e);
  if (technique == nullptr) return {};
  const gi::LevelContext lc{level_, registry_, cookCacheDir()};
  return gi::effectNote(*technique, lc).value_or(std::string());
}

bool Session::runs(scene::Effect e) const {
  if (e == scene::Effect::Direct || e == scene::Effect::Shadows) return true;
  for (const Slot& slot : slots_)
    if (slot.technique->effect() == e) return slot.runtime != nullptr;
  return false;
}

scene::EffectSet Session::runningEffects() const {
  scene::EffectSet out;
  for (int i = 0; i < scene::kEffectCount; ++i)
    if (level_.effects.has(scene::Effect(i)) && runs(scene::Effect(i))) out.add(scene::Effect(i));
  return out;
}

gi::TechniqueRuntime* Session::technique(std::string_view name) {
  for (Slot& slot : slots_)
    if (slot.technique->name() == name) return slot.runtime.get();
  return nullptr;
}

gi::dnrt::Runtime* Session::dnrt() {
  auto* s = technique<gi::dnrt::SessionRuntime>("dnrt");
  return s ? &s->runtime() : nullptr;
}

std::vector<std::string> Session::profileLines() const {
  std::vector<std::string> lines;
  for (const Slot& slot : slots_)
    if (slot.runtime && level_.effects.has(slot.technique->effect()))
      for (auto& line : slot.runtime->profileLines()) lines.push_back(std::move(line));
  return lines;
}

Session::~Session() {
  if (renderer_) renderer_->frames().waitIdle();
  for (auto it = slots_.rbegin(); it != slots_.rend(); ++it) it->runtime.reset();  // later ones use earlier ones' Services
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
  const gi::FrameUpdate frame{registry_, t};
  for (Slot& slot : slots_)
    if (slot.runtime && level_.effects.has(slot.technique->effect())) slot.runtime->update(frame);
}

void Session::extractOnly(VkExtent2D extent, std::uint32_t shadowResolution) {
  scene_->extract(registry_, level_, {extent, shadowResolution}, world_);
}

void Session::render(gpu::Presenter& presenter, const render::FrameSettings& settings) {
  syncTechniques();
  extractOnly(presenter.extent(), settings.shadowResolution);
  renderer_->render(world_, presenter, settings);
}

}  // namespace bounce::game
