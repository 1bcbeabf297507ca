#include "engine/gi/dnrt/runtime.hpp"

#include <algorithm>

#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/object_scene.hpp"

namespace bounce::gi::dnrt {

Runtime::Runtime(gpu::Context& ctx, const render::Pipelines& pipelines, ecs::Registry& registry,
                 const ref::ReferenceAssets& assets, const std::filesystem::path& cacheDir,
                 std::uint32_t framesInFlight, glm::vec3 background)
    : ctx_(ctx), assets_(assets), cacheDir_(cacheDir), registry_(registry), background_(background) {
  incident_.setIndirect(&background_);
  std::vector<ecs::Entity> entities;
  registry.view<scene::Dnrt, scene::MeshRef>().each([&](ecs::Entity e, scene::Dnrt&, scene::MeshRef&) {
    entities.push_back(e);
  });
  std::sort(entities.begin(), entities.end());  // deterministic order (ecs::Entity orders by index)
  for (ecs::Entity e : entities) {
    Object o;
    o.entity = e;
    const auto* name = registry.tryGet<scene::Name>(e);
    o.name = name ? name->id : std::to_string(e.index());
    bool cached = false;
    o.field = bakeCached(objectScene(registry, e, assets), settingsFrom(registry.get<scene::Dnrt>(e)), cacheDir, &cached);
    baked_ += cached ? 0 : 1;
    o.textures = std::make_unique<FieldTextures>(ctx, o.field, o.name);
    if (!registry.get<scene::Dnrt>(e).lightsInAntiRadiance) addOcclusion(o);
    objects_.push_back(std::move(o));
  }
  node_ = std::make_unique<Node>(ctx, pipelines, framesInFlight);
}

void Runtime::addOcclusion(Object& o) {
  FieldSettings s = o.field.settings;
  s.occlusionOnly = true;
  bool cached = false;
  o.occlusion = bakeCached(objectScene(registry_, o.entity, assets_), s, cacheDir_, &cached);
  baked_ += cached ? 0 : 1;
  o.occlusionTextures = std::make_unique<FieldTextures>(ctx_, *o.occlusion, o.name + ".occlusion");
}

void Runtime::excludeLightsFromAntiRadiance() {
  for (Object& o : objects_)
    if (!o.occlusionTextures) addOcclusion(o);
}

bool Runtime::lightsExcludedFromAntiRadiance() const {
  return std::all_of(objects_.begin(), objects_.end(), [](const Object& o) { return o.occlusionTextures != nullptr; });
}

void Runtime::setIrradianceSource(const IrradianceSource* source) {
  incident_.setIndirect(source ? source : &background_);
}

render::Renderer::GraphNode Runtime::node() {
  return [this](rg::RenderGraph& graph, render::PassContext& pc) {
    node_->addTo(graph, pc, objectsFor(*pc.world), settings_);
  };
}

}  // namespace bounce::gi::dnrt
