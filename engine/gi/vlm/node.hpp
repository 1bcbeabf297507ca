#pragma once
// The VLM runtime and render-graph node (effect `vlm`; thesis §3.3 and §4.3). Per frame:
//   CPU: place every virtual light (static ones once, dynamic ones with their entity's world
//        matrix), rebuild the dynamic grid by scattering (grid.hpp; the static grid is built once,
//        §4.3), pack lights, grid slots and the per-entity tag table into this frame slot's buffers;
//   pass "vlm.lights" (phase 1): each virtual light's emitted radiance from the real lights with
//        shadow-atlas visibility, one texel per light (shaders/vlm/vlm_lights.frag);
//   pass "vlm" (phase 2): full screen, Σ over the pixel's cell candidates of π L_k F_k, skipping
//        its own tag, ρE/π added to "lighting.hdr" (shaders/vlm/vlm.frag).
// What a session does:
//   gi::vlm::Runtime vlm(ctx, renderer.pipelines(), registry, level.vlm, cookCache, framesInFlight);
//   renderer.setNode("vlm", vlm.node());
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "engine/gi/technique.hpp"
#include "engine/gi/vlm/grid.hpp"
#include "engine/gi/vlm/vlm_mesh.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/render/renderer.hpp"
#include "engine/scene/level.hpp"

namespace bounce::gi::vlm {

struct NodeSettings {
  int grid = 16;        // cells per axis over the scene bounds (both grids)
  std::uint32_t k = 32; // candidates per cell (§4.1)
  float range = 2.5f;   // active-hemisphere range (§4.2)
  // Phase 1 tests shadow visibility this far in front of the virtual light (metres): VLMs sit just
  // behind the real surface they stand for (§3.4), which would otherwise shadow them.
  float shadowLift = 0.02f;
  // Per-tag intensity/hue overrides (level "vlm.overrides", live keys in `bounce play`), applied
  // to the packed lights every frame (prepare()).
  std::map<int, scene::VlmOverride> overrides;
  // Conservative overflow mode (grid.hpp) when > 0: level key vlm.conservative_threshold.
  float conservativeThreshold = 0.0f;
};
NodeSettings settingsFrom(const scene::VlmConfig& config);

// The pixels of an `extent` image that world box [lo, hi] covers under `viewProj` (the whole
// image when a corner is at or behind the camera plane, or the box is empty; width 0 when it
// projects outside). Phase 2 scissors each dynamic VLM's draw to it.
VkRect2D screenRect(const glm::mat4& viewProj, glm::vec3 lo, glm::vec3 hi, VkExtent2D extent);

// One frame's lights and grids as the passes read them (exposed for tests and the overlay).
struct FrameData {
  std::vector<VirtualLight> lights;      // static first, then dynamic
  std::uint32_t staticCount = 0;
  const Grid* staticGrid = nullptr;      // indices into lights
  Grid dynamicGrid;                      // indices already offset by staticCount
  std::vector<std::uint32_t> entityTags; // vlm_tag per entity index (0 = none)
  // The lights of each dynamic VLM: lights[first, first + count), lit by phase 1 under the
  // timestamp scope "vlm.lights/<name>" and shaded by phase 2 under "vlm/<name>" (per-object rows
  // in `bounce profile`). [lo, hi]: the world box its lights can reach through the dynamic grid
  // (their half-ball boxes grown by one cell), which bounds phase 2's pixels for it.
  struct Range {
    std::string name;
    std::uint32_t first = 0, count = 0;
    glm::vec3 lo{0.0f}, hi{0.0f};
  };
  std::vector<Range> dynamicRanges;
};


class Runtime final : public TechniqueRuntime {
 public:
  Runtime(gpu::Context& ctx, const render::Pipelines& pipelines, ecs::Registry& registry, NodeSettings settings,
          const std::filesystem::path& cookCache, std::uint32_t framesInFlight);

  std::size_t vlmCount() const { return meshes_.size(); }
  std::size_t lightCount() const;  // virtual lights (triangles) over every VLM
  const NodeSettings& settings() const { return settings_; }
  // The tags of every virtual light, sorted (what `bounce play` cycles through).
  const std::vector<std::uint32_t>& tags() const { return tags_; }
  // Replaces the per-tag overrides; the next prepare() applies them.
  void setOverrides(std::map<int, scene::VlmOverride> overrides) { settings_.overrides = std::move(overrides); }
  // Cells that had more than K candidates in the static grid / in the last dynamic grid.
  std::uint64_t overflowCells() const;
  OverflowReport overflow() const { return overflow_; }
  // `bounce profile`'s line after the timings: formatOverflow(overflow()).
  std::vector<std::string> profileLines() const override { return {formatOverflow(overflow_)}; }

  // For benchmarks (`bounce bench vlm-lights|vlm-k`): replaces the static lights and/or the
  // settings; the static grid is rebuilt on the next frame.
  void replaceStaticLights(std::vector<VirtualLight> lights);
  void setSettings(const NodeSettings& settings);
  std::span<const VirtualLight> staticLights() const { return staticLights_; }

  // Places the lights for `world` (its scene bounds fix the grids) and builds the dynamic grid.
  FrameData prepare(const render::RenderWorld& world);
  // Adds "vlm.lights" and "vlm" (nothing when there is no light) and puts the new "lighting.hdr".
  void addTo(rg::RenderGraph& graph, render::PassContext& pc);
  render::Renderer::GraphNode node() override {
    return [this](rg::RenderGraph& g, render::PassContext& pc) { addTo(g, pc); };
  }

 private:
  GridDesc gridFor(const render::RenderWorld& world) const;

  gpu::Context& ctx_;
  ecs::Registry& registry_;
  NodeSettings settings_;
  std::vector<VlmMesh> meshes_;
  std::vector<VirtualLight> staticLights_;
  std::vector<std::uint32_t> tags_;
  Grid staticGrid_;
  bool staticBuilt_ = false;
  GridScatterBuilder dynamicBuilder_;  // the dynamic grid's working memory, kept from frame to frame
  OverflowReport overflow_;
  gpu::DescriptorSetLayout lightsLayout_, shadeLayout_;
  gpu::PipelineLayout lightsPipelineLayout_, shadePipelineLayout_;
  gpu::Pipeline lightsPipeline_, shadePipeline_;
  struct SlotBuffers {
    gpu::Buffer lights, slots, tags;
  };
  std::vector<SlotBuffers> buffers_;  // per frame slot
};

}  // namespace bounce::gi::vlm
