#pragma once
// The SL render-graph node: two passes per frame, three at half or quarter resolution.
//  "sl.intensity" (compute, pass 1, §5.1): every SL's intensity SH from the level's lights (with the
//     shadow atlas when `shadows` runs) and the probes' light at its samples (IntensityPass);
//  "sl" (fragment, pass 2, §5.2): adds ρ/π · Σ L̃ Ṽ to "lighting.hdr" per G-buffer pixel
//     (shaders/sl/sl.frag), reading "gbuffer.albedo", "gbuffer.normal", "gbuffer.depth" from the
//     blackboard. Drawn as 16×16 tiles: only the tiles some SL's influence bound covers, each pixel
//     visiting only its tile's SLs (tiles.hpp, shaders/sl/tiles.vert); with per-object blocking the
//     tiles of one object's SLs are drawn first, by a pipeline without the closer objects' exp;
//  at Resolution::Half (Quarter), "sl" writes E at every second (fourth) G-buffer pixel per axis
//     into the transient "sl.half" ("sl.quarter"; RGBA16F, resolution.hpp) and "sl.upsample"
//     (shaders/sl/upsample.frag, the same step) adds the depth- and normal-weighted upsample times
//     ρ/π to "lighting.hdr".
//  "sl.hierarchy" (compute, §7.3 Eq. 25, with `hierarchy`: one parent SL per set, hierarchy.hpp):
//     per drawn tile of "sl" the ratio t per object at the tile's centre (hierarchy_ratio.comp), read
//     by "sl" (sl_hierarchy.frag: Eq. 26's parent term) — the parents' spheres per frame on the CPU
//     (update.hpp parentSpheres), their intensity at the end of "sl.intensity" (IntensityPass
//     parents), their tiles by their own influence ball F·r_P;
//  "sl.local" (fragment, §7.3, when `localLights`): the SLs' soft shadows on the level's point and
//     spot lights (LocalLightPass), drawn as the full-resolution tiles, last;
//  "sl.shadow" (fragment, pass 2's shadow on the probes' light): when the probes' light is given and
//     the probes pass runs, the SLs' soft shadow on it (ProbeShadowPass), drawn as the same tiles;
//     at a reduced resolution into "sl.half" / "sl.quarter" before the upsample.
// Each is timed under its own name by the graph. Pass 2 shades every SL of every object in one pass
// (the blocking couples objects: an object's Ṽ needs the closer objects' logs), so there are no
// per-object rows. Per frame slot the node owns its own pass-1 buffers, pass-2 sphere block and tile
// list, so a frame in flight never sees the next one's data.
#include <memory>
#include <span>
#include <vector>

#include "engine/gi/incident/incident.hpp"
#include "engine/gi/sl/evaluate.hpp"
#include "engine/gi/sl/intensity.hpp"
#include "engine/gi/sl/local_light_pass.hpp"
#include "engine/gi/sl/probe_shadow_pass.hpp"
#include "engine/gi/resolution.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"

namespace bounce::gi::probes {
class RelightPass;
}

namespace bounce::gi::sl {

class Node {
 public:
  // `sets` (not owned, must outlive the node) in participant order; `order` ≥ every set's order;
  // `influence`: evaluate.hpp rule 0's F (0: off); `probes` (not owned, may be empty: no
  // "sl.shadow"): the probes' baked volume and the probes node's device images of it.
  Node(gpu::Context& ctx, const render::Pipelines& shared, std::uint32_t framesInFlight,
       std::span<const SphereSet* const> sets, int order, Blocking blocking, float influence,
       Resolution resolution = Resolution::Full, ProbeLight probes = {}, bool localLights = false,
       bool hierarchy = false, bool fuse = true, std::uint32_t terms = 3u, bool blockedAtSphere = false,
       bool tileCut = true, bool blockedMap = false);
  // `tileCut` (scene::Sl::tileCut; true but in tests): without the hierarchy, "sl", "sl.shadow" and
  // the fused pass cut each tile's list by its receivers (cut_tiles.vert, shadow_cut_tiles.vert).
  // `blockedAtSphere` (level "blocked_light": "sphere", probe_shadow.hpp BlockedLight::Sphere): the
  // shadow on the probes' light reads the blocked light at each SL's centre (addTo's `indirect`);
  // with `blockedMap` (level "blocked_read": "map") from the direction maps blended there (addTo's
  // `maps`) instead of the SH.
  // `fuse` (level "fused", default true): with "sl.shadow" running and the hierarchy off, one pass
  // "sl" walks each tile's candidates once for both terms (ProbeShadowPass::addFused). `terms`
  // (scene::Sl::terms, a diagnostic): bit 0 the SLs' bounce E, bit 1 the shadow on the probes' light;
  // anything but both needs the fused pass.
  // This frame's SLs, concatenated over the sets: pose, object index, probes' SH at the centre.
  void addTo(rg::RenderGraph& graph, const render::PassContext& pc, std::span<const PosedSphere> posed,
             std::span<const std::uint32_t> objects, std::span<const incident::RadianceSH> indirect,
             std::span<const incident::DirectionMap> maps = {});
  std::uint32_t sphereCount() const { return spheres_; }
  bool hierarchy() const { return hierarchy_; }
  // Level `"probes": {"relight": true, "sl_bounce": true}`: each frame, after "sl.intensity", pass
  // "sl.relight_bounce" (shaders/sl/relight_bounce.comp) writes the posed SLs' irradiance at each of
  // `relight`'s surfels into relight.slBounce(), which the next "probes.relight" adds to the surfels'
  // ΔE (relight_pass.hpp setSlBounce). Not with `terms` lacking the bounce bit (those diagnostic rows
  // leave the SLs' bounce out, its 2nd+ bounces too), nor with local lights (relight carries none of
  // those objects' shadow). `relight` must outlive the node.
  void enableRelightBounce(probes::RelightPass& relight);

 private:
  struct Slot;
  // "sl.upsample" (half or quarter resolution): spreads `reducedE` ("sl.half" / "sl.quarter") over
  // "lighting.hdr", then "sl.local".
  void addUpsample(rg::RenderGraph& graph, const render::PassContext* pc, Slot& slot, rg::Handle<rg::Texture> reducedE,
                   std::uint32_t shadeTiles, std::uint32_t upsampleTiles);
  struct Slot {
    std::unique_ptr<IntensityPass> intensity;
    std::unique_ptr<ShadeData> shade;
    gpu::Buffer tiles;  // this frame's drawn tiles (tiles.hpp ShadeTile), host-visible
    gpu::Buffer ratios;  // hierarchy: Eq. 25's t, 4 vec4 per drawn tile of "sl" (device-local)
    gpu::Buffer shadowRatios;  // hierarchy: "sl.shadow"'s τ, the same layout
  };
  gpu::Context& ctx_;
  int order_;
  Blocking blocking_;
  float influence_ = 0.0f;
  Resolution resolution_ = Resolution::Full;
  std::uint32_t spheres_ = 0;
  std::vector<Slot> slots_;
  gpu::DescriptorSetLayout inputLayout_;
  gpu::PipelineLayout layout_;
  gpu::DescriptorSetLayout upsampleInputs_;  // at a reduced resolution only
  gpu::PipelineLayout upsampleLayout_;
  // vert_: the tiles as listed ("sl.upsample"); cutVert_: "sl" without the hierarchy, each tile's list cut
  // by its receivers' world box (shaders/sl/tiles.glsl slCutTile); hierarchyVert_: "sl" with the hierarchy.
  gpu::ShaderModule vert_, cutVert_, frag_, upsampleFrag_, hierarchyVert_;
  gpu::Pipeline pipeline_, upsample_;  // upsample_: at a reduced resolution only
  // Per-object blocking only: pass 2 for the tiles whose SLs all belong to one object (sl.frag
  // kSingleObject: no exp of closer objects, which is exp(0) there); pipeline_ draws the others.
  gpu::Pipeline singleObject_;
  std::unique_ptr<ProbeShadowPass> shadow_;
  std::unique_ptr<LocalLightPass> local_;  // "sl.local" (localLights): the lights' SL shadows
  std::vector<float> share_;  // per object (set): unionShare of its spheres, for "sl.shadow"
  std::vector<float> silhouette_;  // per object (set): its shadow scale (SlSphere::shadowScale)
  // §7.3 hierarchy (sl/hierarchy.glsl): the tile pass's layout and pipeline.
  bool hierarchy_ = false;
  bool tileCut_ = true;  // the constructor's tileCut, false with the hierarchy: cut_tiles.vert draws "sl"
  std::uint32_t terms_ = 3u;  // the constructor's `terms`: addTo refuses a partial mask unfused
  gpu::DescriptorSetLayout ratioInputs_;
  gpu::PipelineLayout ratioLayout_;
  gpu::Pipeline ratioPipeline_;
  // "sl.relight_bounce" (enableRelightBounce): relight's surfels as SL receivers.
  probes::RelightPass* relightBounce_ = nullptr;
  gpu::DescriptorSetLayout bounceInputs_;
  gpu::PipelineLayout bounceLayout_;
  gpu::Pipeline bouncePipeline_;
};

// Objects (sets) one hierarchy serves: sl/hierarchy.glsl kSlHierObjects.
inline constexpr std::uint32_t kMaxHierarchyObjects = 4;

}  // namespace bounce::gi::sl
