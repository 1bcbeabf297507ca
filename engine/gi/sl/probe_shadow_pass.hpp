#pragma once
// Pass "sl.shadow" (issue 13, pass 2's "dynamic objects' soft shadows on the probes' indirect
// light"): adds ρ/π · ao · ΔE to "lighting.hdr" per G-buffer pixel (shaders/sl/probe_shadow.frag;
// ΔE ≤ 0 from sl/probe_shadow.glsl, whose C++ reference is sl::probeShadow). It runs when the probes
// pass runs in the same frame (their light is what it shadows) and reads the SLs from the SL node's
// ShadeData, so the blockers are the same spheres, receiver rules and influence as the SLs' own light.
// Drawn as the SL pass's tiles (tiles.hpp, shaders/sl/tiles.vert): a tile no SL's influence bound
// reaches gets no shadow (every SL is culled there, so ΔE = 0), and each pixel visits only its
// tile's SLs. At half or quarter resolution it follows pass 2: ao · ΔE at G-buffer pixel step·j is
// added into "sl.half" / "sl.quarter" before "sl.upsample", which applies each full pixel's ρ/π.
// It binds the probes node's device images of the volume (gi::Services::probeSh / probeMoments:
// the layout probes/probe_sh.glsl reads); before, it uploaded a copy of its own.
#include "engine/gi/probes/probe_volume.hpp"
#include "engine/gi/resolution.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/gpu/image.hpp"
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/pass_context.hpp"

namespace bounce::gi::sl {

// The probes' light as sl.shadow reads it: their volume and its device images (not owned).
struct ProbeLight {
  const probes::ProbeVolume* volume = nullptr;
  const gpu::Image* sh = nullptr;
  const gpu::Image* moments = nullptr;
  explicit operator bool() const { return volume && sh && moments; }
};

// The tiles to draw: `count` ShadeTile records from `first` in `buffer` (tiles.hpp), in the target's
// pixels.
struct TileRange {
  const gpu::Buffer* buffer = nullptr;
  std::uint32_t first = 0;
  std::uint32_t count = 0;
};

class ProbeShadowPass {
 public:
  // `probes` (not owned) must outlive the pass; order, blocking, spheres and influence as the SL
  // pass's pipeline (ShadeData::specialization); `step` (resolution.hpp): 1 full resolution, 2 or 4:
  // write ao · ΔE at G-buffer pixel step·j into "sl.half" / "sl.quarter". `blockedAtSphere`
  // ("blocked_light": "sphere", probe_shadow.hpp BlockedLight::Sphere; not with the hierarchy): the
  // blocked light read from ShadeData's SlIndirect block: the SH, or with `blockedMap` ("blocked_read":
  // "map") the direction maps (ShadeData::setSpheres' `maps`). `tileCut` (Node's; ignored with the
  // hierarchy): each tile's list cut by its receivers (shaders/sl/shadow_cut_tiles.vert).
  ProbeShadowPass(gpu::Context& ctx, const render::Pipelines& shared, ProbeLight probes, int order, Blocking blocking,
                  std::uint32_t spheres, float influence, std::uint32_t step, bool hierarchy = false, bool fuse = false,
                  std::uint32_t terms = 3u, bool blockedAtSphere = false, bool tileCut = true, bool blockedMap = false);
  // Adds the pass when "probes" runs this frame; `shade` and `intensity` as the SL pass binds them.
  // Full resolution: blends into "lighting.hdr" and publishes it; half / quarter: into `reducedTarget`
  // ("sl.half" / "sl.quarter", which the SL pass cleared) and returns its new version. Returns
  // `reducedTarget` unchanged when it does not run.
  // With `hierarchy` (§7.3, sl/hierarchy_shadow.glsl): "sl.shadow.hierarchy" first writes each drawn
  // tile's τ into `ratios` (4 vec4 per tile, the frame slot's), which "sl.shadow" reads.
  rg::Handle<rg::Texture> addTo(rg::RenderGraph& graph, const render::PassContext* pc, const ShadeData& shade,
                                const gpu::Buffer& intensity, TileRange tiles,
                                rg::Handle<rg::Texture> reducedTarget = {}, const gpu::Buffer* ratios = nullptr);
  // One walk for "sl" and "sl.shadow" (shaders/sl/sl_shadow.frag; built with `fuse`, never with the
  // hierarchy): whether this frame draws the fused pass instead of the two (the probes run).
  bool fusesThisFrame(const render::PassContext* pc) const;
  // Adds pass "sl" with both terms: full resolution blends ρ/π (E + ao ΔE) into "lighting.hdr" and
  // publishes it; half / quarter creates "sl.half" / "sl.quarter" (cleared, `reducedExtent` texels)
  // with E + ao ΔE and returns it. `singleTiles`: the first tiles of `tiles` whose SLs are one
  // object's (per-object blocking, sl.frag kSingleObject).
  rg::Handle<rg::Texture> addFused(rg::RenderGraph& graph, const render::PassContext* pc, const ShadeData& shade,
                                   const gpu::Buffer& intensity, TileRange tiles, std::uint32_t singleTiles,
                                   glm::uvec2 reducedExtent);

 private:
  // "gbuffer.depth"'s read: the vertex stage too when the tiles are cut (slCutTile reads it there).
  rg::Usage depthUsage() const { return tileCut_ ? rg::Usage::SampledGraphics : rg::Usage::SampledFragment; }
  // Set 1 of sl.shadow and the fused pass (probe_shadow_frag.glsl's bindings), and their push block.
  VkDescriptorSet writeInputs(const render::PassContext* pc, const rg::PassResources& res, const render::DeferredInputs& g,
                              rg::Handle<rg::Texture> ao, const ShadeData& shade, const gpu::Buffer& intensity,
                              const gpu::Buffer& tiles, const gpu::Buffer* ratios) const;
  void push(VkCommandBuffer cmd, const gpu::Pipeline& pipeline, bool withAo, VkExtent2D extent) const;

  gpu::Context& ctx_;
  ProbeLight probes_;
  bool reduced_ = false;  // reduced resolution: half or quarter (step_ > 1)
  std::uint32_t step_ = 1;
  gpu::DescriptorSetLayout inputLayout_;
  gpu::PipelineLayout layout_;
  gpu::Pipeline pipeline_;
  gpu::Pipeline fused_, fusedSingle_;  // with `fuse`: sl_shadow.frag, kSingleObject off / on (per-object)
  bool hierarchy_ = false;
  bool tileCut_ = true;  // `tileCut` without the hierarchy: shadow_cut_tiles.vert reads the depth per tile
  gpu::DescriptorSetLayout ratioInputs_;
  gpu::PipelineLayout ratioLayout_;
  gpu::Pipeline ratioPipeline_;
};

}  // namespace bounce::gi::sl
