#pragma once
// The RTF render-graph node (Pan et al. 2007 §5 on the GPU), two passes and, below full resolution, a third:
//  "rtf.bounce"  compute, a side-effect pass: per object (scope "rtf.bounce/<name>") the ξ caches of
//                Eq. 11–12 from the proxies' light of the frame's bouncing step (xi_pass.hpp), into
//                the object's ξ image;
//  "rtf"         deferred shading, additive into "lighting.hdr": per object (scope "rtf/<name>") its
//                field's sphere of radius (outer + Δr)·η is covered by a camera-facing octagon
//                (rtf.vert: no depth test, no culling) and every covered receiver pixel gets ρ/π·E_n of the Eq. 10 lookup of ξ
//                (the interreflected light) minus ρ/π·E_n((1 − V) ⊙ L) (the indirect light the
//                object's OOF blocks), shaders/rtf/rtf.frag. The object's own pixels skip its field.
//  "rtf.upsample" only below full resolution (addTo's `step`, the level's "rtf": {"resolution"}): the
//                draws above then shade one G-buffer pixel in step² into the transient "rtf.half" /
//                "rtf.quarter" (⌈size/step⌉, cleared) without ρ, and this full-screen pass adds ρ times
//                its depth- and normal-aware upsample to "lighting.hdr" (gi/upsample_pass.hpp).
// Reads "gbuffer.albedo", "gbuffer.normal", "gbuffer.depth", "gbuffer.entity"; puts back "lighting.hdr".
// No object: no pass.
#include <memory>
#include <string>
#include <vector>

#include "engine/gi/rtf/update.hpp"
#include "engine/gi/rtf/xi_pass.hpp"
#include "engine/gi/upsample_pass.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"

namespace bounce::gi::rtf {

struct NodeObject {
  XiPass* xi = nullptr;               // the object's field on the GPU (outlives the frame)
  std::vector<glm::vec3> proxyLight;  // m·16 RGB, object frame: this frame's bouncing step
  RtfObjectGpu record{};              // packObject()
  std::string name;                   // timestamp scopes "rtf/<name>", "rtf.bounce/<name>"
  std::vector<glm::vec4> blockedScale;  // per sample (XiPass::setBlockedScale); empty: the light at o
  std::vector<float> onObjects;         // per sample, w for receivers on an rtf object (XiPass::setBlockedScale); empty: blockedScale's w
};

class Node {
 public:
  Node(gpu::Context& ctx, const render::Pipelines& shared, std::uint32_t framesInFlight);
  // `step`: G-buffer pixels per shaded sample along each axis, 1 (full), 2 (half) or 4 (quarter).
  void addTo(rg::RenderGraph& graph, const render::PassContext& pc, std::vector<NodeObject> objects,
             std::uint32_t step = 1);

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSetLayout inputLayout_, objectLayout_;
  gpu::PipelineLayout layout_;
  // rtf.frag's variant: sh 9 or 4 (kSh9), the self test on the normal's w or on gbuffer.entity
  // (kSelfInNormal), step 1, 2 or 4 (kStep); made on first use.
  const gpu::Pipeline& pipeline(bool sh4, bool entity, std::uint32_t step);
  gpu::ShaderModule vert_, frag_;
  gpu::Pipeline pipelines_[2][2][3];  // [sh 4][entity][step 1, 2, 4]
  gi::ReducedUpsample upsample_;      // "rtf.upsample"
  std::vector<gpu::Buffer> records_;  // per frame slot, RtfObjectGpu at kRtfObjectStride
};

}  // namespace bounce::gi::rtf
