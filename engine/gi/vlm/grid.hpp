#pragma once
// The VLM acceleration grid (thesis chapter 4): a uniform 3D grid over the scene whose cells each
// hold a fixed-size list of K candidate virtual lights (indices into the light array; unused slots
// hold kNullLight, the "special virtual light that generates no illumination" of §4.1). Memory:
// cells × K × 4 bytes.
//
// A light is a candidate for a cell when the cell touches its active hemisphere (§4.2): the half of
// the sphere about the light's centroid, of radius range × (farthest vertex distance), on the
// emitting side. The thesis's test is per point; a cell holds candidates for every point inside it,
// so here the test is cell-box against half-sphere, conservative: the box overlaps the half-ball's
// bounding box, the sphere, and the open half-space in front of the light.
//
// Two builds that give identical grids, slot for slot:
//  - gather (the thesis's, grid.cpp): every cell tests every light — O(cells × lights), kept as the
//    reference and the benchmark baseline;
//  - scatter (grid_scatter.cpp): every light visits only the cells under its half-ball's bounding
//    box — O(touched cells). Lights are binned into blocks of 8³ cells in increasing index; each
//    block, in parallel (TBB), offers its lights to its own cells' lists, which stay in cache: no
//    locks, no random writes to a grid-sized array.
// Overflow (more than K candidates): a cell keeps the K with the largest upper bound on the
// irradiance they can deliver anywhere in the cell, E ≤ min(π, A/d²)·L (F ≤ 1 and F ≤ A/(π d²),
// d the distance from the light's bounding sphere to the cell), ties broken by light index; the
// number of overflowing cells is reported. A list's order is not sorted: it is what the shared
// per-cell list (grid_detail.hpp: CandidateList) leaves when offered a cell's candidates in
// increasing light index, which both builds do. Lists are packed, unused slots last.
// Conservative mode (issue 5 §4; GridDesc::conservativeThreshold > 0): a light is dropped from a
// cell only when its bound there is below the threshold. Every list grows to the largest number of
// above-threshold candidates any cell has (at least K, at most maxK slots); the (light, cell) pairs
// above the threshold that still do not fit are counted in Grid::droppedAboveThreshold.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::gi::vlm {

inline constexpr std::uint32_t kNullLight = 0xFFFFFFFFu;

// What the grid needs of a virtual light: its triangle (counter-clockwise from the emitting side)
// and a weight for the overflow ranking (its radiance's largest channel, or 1 for geometry only).
struct GridLight {
  glm::vec3 v0, v1, v2;
  float weight = 1.0f;
};

struct GridDesc {
  glm::vec3 origin{0.0f};    // world-space minimum corner
  glm::vec3 cellSize{1.0f};  // world units per cell along each axis
  glm::uvec3 dims{1u};       // cells along each axis
  std::uint32_t k = 32;      // candidates per cell
  float range = 2.5f;        // active-hemisphere range parameter (§4.2)
  // Conservative overflow mode when > 0: lights whose cellBound is at least this are never dropped
  // while maxK allows (units of cellBound: the irradiance, W/m², the light could deliver into the
  // cell if it received irradiance π itself, i.e. emitted radiance = weight).
  float conservativeThreshold = 0.0f;
  std::uint32_t maxK = 256;  // conservative mode: lists grow up to this many slots

  std::uint64_t cellCount() const { return std::uint64_t(dims.x) * dims.y * dims.z; }
};

// A grid of dims³ cells covering box [lo, hi] (padded so no extent is zero).
GridDesc fitGrid(glm::vec3 lo, glm::vec3 hi, glm::uvec3 dims, std::uint32_t k, float range);

// The active hemisphere of one light; radius 0 for a degenerate (zero-area) light, which is never
// a candidate anywhere.
struct ActiveHemisphere {
  glm::vec3 centre{0.0f};
  glm::vec3 normal{0.0f};  // unit, the emitting side
  float radius = 0.0f;     // range × farthest vertex distance
  float extent = 0.0f;     // farthest vertex distance (the light's own bounding sphere)
  float area = 0.0f;
  float weight = 0.0f;
  glm::vec3 lo{0.0f}, hi{0.0f};  // bounding box of the half-ball (tighter than the sphere's)
};
ActiveHemisphere activeHemisphere(const GridLight& light, float range);

// The cell's world box.
void cellBox(const GridDesc& desc, glm::uvec3 cell, glm::vec3& lo, glm::vec3& hi);
// True when the hemisphere may light some point of box [lo, hi] (see the header comment).
bool touchesCell(const ActiveHemisphere& h, glm::vec3 lo, glm::vec3 hi);
// Upper bound on the irradiance the light can deliver inside [lo, hi], per unit weight × weight.
float cellBound(const ActiveHemisphere& h, glm::vec3 lo, glm::vec3 hi);

struct Grid {
  GridDesc desc;                     // desc.k: the slots per cell built (conservative mode may grow it)
  std::vector<std::uint32_t> slots;  // cellCount × k; kNullLight in unused slots
  std::uint64_t overflowCells = 0;   // cells that had more than k candidates
  std::uint64_t candidates = 0;      // (light, cell) pairs before truncation
  // Conservative mode: (light, cell) pairs whose bound reached the threshold but did not fit in
  // maxK slots (0 otherwise).
  std::uint64_t droppedAboveThreshold = 0;

  // The cell holding world point p, or -1 outside the grid.
  std::int64_t cellOf(glm::vec3 p) const;
  std::span<const std::uint32_t> cell(std::uint64_t index) const {
    return {slots.data() + index * desc.k, desc.k};
  }
};

Grid buildGridGather(std::span<const GridLight> lights, const GridDesc& desc);
Grid buildGridScatter(std::span<const GridLight> lights, const GridDesc& desc);

// Repeated scatter builds (the per-frame dynamic grid) keep their working memory here and build
// into a Grid whose slots are reused, so after the first build nothing is allocated and no fresh
// page is touched (at 100k lights into 50³ first-touch page faults cost about as much as the
// build itself). The result is the same as buildGridScatter's.
class GridScatterBuilder {
 public:
  GridScatterBuilder();
  ~GridScatterBuilder();
  GridScatterBuilder(GridScatterBuilder&&) noexcept;
  GridScatterBuilder& operator=(GridScatterBuilder&&) noexcept;
  void build(std::span<const GridLight> lights, const GridDesc& desc, Grid& out);

 private:
  struct Scratch;
  std::unique_ptr<Scratch> scratch_;
};

// What the grids dropped (shown by the `bounce play` overlay and `bounce profile`).
struct OverflowReport {
  std::uint64_t cellsPerGrid = 0;
  std::uint32_t k = 0;                       // slots per cell as built (conservative mode may grow it)
  std::uint64_t staticCells = 0;             // overflowing cells of the static grid
  std::uint64_t dynamicCells = 0;            // ... of the last dynamic grid
  std::uint64_t dynamicMaxCells = 0;         // ... most in any dynamic grid built so far
  std::uint64_t droppedAboveThreshold = 0;   // conservative mode: static + last dynamic grid
  bool conservative = false;
};
// One line for the `bounce play` overlay and the `bounce profile` footer, e.g.
//   "vlm overflow: static 12/4096 cells, dynamic 3/4096 (most 5), K 32"
// with ", conservative: 7 candidates above the threshold dropped" in conservative mode.
std::string formatOverflow(const OverflowReport& report);

}  // namespace bounce::gi::vlm

namespace bounce::gi::vlm {

// A random benchmark/test scene in the unit cube: `count` triangles of random orientation, each
// about 1.5 mean spacings wide (so neighbouring hemispheres overlap as in a simplified real mesh),
// weights in [0.1, 1.1). Deterministic for a seed.
std::vector<GridLight> randomGridScene(std::uint32_t count, std::uint64_t seed);

}  // namespace bounce::gi::vlm
