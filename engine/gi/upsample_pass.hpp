#pragma once
// The second step of a deferred GI term shaded at half or quarter resolution (gi/resolution.hpp),
// shared by DNRT ("dnrt.upsample", the level's "dnrt": {"resolution"}) and RTF ("rtf.upsample",
// "rtf": {"resolution"}): the technique's draws wrote its term without ρ_r into a reduced target
// (⌈size/step⌉, G-buffer pixel step·j at sample j, cleared to 0); this full-screen pass blends the 4
// nearest samples of every pixel with the depth- and normal-aware weights SL's upsample uses
// (shaders/common/upsample.glsl, C++ reference gi/upsample.hpp) and adds ρ_r times the blend to
// "lighting.hdr" (shaders/passes/reduced_upsample.frag). One pass whichever technique: the same
// shader, one pipeline per step made on first use.
#include <array>
#include <cstdint>
#include <string>

#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"
#include "engine/render/pipelines.hpp"

namespace bounce::gi {

class ReducedUpsample {
 public:
  // `name`: the pass ("dnrt.upsample", "rtf.upsample"); its pipelines are "<name>.step2" / ".step4".
  ReducedUpsample(gpu::Context& ctx, const render::Pipelines& shared, std::string name);
  // Adds the pass: reads the G-buffer and `reduced` (written at `step`, 2 or 4), puts back
  // "lighting.hdr".
  void addTo(rg::RenderGraph& graph, const render::PassContext& pc, rg::Handle<rg::Texture> reduced, std::uint32_t step);

 private:
  const gpu::Pipeline& pipeline(std::uint32_t step);

  gpu::Context& ctx_;
  std::string name_;
  gpu::DescriptorSetLayout inputs_;  // G-buffer albedo, normal, depth and the reduced target
  gpu::PipelineLayout layout_;
  gpu::ShaderModule vert_, frag_;        // made on first use
  std::array<gpu::Pipeline, 2> steps_;  // index: step 2, 4
};

}  // namespace bounce::gi
