#pragma once
// Pass "sl.local" (issue 13 item 4, §7.3: the level's point and spot lights as SLs of their own
// radius; level key "sl": {"local_lights": true}): per G-buffer pixel of the SL tiles, adds
// −ρ/π · Σ_i E_i (n·l_i)₊ V_i (1 − v_i) to "lighting.hdr" (shaders/sl/local_light.frag), v_i the SLs'
// visible fraction of light i's sphere (sl/local_light.glsl; C++ reference sl::localLightVisibility).
// The lighting pass's shadow map holds no SL object for these lights (DrawItem::slLocal), so the sum
// is E·V_static·v: the objects' shadow once, soft. Runs after "sl" at full resolution (also when "sl"
// is at half: this term has no upsample), drawn as the SL pass's tiles: a tile no SL's influence
// bound reaches gets no SL shadow (every SL is culled there, v = 1).
#include "engine/gi/sl/probe_shadow_pass.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/gpu/image.hpp"
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"

namespace bounce::gi::sl {

class LocalLightPass {
 public:
  // Order, blocking, spheres and influence as the SL pass's pipeline (ShadeData::specialization).
  LocalLightPass(gpu::Context& ctx, const render::Pipelines& shared, int order, Blocking blocking, std::uint32_t spheres,
                 float influence);
  // Blends into "lighting.hdr" and publishes it; `tiles` in full-resolution pixels.
  void addTo(rg::RenderGraph& graph, const render::PassContext* pc, const ShadeData& shade, const gpu::Buffer& intensity,
             TileRange tiles);

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSetLayout inputLayout_;
  gpu::PipelineLayout layout_;
  gpu::Pipeline pipeline_;
};

}  // namespace bounce::gi::sl
