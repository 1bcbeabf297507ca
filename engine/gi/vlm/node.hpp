#pragma once
// The VLM runtime and render-graph node (effect `vlm`; thesis §3.3 and §4.3). Per frame:
//   CPU (update.hpp, gi::vlm::Update): place every virtual light (static ones once, dynamic ones
//        with their entity's world matrix), rebuild the dynamic grid by scattering (grid.hpp; the
//        static grid is built once, §4.3); then (here) pack lights, grid slots and the per-entity
//        tag table into this frame slot's buffers;
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
#include "engine/gi/vlm/update.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/render/renderer.hpp"
#include "engine/scene/level.hpp"

namespace bounce::gi::vlm {

// The pixels of an `extent` image that world box [lo, hi] covers under `viewProj` (the whole
// image when a corner is at or behind the camera plane, or the box is empty; width 0 when it
// projects outside). Phase 2 scissors each dynamic VLM's draw to it.
VkRect2D screenRect(const glm::mat4& viewProj, glm::vec3 lo, glm::vec3 hi, VkExtent2D extent);

class Runtime final : public TechniqueRuntime {
 public:
  Runtime(gpu::Context& ctx, const render::Pipelines& pipelines, ecs::Registry& registry, NodeSettings settings,
          const std::filesystem::path& cookCache, std::uint32_t framesInFlight);

  std::size_t vlmCount() const { return update_.vlmCount(); }
  std::size_t lightCount() const { return update_.lightCount(); }  // virtual lights (triangles) over every VLM
  const NodeSettings& settings() const { return update_.settings(); }
  // The tags of every virtual light, sorted (what `bounce play` cycles through).
  const std::vector<std::uint32_t>& tags() const { return update_.tags(); }
  // Replaces the per-tag overrides; the next prepare() applies them.
  void setOverrides(std::map<int, scene::VlmOverride> overrides) { update_.setOverrides(std::move(overrides)); }
  // Cells that had more than K candidates in the static grid / in the last dynamic grid.
  std::uint64_t overflowCells() const { return update_.overflowCells(); }
  OverflowReport overflow() const { return update_.overflow(); }
  // `bounce profile`'s line after the timings: formatOverflow(overflow()).
  std::vector<std::string> profileLines() const override { return {formatOverflow(update_.overflow())}; }

  // For benchmarks (`bounce bench vlm-lights|vlm-k`): replaces the static lights and/or the
  // settings; the static grid is rebuilt on the next frame.
  void replaceStaticLights(std::vector<VirtualLight> lights) { update_.replaceStaticLights(std::move(lights)); }
  void setSettings(const NodeSettings& settings) { update_.setSettings(settings); }
  std::span<const VirtualLight> staticLights() const { return update_.staticLights(); }

  // The frame's CPU work (update.hpp): lights placed for `world`, the grids built.
  FrameData prepare(const render::RenderWorld& world) { return update_.prepare(world); }
  // Adds "vlm.lights" and "vlm" (nothing when there is no light) and puts the new "lighting.hdr".
  void addTo(rg::RenderGraph& graph, render::PassContext& pc);
  render::Renderer::GraphNode node() override {
    return [this](rg::RenderGraph& g, render::PassContext& pc) { addTo(g, pc); };
  }

 private:
  gpu::Context& ctx_;
  Update update_;  // the per-frame CPU work
  gpu::DescriptorSetLayout lightsLayout_, shadeLayout_;
  gpu::PipelineLayout lightsPipelineLayout_, shadePipelineLayout_;
  gpu::Pipeline lightsPipeline_, shadePipeline_;
  struct SlotBuffers {
    gpu::Buffer lights, slots, tags;
  };
  std::vector<SlotBuffers> buffers_;  // per frame slot
};

}  // namespace bounce::gi::vlm
