// The scatter build of the VLM grid (grid.hpp): every light visits only the cells under its
// half-ball's bounding box, so the cost is O(accepted (light, cell) pairs), where the thesis's
// gather (grid.cpp) is O(cells × lights).
//
// Two levels, so that no step writes to memory at random: lights are binned into blocks of 8³
// cells, then each block, on one thread, offers its lights to per-cell lists that stay in cache
// (grid_detail.hpp: CandidateList) and finishes its cells. Inside a block, a light's cells are
// walked row by row (the y and z terms once per row) and four cells of a row at a time with SSE2:
// the same IEEE operations as the scalar heuristic and bound, so the grids agree bit for bit.
#include <memory>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "engine/core/parallel.hpp"
#include "engine/gi/vlm/grid.hpp"
#include "engine/gi/vlm/grid_detail.hpp"

namespace bounce::gi::vlm {

using namespace detail;

namespace {

constexpr std::uint32_t kBlock = 8;
constexpr std::uint32_t kBlockCells = kBlock * kBlock * kBlock;

// A light as the scatter reads it, one cache line: what the heuristic and the bound need of its
// hemisphere, and the cells its half-ball box covers.
struct alignas(64) ScatterLight {
  glm::vec3 centre, normal;
  float radius2, extent, area, weight;
  glm::uvec3 lo{1u}, hi{0u};  // empty (lo > hi) for a degenerate light or one outside the grid
  bool live() const { return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z; }
};
static_assert(sizeof(ScatterLight) == 64);

// Cell boundaries along one axis, edge[c] = origin + c · cellSize exactly as cellBox computes them
// (cell c spans [edge[c], edge[c + 1]]), padded so a block-wide row read past the last cell stays
// inside (those lanes are masked off).
std::vector<float> edges(const GridDesc& d, int a) {
  std::vector<float> e(d.dims[a] + 1 + kBlock + 1, 0.0f);
  for (std::uint32_t c = 0; c <= d.dims[a]; ++c) e[c] = d.origin[a] + float(c) * d.cellSize[a];
  return e;
}

// One row of a block's cells (local x 0 … kBlock − 1, from edgeX) of one light at fixed y and z:
// which cells the heuristic accepts (accepts() with the y + z parts given), as a bit mask, and
// each cell's bound bits (boundAt, boundBits) in bits[x]. The x overlap test is left to the
// caller's range mask (cellRange). The SSE2 path evaluates all eight cells, two groups of four: a
// fixed amount of work with no branch on the row's length.
inline unsigned evaluateRow(const ScatterLight& h, const float* edgeX, float yzGap2, float yzFront, std::uint32_t* bits) {
#if defined(__SSE2__)
  const __m128 cx = _mm_set1_ps(h.centre.x), nx = _mm_set1_ps(h.normal.x), yz = _mm_set1_ps(yzGap2);
  const __m128 front0 = _mm_set1_ps(yzFront), radius2 = _mm_set1_ps(h.radius2), zero = _mm_setzero_ps();
  const __m128 extent = _mm_set1_ps(h.extent), area = _mm_set1_ps(h.area), weight = _mm_set1_ps(h.weight);
  const __m128 pi = _mm_set1_ps(kPi);
  const float* corner = edgeX + (h.normal.x > 0.0f ? 1 : 0);  // the corner furthest along n: hi or lo
  unsigned mask = 0;
  for (unsigned x = 0; x < kBlock; x += 4) {
    const __m128 lo = _mm_loadu_ps(edgeX + x), hi = _mm_loadu_ps(edgeX + x + 1);
    const __m128 g = _mm_sub_ps(_mm_min_ps(_mm_max_ps(cx, lo), hi), cx);  // clamp(c, lo, hi) − c
    const __m128 gap2 = _mm_add_ps(_mm_mul_ps(g, g), yz);
    const __m128 front = _mm_add_ps(_mm_mul_ps(nx, _mm_sub_ps(_mm_loadu_ps(corner + x), cx)), front0);
    mask |= unsigned(_mm_movemask_ps(_mm_and_ps(_mm_cmple_ps(gap2, radius2), _mm_cmpgt_ps(front, zero)))) << x;
    // boundAt: d = max(√gap2 − extent, 0); shape = d > 0 ? min(A/d², π) : π; bound = weight · shape.
    const __m128 d = _mm_max_ps(_mm_sub_ps(_mm_sqrt_ps(gap2), extent), zero);
    const __m128 near = _mm_cmpgt_ps(d, zero);
    const __m128 shape = _mm_or_ps(_mm_and_ps(near, _mm_min_ps(_mm_div_ps(area, _mm_mul_ps(d, d)), pi)), _mm_andnot_ps(near, pi));
    const __m128 b = _mm_mul_ps(weight, shape);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(bits + x),
                     _mm_and_si128(_mm_castps_si128(b), _mm_castps_si128(_mm_cmpgt_ps(b, zero))));
  }
  return mask;
#else
  unsigned mask = 0;
  for (unsigned x = 0; x < kBlock; ++x) {
    const AxisTerms xt = axisTerms(h.centre.x, h.normal.x, edgeX[x], edgeX[x + 1]);
    mask |= unsigned(accepts(h.radius2, xt, yzGap2, yzFront)) << x;
    bits[x] = boundBits(boundAt(h.extent, h.area, h.weight, xt.gap2 + yzGap2));
  }
  return mask;
#endif
}

}  // namespace

struct GridScatterBuilder::Scratch {
  std::vector<ScatterLight> lights;
  std::vector<std::uint64_t> cursor, offsets;
  std::vector<std::uint32_t> binned;
};

GridScatterBuilder::GridScatterBuilder() : scratch_(std::make_unique<Scratch>()) {}
GridScatterBuilder::~GridScatterBuilder() = default;
GridScatterBuilder::GridScatterBuilder(GridScatterBuilder&&) noexcept = default;
GridScatterBuilder& GridScatterBuilder::operator=(GridScatterBuilder&&) noexcept = default;

Grid buildGridScatter(std::span<const GridLight> lights, const GridDesc& desc) {
  GridScatterBuilder builder;
  Grid g;
  builder.build(lights, desc, g);
  return g;
}

void GridScatterBuilder::build(std::span<const GridLight> lights, const GridDesc& desc, Grid& out) {
  const std::uint32_t nx = desc.dims.x, ny = desc.dims.y;
  std::vector<ScatterLight>& sl = scratch_->lights;
  sl.resize(lights.size());
  parallelFor(0, lights.size(), [&](std::size_t l) {
    const ActiveHemisphere h = activeHemisphere(lights[l], desc.range);
    ScatterLight& s = sl[l];
    s.centre = h.centre, s.normal = h.normal;
    s.radius2 = h.radius * h.radius, s.extent = h.extent, s.area = h.area, s.weight = h.weight;
    s.lo = glm::uvec3(1u), s.hi = glm::uvec3(0u);
    if (h.radius > 0.0f) cellRange(desc, h, s.lo, s.hi);
  }, 1024);
  const std::vector<float> edgeX = edges(desc, 0), edgeY = edges(desc, 1), edgeZ = edges(desc, 2);

  const glm::uvec3 blocks = (desc.dims + (kBlock - 1u)) / kBlock;
  const std::size_t blockCount = std::size_t(blocks.x) * blocks.y * blocks.z;
  auto forEachBlock = [&](const ScatterLight& s, auto&& fn) {
    const glm::uvec3 b0 = s.lo / kBlock, b1 = s.hi / kBlock;
    for (std::uint32_t z = b0.z; z <= b1.z; ++z)
      for (std::uint32_t y = b0.y; y <= b1.y; ++y)
        for (std::uint32_t x = b0.x; x <= b1.x; ++x) fn((std::size_t(z) * blocks.y + y) * blocks.x + x);
  };
  // Bin (count, prefix-sum, fill) by contiguous chunks of lights, each chunk's counts apart, so a
  // block's list comes out in increasing light index with no sort: every cell is then offered its
  // candidates in the gather build's order. Chunks × blocks counters stay under ~4 M.
  const std::size_t chunkSize =
      std::max<std::size_t>({4096, sl.size() / 64 + 1, sl.size() * blockCount / (std::size_t(1) << 22) + 1});
  const std::size_t chunks = (sl.size() + chunkSize - 1) / chunkSize;
  auto chunkLights = [&](std::size_t c, auto&& fn) {
    for (std::size_t l = c * chunkSize, end = std::min(sl.size(), (c + 1) * chunkSize); l < end; ++l)
      if (sl[l].live()) fn(l);
  };
  std::vector<std::uint64_t>& cursor = scratch_->cursor;  // per (chunk, block): count, then fill position
  cursor.assign(chunks * blockCount, 0);
  parallelFor(0, chunks, [&](std::size_t c) {
    std::uint64_t* count = cursor.data() + c * blockCount;
    chunkLights(c, [&](std::size_t l) { forEachBlock(sl[l], [&](std::size_t b) { ++count[b]; }); });
  });
  std::vector<std::uint64_t>& offsets = scratch_->offsets;
  offsets.assign(blockCount + 1, 0);
  for (std::size_t b = 0, at = 0; b < blockCount; ++b) {
    offsets[b] = at;
    for (std::size_t c = 0; c < chunks; ++c) {
      const std::uint64_t n = cursor[c * blockCount + b];
      cursor[c * blockCount + b] = at;
      at += n;
    }
    offsets[b + 1] = at;
  }
  std::vector<std::uint32_t>& binned = scratch_->binned;
  binned.resize(offsets[blockCount]);
  parallelFor(0, chunks, [&](std::size_t c) {
    std::uint64_t* fill = cursor.data() + c * blockCount;
    chunkLights(c, [&](std::size_t l) { forEachBlock(sl[l], [&](std::size_t b) { binned[fill[b]++] = std::uint32_t(l); }); });
  });

  // Per block: each binned light's cells in the block, row by row (the overlap tests are implied:
  // cellRange kept only overlapping cells).
  auto pass = [&](std::uint32_t capacity, auto&& makeCell, auto&& done) {
    using Cell = decltype(makeCell(nullptr));
    parallelFor(0, blockCount, [&](std::size_t b) {
      const glm::uvec3 bc(std::uint32_t(b % blocks.x), std::uint32_t(b / blocks.x % blocks.y),
                          std::uint32_t(b / (std::size_t(blocks.x) * blocks.y)));
      const glm::uvec3 c0 = bc * kBlock, c1 = glm::min(c0 + kBlock, desc.dims) - 1u;
      // Per-thread storage, reused from block to block.
      static thread_local std::vector<std::uint64_t> scratch;
      static thread_local std::vector<Cell> local;
      scratch.resize(std::size_t(kBlockCells) * capacity);
      local.clear();
      for (std::uint32_t j = 0; j < kBlockCells; ++j) local.push_back(makeCell(scratch.data() + std::size_t(j) * capacity));
      constexpr std::uint64_t kAhead = 4;  // a block's lights lie anywhere in the array: fetch ahead
      for (std::uint64_t i = offsets[b]; i < offsets[b + 1]; ++i) {
        if (i + kAhead < offsets[b + 1]) {
          __builtin_prefetch(&sl[binned[i + kAhead]]);
        }
        const std::uint32_t l = binned[i];
        const ScatterLight& h = sl[l];
        const glm::uvec3 lo = glm::max(h.lo, c0), hi = glm::min(h.hi, c1);
        // Rows whose y + z distance alone exceeds the radius are skipped: every cell of theirs
        // fails the sphere test (x² + (y² + z²) ≥ y² + z² in float too: rounding is monotone).
        const unsigned inRange = ((2u << (hi.x - c0.x)) - 1u) & ~((1u << (lo.x - c0.x)) - 1u);
        for (std::uint32_t z = lo.z; z <= hi.z; ++z) {
          const AxisTerms zt = axisTerms(h.centre.z, h.normal.z, edgeZ[z], edgeZ[z + 1]);
          for (std::uint32_t y = lo.y; y <= hi.y; ++y) {
            const AxisTerms yt = axisTerms(h.centre.y, h.normal.y, edgeY[y], edgeY[y + 1]);
            if (yt.gap2 + zt.gap2 > h.radius2) continue;
            alignas(16) std::uint32_t bits[kBlock];
            unsigned m = evaluateRow(h, edgeX.data() + c0.x, yt.gap2 + zt.gap2, yt.front + zt.front, bits) & inRange;
            Cell* cells = local.data() + ((z - c0.z) * kBlock + (y - c0.y)) * kBlock;
            for (; m; m &= m - 1) {
              const unsigned x = unsigned(__builtin_ctz(m));
              cells[x].offer(rankKeyFromBits(bits[x], l));
            }
          }
        }
      }
      for (std::uint32_t z = c0.z; z <= c1.z; ++z)
        for (std::uint32_t y = c0.y; y <= c1.y; ++y)
          for (std::uint32_t x = c0.x; x <= c1.x; ++x)
            done((std::size_t(z) * ny + y) * nx + x, local[((z - c0.z) * kBlock + (y - c0.y)) * kBlock + (x - c0.x)]);
    });
  };
  finishGrid(desc, pass, out);
}

}  // namespace bounce::gi::vlm
