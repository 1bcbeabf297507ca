#include "engine/gi/dnrt/runtime.hpp"

#include <algorithm>

#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/object_scene.hpp"

namespace bounce::gi::dnrt {

Runtime::Runtime(gpu::Context& ctx, const render::Pipelines& pipelines, ecs::Registry& registry,
                 const ref::ReferenceAssets& assets, const std::filesystem::path& cacheDir,
                 std::uint32_t framesInFlight, glm::vec3 background)
    : registry_(registry), background_(background) {
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
    const scene::Dnrt& component = registry.get<scene::Dnrt>(e);
    const ref::SceneDesc object = objectScene(registry, e, assets);
    const FieldSettings settings = settingsFrom(component);
    int baked = 0;
    CachedFields fields = bakeCachedFor(object, settings, component.lightsInAntiRadiance, cacheDir, &baked);
    baked_ += std::size_t(baked);
    o.field = std::move(fields.field);
    o.occlusion = std::move(fields.occlusion);
    if (o.occlusion) o.occlusionTextures = std::make_unique<FieldTextures>(ctx, *o.occlusion, o.name + ".occlusion");
    o.textures = std::make_unique<FieldTextures>(ctx, o.field, o.name);
    objects_.push_back(std::move(o));
  }
  node_ = std::make_unique<Node>(ctx, pipelines, framesInFlight);
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
