#pragma once
// VLM's per-frame CPU work (thesis §4.3), the technique's update.* (DESIGN.md "One shape for every
// GI technique"): place every virtual light (static ones once, dynamic ones with their entity's
// world matrix), build the static grid once and the dynamic grid every frame by scattering
// (grid.hpp), apply the per-tag overrides (§3.5) and gather the per-entity tag table. node.* packs
// the result into GPU buffers and draws the two passes.
//
// It runs in the node's setup rather than TechniqueRuntime::update(): the grids cover the scene
// bounds of the frame's RenderWorld, which exists only once the frame is extracted.
#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "engine/ecs/registry.hpp"
#include "engine/gi/vlm/grid.hpp"
#include "engine/gi/vlm/vlm_mesh.hpp"
#include "engine/render/render_world.hpp"
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

class Update {
 public:
  // Collects the registry's VLMs (cooking their assets through `cookCache`) and places the static
  // ones at their current world transforms.
  Update(ecs::Registry& registry, NodeSettings settings, const std::filesystem::path& cookCache);

  std::size_t vlmCount() const { return meshes_.size(); }
  std::size_t lightCount() const;  // virtual lights (triangles) over every VLM
  const NodeSettings& settings() const { return settings_; }
  const std::vector<std::uint32_t>& tags() const { return tags_; }
  void setOverrides(std::map<int, scene::VlmOverride> overrides) { settings_.overrides = std::move(overrides); }
  std::uint64_t overflowCells() const { return overflow_.staticCells + overflow_.dynamicCells; }
  OverflowReport overflow() const { return overflow_; }
  void replaceStaticLights(std::vector<VirtualLight> lights);
  void setSettings(const NodeSettings& settings);
  std::span<const VirtualLight> staticLights() const { return staticLights_; }
  // The static grid as the last prepare() built it (empty before the first frame).
  const Grid& staticGrid() const { return staticGrid_; }

  // Places the lights for `world` (its scene bounds fix the grids) and builds the dynamic grid.
  FrameData prepare(const render::RenderWorld& world);

 private:
  GridDesc gridFor(const render::RenderWorld& world) const;

  ecs::Registry& registry_;
  NodeSettings settings_;
  std::vector<VlmMesh> meshes_;
  std::vector<VirtualLight> staticLights_;
  std::vector<std::uint32_t> tags_;
  Grid staticGrid_;
  bool staticBuilt_ = false;
  GridScatterBuilder dynamicBuilder_;  // the dynamic grid's working memory, kept from frame to frame
  OverflowReport overflow_;
};

}  // namespace bounce::gi::vlm
