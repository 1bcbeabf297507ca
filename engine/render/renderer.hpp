#pragma once
// Renderer: builds a render graph each frame from the RenderWorld and the level's effects,
// compiles it (cull, order, barriers, transients), executes it on Vulkan and hands the display
// image to a presenter. The graph holds a pass only for what the frame calls for: no `shadows`
// effect or no shadow-casting light → no shadow pass (DESIGN.md "simulate only the effects a scene
// calls for"); a debug view replaces lighting + tonemap.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/gpu/frames.hpp"
#include "engine/gpu/presenter.hpp"
#include "engine/render/graph/render_graph.hpp"
#include "engine/render/pass_context.hpp"
#include "engine/render/pipelines.hpp"
#include "engine/render/render_world.hpp"
#include "engine/render/vk_backend.hpp"

namespace bounce::render {

enum class DebugView { None = 0, Albedo = 1, Normal = 2, Depth = 3, Shadow = 4, EntityId = 5 };
const char* debugViewName(DebugView v);

struct FrameSettings {
  DebugView debugView = DebugView::None;
  float exposure = 1.0f;        // linear scale before tonemapping
  bool culling = true;          // off: every pass runs (debugging the graph)
  std::uint32_t shadowResolution = 1024;
  bool keepHdr = false;         // mark the HDR target as an output (captures read it back)
};

class Renderer {
 public:
  explicit Renderer(gpu::Context& ctx, std::uint32_t framesInFlight = gpu::FrameRing::kDefaultFramesInFlight);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const Pipelines& pipelines() const { return *pipelines_; }
  gpu::SamplerCache& samplers() { return *samplers_; }
  gpu::FrameRing& frames() { return *frames_; }
  // The graph's Vulkan backend (tests: transient pooling, VkBackend::createdImages()).
  const VkBackend& backend() const { return *backend_; }

  // Records and submits one frame through `presenter` (which decides the size).
  void render(const RenderWorld& world, gpu::Presenter& presenter, const FrameSettings& settings);

  // The graph the given world would run, as Graphviz DOT (compiled; culled passes dashed). Nothing
  // is executed. Pass names are the ones timings and the profile use.
  std::string graphDot(const RenderWorld& world, VkExtent2D extent, const FrameSettings& settings);
  // Names of the passes the last rendered frame executed, in order.
  const std::vector<std::string>& executedPasses() const { return executed_; }

  // A GI technique's render-graph node (DESIGN.md "One shape for every GI technique"), run after
  // the lighting pass when the world's effects name `effect`, in the order nodes were first set. It reads
  // "gbuffer.*" and "lighting.hdr" from the blackboard and, when it adds its term, writes
  // "lighting.hdr" and puts the new version back (tonemap reads whatever is there). It adds no
  // pass when no entity takes part. An empty function removes the node.
  using GraphNode = std::function<void(rg::RenderGraph&, PassContext&)>;
  void setNode(const std::string& effect, GraphNode node);

  // The posed vertices of the last frame (RenderWorld::posedVertices after the skinning pass:
  // MeshVertex layout, 8 floats per vertex); waits for the GPU. For the CPU = GPU skinning tests.
  std::vector<float> readPosedVertices();

  // Linear HDR radiance of the last frame as float RGB (waits for the GPU; needs keepHdr).
  std::vector<float> readHdr();
  gpu::Image& hdrImage() { return *hdr_; }
  gpu::Image& displayImage() { return *display_; }

 private:
  struct SlotBuffers {
    gpu::Buffer camera, instances, lights, shadowMatrices, posedVertices, jointMatrices, morphWeights;
  };
  void ensureTargets(VkExtent2D extent);
  void writeFrameData(std::uint32_t slot, const RenderWorld& world, PassContext& pc);
  void buildGraph(rg::RenderGraph& graph, PassContext& pc, VkExtent2D extent, const FrameSettings& settings,
                  rg::PhysicalId hdrId, rg::PhysicalId displayId, rg::PhysicalId posedId);

  gpu::Context& ctx_;
  std::unique_ptr<Pipelines> pipelines_;
  std::unique_ptr<gpu::SamplerCache> samplers_;
  std::unique_ptr<gpu::FrameRing> frames_;
  std::unique_ptr<VkBackend> backend_;
  std::vector<SlotBuffers> slots_;
  std::unique_ptr<gpu::Image> hdr_, display_, dummyAtlas_;
  std::vector<std::string> executed_;
  std::uint32_t lastSlot_ = 0;
  std::size_t lastPosedFloats_ = 0;
  // In registration order: a node that reads another's output (e.g. "ao.term") is set after it.
  std::vector<std::pair<std::string, GraphNode>> nodes_;
};

}  // namespace bounce::render
