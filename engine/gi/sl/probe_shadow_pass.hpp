#pragma once
// Pass "sl.shadow" (issue 13, pass 2's "dynamic objects' soft shadows on the probes' indirect
// light"): a full-screen triangle adds ρ/π · ao · ΔE to "lighting.hdr" per G-buffer pixel
// (shaders/sl/probe_shadow.frag; ΔE ≤ 0 from sl/probe_shadow.glsl, whose C++ reference is
// sl::probeShadow). It runs when the probes pass runs in the same frame (their light is what it
// shadows) and reads the SLs from the SL node's ShadeData, so the blockers are the same spheres,
// receiver rules and influence as the SLs' own light. It owns a device copy of the probe volume
// (probes::uploadSh/uploadMoments: the layout probes/probe_sh.glsl reads).
#include <memory>

#include "engine/gi/probes/probe_volume.hpp"
#include "engine/gi/sl/shade.hpp"
#include "engine/gpu/image.hpp"
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"

namespace bounce::gi::sl {

class ProbeShadowPass {
 public:
  // `volume` (not owned) must outlive the pass; order, blocking, spheres and influence as the
  // SL pass's pipeline (ShadeData::specialization).
  ProbeShadowPass(gpu::Context& ctx, const render::Pipelines& shared, const probes::ProbeVolume& volume, int order,
                  Blocking blocking, std::uint32_t spheres, float influence);
  // Adds the pass when "probes" runs this frame; `shade` and `intensity` as the SL pass binds them.
  void addTo(rg::RenderGraph& graph, const render::PassContext* pc, const ShadeData& shade, const gpu::Buffer& intensity);

 private:
  gpu::Context& ctx_;
  const probes::ProbeVolume& volume_;
  std::unique_ptr<gpu::Image> sh_, moments_;
  gpu::DescriptorSetLayout inputLayout_;
  gpu::PipelineLayout layout_;
  gpu::Pipeline pipeline_;
};

}  // namespace bounce::gi::sl
