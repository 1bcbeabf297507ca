#pragma once
// DNRT for one level, end to end: bakes (through the cache) a field for every entity with a `dnrt`
// component and a mesh, uploads it, and each frame packs the visible ones (§5.2.1: placement,
// c_j at o rotated into the object's frame) for the node. c_j come from the incident-light service
// (engine/gi/incident): the indirect source's radiance SH at o plus the frame's lights projected at
// o (a cap over the object's bounding sphere, visibility from setLightVisibility). What a session
// does to enable DNRT:
//
//   gi::dnrt::Runtime dnrt(ctx, renderer.pipelines(), registry, assets, cacheDir, framesInFlight);
//   dnrt.setIrradianceSource(&probeVolume);                  // optional; default: the background
//   dnrt.setLightVisibility(&staticSceneRays);               // optional; default: lights unoccluded
//   renderer.setNode("dnrt", dnrt.node());                   // runs only when effects name dnrt
//
// Objects count as visible when the frame draws them (RenderWorld::draws names their entity).
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/ecs/registry.hpp"
#include "engine/gi/dnrt/irradiance_source.hpp"
#include "engine/gi/dnrt/node.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/render/renderer.hpp"

namespace bounce::gi::dnrt {

// One object's eligibility for the fused term (Runtime::addFused): in the fused mode (`mode` after
// NodeSettings::mode's override), no intrusion map, and its entity id + 1 (`entityId1`, 0 = none)
// fits the G-buffer normal's w, where probes.frag's self test reads it (render::kEntityInNormalMax).
bool fusedEligible(Mode mode, bool intrusion, std::uint32_t entityId1);

class Runtime {
 public:
  // `assets` must have loaded the registry's MeshRefs. `background`: the uniform radiance used as
  // c_j source until setIrradianceSource() names another (a level's "background").
  Runtime(gpu::Context& ctx, const render::Pipelines& pipelines, ecs::Registry& registry,
          const ref::ReferenceAssets& assets, const std::filesystem::path& cacheDir, std::uint32_t framesInFlight,
          glm::vec3 background = glm::vec3(0.0f));

  // Where c_j come from (not owned; must outlive the runtime); null restores the background.
  void setIrradianceSource(const IrradianceSource* source);
  // An object whose `dnrt` says "lights_in_anti_radiance": false (meant with "probes": {"relight":
  // true}) leaves the lights out of its anti-radiance: their occlusion is drawn elsewhere (the direct
  // pass's shadow maps; the relit probes carry its bounce), so its anti-radiance subtracts only the
  // indirect source's light. The paper's Eq. 11 subtracts L_init, all the light arriving through the
  // object; a light's share of it is already missing behind the object in this renderer (shadow
  // maps), so subtracting it again counts the shadow twice, smeared by the SH over pixels the object
  // does not shadow (README "DNRT with the relit probes, session 10"). The constructor bakes (through
  // the cache, from the same rays as the field: bakeCachedWithOcclusion) the object's occlusion-only
  // field (FieldSettings::occlusionOnly, −k_j) and objectsFor adds per frame Σ_j (−c_j^lights) (−k_j):
  //   L_DNRT = ρ (n_o·n_r)₊ [Σ_j c_j (t_j − k_j) + Σ_j c_j^lights k_j],  c_j = c_j^indirect + c_j^lights.
  // (No call switches it for every object: the level's key is the one switch; tests set it there.)
  // How much of an object sees each light (not owned; null: every light fully visible).
  void setLightVisibility(const incident::Visibility* visibility) { incident_.setVisibility(visibility); }
  // c_j's source for one object: the radiance SH arriving at its bounding sphere (centre, radius
  // in world units), world axes, before convolution and rotation.
  // `window`: per-band factors on the lights' part (incident.hpp BandWindow); `lightsPart`
  // (optional): the lights' part alone. objectsFor gets every object's c_j through it, and tests
  // call it to compute the c_j a frame used.
  incident::RadianceSH incidentSH(glm::vec3 centre, float radius, std::span<const render::LightGpu> lights,
                                  const incident::BandWindow& window = incident::kNoWindow,
                                  incident::RadianceSH* lightsPart = nullptr) const;
  NodeSettings& settings() { return settings_; }
  std::size_t objectCount() const { return objects_.size(); }
  const Field& field(std::size_t i) const { return objects_[i].field; }
  ecs::Entity entity(std::size_t i) const { return objects_[i].entity; }
  // Baked this run (the others came from the cache).
  std::size_t bakedCount() const { return baked_; }

  // The frame's visible objects, packed for the node (textures owned by this runtime).
  std::vector<NodeObject> objectsFor(const render::RenderWorld& world) const;
  // For Renderer::setNode("dnrt", …): adds the node for the visible objects of the frame (but the
  // one addFused gave the probes pass this frame).
  render::Renderer::GraphNode node();
  // The fused mode ("dnrt": {"mode": "fused"}, or NodeSettings::mode), for
  // probes::ProbeNode::setFusedDnrt: called while the probes node adds its pass (before this runtime's
  // node, table order). It takes every visible object in that mode that has no intrusion and whose
  // entity id + 1 fits the normal's w (the self test there), up to kClusterBatch; node() then leaves
  // them out. One object: its record in the push block (Node::addFused, probes.frag kDnrt 1), and
  // below full resolution (settings().step 2, 4) its term's position-only factor from pass
  // dnrt.fused.reduced. Two or more: the clustered visit of the pixel's tile mask (Node::addFusedCluster,
  // kDnrt 2), always at full resolution (the level load warns when the level asks for less:
  // technique.cpp). Nothing when the frame's effects do not name dnrt or no object qualifies; without
  // the probes effect this is never called and node() draws fused objects as boxes.
  std::optional<probes::FusedDnrt> addFused(rg::RenderGraph& graph, const render::PassContext& pc);
  // The names of the objects addFused would take were all of them visible (its rule, fusedEligible,
  // and its cap of kClusterBatch); the level load warns from this list (technique.cpp), so the warning
  // and the frame apply one rule.
  std::vector<std::string> fusedEligibleNames() const;

 private:
  struct Object {
    ecs::Entity entity;
    std::string name;
    Field field;
    std::unique_ptr<FieldTextures> textures;
    // "lights_in_anti_radiance": false: the occlusion-only field (−k_j) and its textures.
    std::optional<Field> occlusion;
    std::unique_ptr<FieldTextures> occlusionTextures;
  };
  ecs::Registry& registry_;
  ConstantEnvironment background_;
  incident::Service incident_;
  NodeSettings settings_;
  std::vector<Object> objects_;
  std::unique_ptr<Node> node_;
  std::size_t baked_ = 0;
  // This frame's objects when addFused took some (`fused[i]`: object i is in the probes pass), for
  // node() in the same frame.
  struct FusedFrame {
    std::vector<NodeObject> objects;
    std::vector<bool> fused;
  };
  std::optional<FusedFrame> fusedFrame_;
};

}  // namespace bounce::gi::dnrt
