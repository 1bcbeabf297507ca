// The range-too-small artefact (thesis §4.2, Fig. 5.6) as a number. A finely tessellated VLM (a
// unit wall of 512 small triangles) lights receivers close in front of it; the grid keeps a light
// in a cell only when the cell touches its active hemisphere of radius range × (light size), so
// with a small range the receivers miss the light of the wall's farther triangles: the irradiance
// Σ π L F over the cell's candidates falls short of the sum over every light. The shortfall must
// shrink as the range grows and be small at the thesis's largest range, 4.5.
#include <gtest/gtest.h>

#include "engine/gi/vlm/form_factor.hpp"
#include "engine/gi/vlm/grid.hpp"
#include "engine/math/sampling.hpp"

using namespace bounce;

namespace {

constexpr int kTiles = 16;           // 16 × 16 squares of 2 triangles: 512 virtual lights, legs 1/16 m
constexpr int kGrid = 32;            // cells per axis over [−0.1, 1.1]³: 3.75 cm cells
constexpr std::uint32_t kNoOverflow = 1024;  // K above any cell's candidate count: only the range drops lights
// At range 4.5 a hemisphere reaches ~21 cm (4.5 × 4.7 cm, the triangles' centroid-to-vertex
// distance); what lies beyond, seen from 1–3 cm, is about (h/R)² ≈ 1 % of the wall's form factor,
// and the cells' conservative boxes keep some of it. 2 % leaves room for the cell layout.
constexpr double kRange45MaxError = 0.02;

// The wall z = 0, x, y ∈ [0, 1], emitting towards +z (counter-clockwise seen from +z), radiance 1.
std::vector<gi::vlm::GridLight> wall() {
  std::vector<gi::vlm::GridLight> lights;
  const float s = 1.0f / kTiles;
  for (int j = 0; j < kTiles; ++j)
    for (int i = 0; i < kTiles; ++i) {
      const glm::vec3 a(i * s, j * s, 0.0f), b((i + 1) * s, j * s, 0.0f), c((i + 1) * s, (j + 1) * s, 0.0f),
          d(i * s, (j + 1) * s, 0.0f);
      lights.push_back({a, b, c, 1.0f});
      lights.push_back({a, c, d, 1.0f});
    }
  return lights;
}

double irradiance(const glm::dvec3& x, const glm::dvec3& n, const std::vector<gi::vlm::GridLight>& lights,
                  std::span<const std::uint32_t> subset) {
  constexpr double kPi = 3.14159265358979323846;
  double e = 0.0;
  for (std::uint32_t i : subset) {
    if (i == gi::vlm::kNullLight) break;
    const auto& l = lights[i];
    e += kPi * gi::vlm::formFactor(x, n, glm::dvec3(l.v0), glm::dvec3(l.v1), glm::dvec3(l.v2));  // L = 1
  }
  return e;
}

// Mean relative shortfall (E_all − E_grid)/E_all over receivers 1–3 cm in front of the wall's
// middle, facing it.
double rangeError(float range) {
  const auto lights = wall();
  const auto desc = gi::vlm::fitGrid(glm::vec3(-0.1f), glm::vec3(1.1f), glm::uvec3(kGrid), kNoOverflow, range);
  const gi::vlm::Grid grid = gi::vlm::buildGridScatter(lights, desc);
  EXPECT_EQ(grid.overflowCells, 0u);
  std::vector<std::uint32_t> every(lights.size());
  for (std::uint32_t i = 0; i < every.size(); ++i) every[i] = i;
  math::Pcg32 rng(3, 7);
  double sum = 0.0;
  constexpr int kReceivers = 200;
  for (int r = 0; r < kReceivers; ++r) {
    const glm::dvec3 u(rng.nextFloat3());
    const glm::dvec3 x(0.25 + 0.5 * u.x, 0.25 + 0.5 * u.y, 0.01 + 0.02 * u.z);
    const glm::dvec3 n(0.0, 0.0, -1.0);
    const double all = irradiance(x, n, lights, every);
    const std::int64_t cell = grid.cellOf(glm::vec3(x));
    EXPECT_GE(cell, 0);
    const double fromGrid = irradiance(x, n, lights, grid.cell(std::uint64_t(cell)));
    EXPECT_LE(fromGrid, all * (1.0 + 1e-12));  // a subset of the lights, all of positive F
    sum += (all - fromGrid) / all;
  }
  return sum / kReceivers;
}

}  // namespace

TEST(VlmRange, TooSmallARangeIsMeasurableAsAnErrorIncrease) {
  const double e15 = rangeError(1.5f), e25 = rangeError(2.5f), e35 = rangeError(3.5f), e45 = rangeError(4.5f);
  std::printf("mean irradiance shortfall: range 1.5 %.4f, 2.5 %.4f, 3.5 %.4f, 4.5 %.4f\n", e15, e25, e35, e45);
  EXPECT_GT(e15, e25);
  EXPECT_GT(e25, e35);
  EXPECT_GT(e35, e45);
  // The artefact is visible at 1.5: several times the 4.5 error.
  EXPECT_GT(e15, 3.0 * e45);
  EXPECT_LT(e45, kRange45MaxError);
}
