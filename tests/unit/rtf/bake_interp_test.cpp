// RTF bake, Eq. 6–7 at the hit point (issue 14, session 11): a projection ray's hit takes the
// transfer of its triangle interpolated with Embree's barycentrics, t_x = Σ_c b_c t_{v_c}, as the
// rasteriser shades per-vertex transfer — not its nearest vertex's t (the bake until session 11).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "engine/math/sh.hpp"
#include "tests/unit/rtf/small_field.hpp"

namespace bounce::gi::rtf {
namespace {

TEST(RtfBakeInterp, ItfIsThePerRaySumOfTheTrianglesInterpolatedTransfer) {
  // A faceted two-tone sphere: two meshes (the flattened vertex index is offset by the first
  // mesh's count), unshared corners with smooth normals, so the three corners of a triangle carry
  // different transfer. Reference: Eq. 6–7 evaluated ray by ray in double, M^{ij}_{q,k} = Σ_ω Δω
  // y_i(ω) Σ_c b_c t^j_{v_c,k}, against the bake's regrouped float sum (dense.hpp, one rank-n update
  // per sample): float rounding only, < 1e-5 of the largest |M|.
  FieldSettings fs = testing::smallSettings();
  fs.raysPerAxis = 8;
  const ref::SceneDesc object =
      dnrt::testing::twoToneSphere(glm::vec3(0.3f, -0.2f, 0.1f), 1.5f, glm::vec3(0.9f, 0.2f, 0.2f), glm::vec3(0.2f, 0.9f, 0.3f), 6);
  ASSERT_EQ(object.meshes.size(), 2u);
  const BakeResult b = bake(object, fs);
  const std::vector<glm::vec3> t = vertexTransfer(object, b.field.proxies, b.field.radius, fs);
  const ref::SceneBvh bvh{ref::SceneDesc(object)};
  const std::uint32_t offset[2] = {0, std::uint32_t(object.meshes[0].positions.size())};
  const std::size_t N = sampleCount(fs), D = itfDimension(fs), m = std::size_t(fs.proxies), stride = m * kShCount;
  std::vector<double> interp(N * D, 0.0), nearest(N * D, 0.0);
  std::vector<char> inside(N, 0);
  for (std::size_t s = 0; s < N; ++s) {
    const glm::vec3 q = b.field.centre + b.field.radius * samplePosition(fs, s);
    int front = 0, back = 0;
    for (int face = 0; face < 6; ++face)
      for (int y = 0; y < fs.raysPerAxis; ++y)
        for (int x = 0; x < fs.raysPerAxis; ++x) {
          const glm::dvec3 w = sh::cubeTexelDirection(face, x, y, fs.raysPerAxis);
          const double dw = sh::cubeTexelSolidAngle(x, y, fs.raysPerAxis);
          ref::Hit hit;
          if (!bvh.intersect(q, glm::vec3(w), 0.0f, std::numeric_limits<float>::infinity(), hit)) continue;
          if (glm::dot(glm::dvec3(hit.geometricNormal), w) > 0.0) {
            ++back;
            continue;
          }
          ++front;
          const ref::RefMesh& mesh = object.meshes[hit.mesh];
          std::array<std::uint32_t, 3> v{};
          glm::vec3 at(0.0f);
          for (int c = 0; c < 3; ++c) {
            v[std::size_t(c)] = offset[hit.mesh] + mesh.indices[3 * std::size_t(hit.triangle) + std::size_t(c)];
            at += hit.barycentric[c] * mesh.positions[mesh.indices[3 * std::size_t(hit.triangle) + std::size_t(c)]];
          }
          // The Hit's triangle and barycentrics are the hit's: Σ b_c = 1, Σ b_c p_c = the hit point.
          EXPECT_NEAR(hit.barycentric[0] + hit.barycentric[1] + hit.barycentric[2], 1.0f, 1e-6f);
          EXPECT_LT(glm::length(at - hit.position), 1e-5f);
          const int big = int(std::max_element(&hit.barycentric[0], &hit.barycentric[0] + 3) - &hit.barycentric[0]);
          const auto yi = sh::evalBasis<double>(kShOrder, w);  // the first kShCount entries
          for (std::size_t k = 0; k < m; ++k)
            for (int i = 0; i < kShCount; ++i)
              for (int j = 0; j < kShCount; ++j)
                for (int c = 0; c < 3; ++c) {
                  const std::size_t e = k * kShCount + std::size_t(j);
                  double tx = 0.0;
                  for (int corner = 0; corner < 3; ++corner)
                    tx += double(hit.barycentric[corner]) * double(t[v[std::size_t(corner)] * stride + e][c]);
                  const std::size_t out = s * D + itfIndex(int(k), i, j, c);
                  interp[out] += dw * yi[std::size_t(i)] * tx;
                  nearest[out] += dw * yi[std::size_t(i)] * double(t[v[std::size_t(big)] * stride + e][c]);
                }
        }
    if (back > front) inside[s] = 1;
  }
  double largest = 0.0, worst = 0.0, nearestGap = 0.0;
  std::size_t insideCount = 0;
  for (std::size_t s = 0; s < N; ++s) {
    insideCount += std::size_t(inside[s]);
    for (std::size_t d = 0; d < D; ++d) {
      const double want = inside[s] ? 0.0 : interp[s * D + d];
      largest = std::max(largest, std::abs(want));
      worst = std::max(worst, std::abs(double(b.itf[s * D + d]) - want));
      if (!inside[s]) nearestGap = std::max(nearestGap, std::abs(nearest[s * D + d] - want));
    }
  }
  EXPECT_EQ(insideCount, b.stats.insideSamples);
  EXPECT_EQ(insideCount, std::size_t(samplesPerSphere(fs)));  // sphere 0 (0.5 η) lies inside
  ASSERT_GT(largest, 0.0);
  EXPECT_LT(worst, 1e-5 * largest);
  // The check tells the two apart: the largest corner's transfer alone misses by far more.
  EXPECT_GT(nearestGap, 1e-3 * largest);
}

}  // namespace
}  // namespace bounce::gi::rtf
