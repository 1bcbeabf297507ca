#pragma once
// Screen-space ambient occlusion baselines, the DNRT paper's comparison points (§6.4): SSAO
// (normal-oriented hemisphere kernel, shaders/ao/ssao.frag) and HBAO (Bavoil et al. 2008,
// shaders/ao/hbao.frag). Each reads "gbuffer.depth" and "gbuffer.normal" and writes its own R16F
// visibility image (1 = unoccluded), published as "ao.ssao" / "ao.hbao" and as "ao.term" (the last
// one added), the blackboard name an indirect-lighting node multiplies its term by. The image is
// persistent and marked as a graph output, so the pass runs (and is timed) even before an
// indirect node reads it, and tests read it back.
#include <memory>

#include "engine/gi/technique.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"
#include "engine/render/renderer.hpp"

namespace bounce::gi::ao {

enum class Kind { Ssao, Hbao };
const char* kindName(Kind k);  // "ssao" / "hbao": effect, pass and blackboard name

struct Settings {
  float radius = 0.1f;   // metres: the neighbourhood that can occlude
  float bias = 0.01f;    // SSAO: metres of depth; HBAO: sine of the angle above the tangent plane
  std::uint32_t samples = 16;    // SSAO kernel size; HBAO steps per direction
  std::uint32_t directions = 8;  // HBAO only
};

class Node final : public TechniqueRuntime {
 public:
  Node(gpu::Context& ctx, const render::Pipelines& shared, Kind kind, Settings settings = {});
  Kind kind() const { return kind_; }
  Settings& settings() { return settings_; }
  // For Renderer::setNode(kindName(kind), …).
  render::Renderer::GraphNode node() override;
  // The visibility image of the last frame (R16F; read back with gpu::readback after the frame).
  gpu::Image* image() { return image_.get(); }

 private:
  void addTo(rg::RenderGraph& graph, render::PassContext& pc);
  gpu::Context& ctx_;
  Kind kind_;
  Settings settings_;
  gpu::DescriptorSetLayout inputLayout_;
  gpu::PipelineLayout layout_;
  gpu::Pipeline pipeline_;
  std::unique_ptr<gpu::Image> image_;
};

}  // namespace bounce::gi::ao
