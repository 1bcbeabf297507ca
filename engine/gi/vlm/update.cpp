#include "engine/gi/vlm/update.hpp"

#include <algorithm>
#include <limits>

#include "engine/scene/components.hpp"

namespace bounce::gi::vlm {
namespace {

// The grids cover the scene bounds padded by this fraction of their diagonal on every side, so
// receivers on the bounding walls fall inside a cell.
constexpr float kBoundsPad = 0.02f;

std::vector<GridLight> gridLights(std::span<const VirtualLight> lights) {
  std::vector<GridLight> out;
  out.reserve(lights.size());
  for (const auto& l : lights) out.push_back({l.v0, l.v1, l.v2, std::max({l.scale.r, l.scale.g, l.scale.b, 1e-6f})});
  return out;
}

}  // namespace

NodeSettings settingsFrom(const scene::VlmConfig& config) {
  NodeSettings s;
  s.grid = config.grid;
  s.k = std::uint32_t(config.k);
  s.range = config.range;
  s.overrides = config.overrides;
  s.conservativeThreshold = config.conservativeThreshold;
  return s;
}

Update::Update(ecs::Registry& registry, NodeSettings settings, const std::filesystem::path& cookCache)
    : registry_(registry), settings_(std::move(settings)), meshes_(collectVlms(registry, cookCache)) {
  for (const VlmMesh& m : meshes_)
    if (!m.dynamic) {
      const auto* placed = registry.tryGet<scene::WorldTransform>(m.entity);
      appendPlaced(m, placed ? placed->matrix : glm::mat4(1.0f), staticLights_);
    }
  {
    std::vector<VirtualLight> all;
    for (const VlmMesh& m : meshes_) all.insert(all.end(), m.local.begin(), m.local.end());
    tags_ = tagsOf(all);
  }
}

std::size_t Update::lightCount() const {
  std::size_t n = 0;
  for (const auto& m : meshes_) n += m.local.size();
  return n;
}

void Update::replaceStaticLights(std::vector<VirtualLight> lights) {
  staticLights_ = std::move(lights);
  staticBuilt_ = false;
}

void Update::setSettings(const NodeSettings& settings) {
  settings_ = settings;
  staticBuilt_ = false;
  overflow_ = {};
}

GridDesc Update::gridFor(const render::RenderWorld& world) const {
  glm::vec3 lo = world.sceneMin, hi = world.sceneMax;
  const float pad = kBoundsPad * glm::length(hi - lo) + 1e-3f;
  const auto dims = glm::uvec3(std::uint32_t(std::max(1, settings_.grid)));
  GridDesc d = fitGrid(lo - pad, hi + pad, dims, settings_.k, settings_.range);
  d.conservativeThreshold = settings_.conservativeThreshold;
  return d;
}

FrameData Update::prepare(const render::RenderWorld& world) {
  FrameData f;
  const GridDesc desc = gridFor(world);
  // The static grid is built once (§4.3), over the bounds of the first frame's scene.
  if (!staticBuilt_) {
    staticGrid_ = buildGridScatter(gridLights(staticLights_), desc);
    staticBuilt_ = true;
  }
  f.lights = staticLights_;
  f.staticCount = std::uint32_t(staticLights_.size());
  f.staticGrid = &staticGrid_;
  std::vector<VirtualLight> moving;
  for (const VlmMesh& m : meshes_) {
    const auto* placed = registry_.tryGet<scene::WorldTransform>(m.entity);
    if (!m.dynamic || !registry_.valid(m.entity) || !placed) continue;
    const auto first = std::uint32_t(moving.size());
    appendPlaced(m, placed->matrix, moving);
    FrameData::Range r{m.name, f.staticCount + first, std::uint32_t(moving.size()) - first};
    r.lo = glm::vec3(std::numeric_limits<float>::max()), r.hi = -r.lo;
    for (std::size_t i = first; i < moving.size(); ++i) {
      const ActiveHemisphere h = activeHemisphere({moving[i].v0, moving[i].v1, moving[i].v2, 1.0f}, desc.range);
      if (h.radius > 0.0f) r.lo = glm::min(r.lo, h.lo), r.hi = glm::max(r.hi, h.hi);
    }
    r.lo -= desc.cellSize, r.hi += desc.cellSize;
    f.dynamicRanges.push_back(std::move(r));
  }
  if (!moving.empty()) {
    dynamicBuilder_.build(gridLights(moving), desc, f.dynamicGrid);
    for (auto& s : f.dynamicGrid.slots)
      if (s != kNullLight) s += f.staticCount;
  }
  overflow_.cellsPerGrid = desc.cellCount();
  overflow_.k = staticGrid_.desc.k;
  overflow_.staticCells = staticGrid_.overflowCells;
  overflow_.dynamicCells = f.dynamicGrid.overflowCells;
  overflow_.dynamicMaxCells = std::max(overflow_.dynamicMaxCells, f.dynamicGrid.overflowCells);
  overflow_.droppedAboveThreshold = staticGrid_.droppedAboveThreshold + f.dynamicGrid.droppedAboveThreshold;
  overflow_.conservative = settings_.conservativeThreshold > 0.0f;
  f.lights.insert(f.lights.end(), moving.begin(), moving.end());
  // Artistic per-tag overrides (§3.5) on this frame's copy; the grids keep the unmodified bounds.
  if (!settings_.overrides.empty())
    for (VirtualLight& l : f.lights)
      if (auto it = settings_.overrides.find(int(l.tag)); it != settings_.overrides.end())
        l.scale = applyOverride(l.scale, it->second);
  registry_.view<scene::VlmTag>().each([&](ecs::Entity e, scene::VlmTag& t) {
    if (f.entityTags.size() <= e.index()) f.entityTags.resize(e.index() + 1, 0u);
    f.entityTags[e.index()] = std::uint32_t(t.tag);
  });
  return f;
}

}  // namespace bounce::gi::vlm
