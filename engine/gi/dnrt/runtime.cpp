#include "engine/gi/dnrt/runtime.hpp"

#include <algorithm>

#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"  // kEntityInNormalMax

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
    std::vector<NodeObject> objects;
    if (fusedFrame_) {  // the probes pass adds that one's term
      objects = std::move(fusedFrame_->objects);
      objects.erase(objects.begin() + std::ptrdiff_t(fusedFrame_->fused));
    } else {
      objects = objectsFor(*pc.world);
    }
    fusedFrame_.reset();
    node_->addTo(graph, pc, std::move(objects), settings_);
  };
}

std::optional<probes::FusedDnrt> Runtime::addFused(rg::RenderGraph& graph, const render::PassContext& pc) {
  fusedFrame_.reset();
  if (!pc.world->has("dnrt")) return std::nullopt;
  const auto modeOf = [&](Mode m) { return settings_.mode.value_or(m); };
  // objectsFor (c_j per object) only when some object asks for the mode.
  const bool any = std::any_of(objects_.begin(), objects_.end(), [&](const Object& o) {
    const auto* c = registry_.tryGet<scene::Dnrt>(o.entity);
    return modeOf(c ? c->mode : Mode::Box) == Mode::Fused;
  });
  if (!any) return std::nullopt;
  std::vector<NodeObject> objects = objectsFor(*pc.world);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const NodeObject& o = objects[i];
    if (modeOf(o.mode) != Mode::Fused || o.intrusion || o.data.ids.x == 0u || o.data.ids.x > render::kEntityInNormalMax)
      continue;
    // Below full resolution the term's position-only factor comes from pass dnrt.fused.reduced.
    probes::FusedDnrt fused = node_->addFused(graph, pc, o, settings_.step);
    fusedFrame_ = FusedFrame{std::move(objects), i};
    return fused;
  }
  return std::nullopt;
}

}  // namespace bounce::gi::dnrt
