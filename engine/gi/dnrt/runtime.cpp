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

namespace {
// Put on the graph's blackboard by addFused: the graph is built anew every frame, so node() finds
// it only in the frame whose probes node took the object. A frame that threw between the probes
// node and DNRT's leaves fusedFrame_ set, and the next frame may have no probes pass.
constexpr const char* kFusedThisFrame = "dnrt.fused.volume";
}  // namespace

render::Renderer::GraphNode Runtime::node() {
  return [this](rg::RenderGraph& graph, render::PassContext& pc) {
    std::vector<NodeObject> objects;
    if (fusedFrame_ && graph.blackboard().contains(kFusedThisFrame)) {  // the probes pass adds those objects' terms
      for (std::size_t i = 0; i < fusedFrame_->objects.size(); ++i)
        if (!fusedFrame_->fused[i]) objects.push_back(std::move(fusedFrame_->objects[i]));
    } else {
      objects = objectsFor(*pc.world);
    }
    fusedFrame_.reset();
    node_->addTo(graph, pc, std::move(objects), settings_);
  };
}

bool fusedEligible(Mode mode, bool intrusion, std::uint32_t entityId1) {
  return mode == Mode::Fused && !intrusion && entityId1 != 0u && entityId1 <= render::kEntityInNormalMax;
}

std::vector<std::string> Runtime::fusedEligibleNames() const {
  std::vector<std::string> names;
  for (const Object& o : objects_) {
    const auto* c = registry_.tryGet<scene::Dnrt>(o.entity);
    if (!c || names.size() == kClusterBatch) continue;
    if (fusedEligible(settings_.mode.value_or(c->mode), c->intrusion, o.entity.index() + 1u)) names.push_back(o.name);
  }
  return names;
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
  // The visible objects in the mode that qualify, up to one clustered batch (the rest: boxes).
  std::vector<std::size_t> chosen;
  for (std::size_t i = 0; i < objects.size() && chosen.size() < kClusterBatch; ++i) {
    const NodeObject& o = objects[i];
    if (!fusedEligible(modeOf(o.mode), o.intrusion, o.data.ids.x)) continue;
    chosen.push_back(i);
  }
  if (chosen.empty()) return std::nullopt;
  std::vector<bool> fused(objects.size(), false);
  std::optional<probes::FusedDnrt> out;
  if (chosen.size() == 1) {  // one object: its record in the push block, no loop (probes.frag kDnrt 1)
    // Below full resolution the term's position-only factor comes from pass dnrt.fused.reduced.
    out = node_->addFused(graph, pc, objects[chosen[0]], settings_.step, settings_.splitProbes);
    fused[chosen[0]] = true;
  } else {
    // Several: the clustered visit of the pixel's tile (kDnrt 2), at full resolution whatever
    // settings_.step asks (the reduced factor is one object's; SessionRuntime warns at level load).
    std::vector<NodeObject> subset;
    for (std::size_t i : chosen) subset.push_back(objects[i]);
    std::vector<bool> taken;
    out = node_->addFusedCluster(graph, pc, subset, settings_.tileCull, taken);
    for (std::size_t k = 0; k < chosen.size(); ++k) fused[chosen[k]] = taken[k];
  }
  if (out) {
    graph.blackboard().put(kFusedThisFrame, out->volume);
    fusedFrame_ = FusedFrame{std::move(objects), std::move(fused)};
  }
  return out;
}

}  // namespace bounce::gi::dnrt
