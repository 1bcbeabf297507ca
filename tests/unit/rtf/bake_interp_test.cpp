// RTF bake, Eq. 6–7 at the hit point (issue 14, session 12): a projection ray's hit takes the
// transfer of its triangle interpolated with Embree's barycentrics, t_x = Σ_c b_c t_{v_c}, as the
// rasteriser shades per-vertex transfer — not its nearest same-facing vertex's t (the bake until
// session 12, which gave 704 of 715 hits on cornell-5's truck roof a covered corner's zero).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "engine/math/sh.hpp"
#include "tests/unit/rtf/small_field.hpp"

namespace bounce::gi::rtf {
namespace {

// Eq. 6–7 evaluated ray by ray in double over the bake's own cube-map directions and samples, two
// ways: `interp` with the hit's transfer Σ_c b_c t_{v_c} (what the bake must give), `nearest` with
// the transfer of the vertex nearest the hit among those whose normal faces the hit's way (the
// old bake's rule, brute force). Samples inside the object (back > front hits) are 0 in both.
struct ReferenceItf {
  std::vector<double> interp, nearest;
  std::vector<char> inside;
};

ReferenceItf referenceItf(const ref::SceneDesc& object, const FieldSettings& fs, const BakeResult& b,
                          const std::vector<glm::vec3>& t) {
  const ref::SceneBvh bvh{ref::SceneDesc(object)};
  std::vector<std::uint32_t> offset;
  std::vector<glm::vec3> position, normal;
  for (const ref::RefMesh& mesh : object.meshes) {
    offset.push_back(std::uint32_t(position.size()));
    position.insert(position.end(), mesh.positions.begin(), mesh.positions.end());
    for (const glm::vec3& n : mesh.normals) normal.push_back(glm::normalize(n));
  }
  const std::size_t N = sampleCount(fs), D = itfDimension(fs), m = std::size_t(fs.proxies), stride = m * kShCount;
  ReferenceItf r{std::vector<double>(N * D, 0.0), std::vector<double>(N * D, 0.0), std::vector<char>(N, 0)};
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
            const std::uint32_t corner = mesh.indices[3 * std::size_t(hit.triangle) + std::size_t(c)];
            v[std::size_t(c)] = offset[hit.mesh] + corner;
            at += hit.barycentric[c] * mesh.positions[corner];
          }
          // The Hit's triangle and barycentrics are the hit's: Σ b_c = 1, Σ b_c p_c = the hit point.
          EXPECT_NEAR(hit.barycentric[0] + hit.barycentric[1] + hit.barycentric[2], 1.0f, 1e-6f);
          EXPECT_LT(glm::length(at - hit.position), 1e-5f * b.field.radius);
          std::uint32_t near = 0;
          float best = std::numeric_limits<float>::infinity();
          for (std::uint32_t u = 0; u < position.size(); ++u) {
            const glm::vec3 d = position[u] - hit.position;
            if (glm::dot(normal[u], hit.geometricNormal) > 0.0f && glm::dot(d, d) < best) best = glm::dot(d, d), near = u;
          }
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
                  r.interp[out] += dw * yi[std::size_t(i)] * tx;
                  r.nearest[out] += dw * yi[std::size_t(i)] * double(t[std::size_t(near) * stride + e][c]);
                }
        }
    if (back > front) {
      r.inside[s] = 1;
      std::fill_n(r.interp.begin() + std::ptrdiff_t(s * D), D, 0.0);
      std::fill_n(r.nearest.begin() + std::ptrdiff_t(s * D), D, 0.0);
    }
  }
  return r;
}

struct Gaps {
  double largest = 0.0, bake = 0.0, nearest = 0.0;  // max |M_ref|, max |M_bake − M_ref|, max |M_nearest − M_ref|
};
Gaps gaps(const BakeResult& b, const ReferenceItf& r) {
  Gaps g;
  for (std::size_t d = 0; d < r.interp.size(); ++d) {
    g.largest = std::max(g.largest, std::abs(r.interp[d]));
    g.bake = std::max(g.bake, std::abs(double(b.itf[d]) - r.interp[d]));
    g.nearest = std::max(g.nearest, std::abs(r.nearest[d] - r.interp[d]));
  }
  return g;
}

TEST(RtfBakeInterp, ItfIsThePerRaySumOfTheTrianglesInterpolatedTransfer) {
  // A faceted two-tone sphere: two meshes (the flattened vertex index is offset by the first
  // mesh's count), unshared corners with smooth normals, so the three corners of a triangle carry
  // different transfer. The bake's regrouped float sum (dense.hpp, one rank-n update per sample)
  // against the double reference: float rounding only, < 1e-5 of the largest |M|.
  FieldSettings fs = testing::smallSettings();
  fs.raysPerAxis = 8;
  const ref::SceneDesc object =
      dnrt::testing::twoToneSphere(glm::vec3(0.3f, -0.2f, 0.1f), 1.5f, glm::vec3(0.9f, 0.2f, 0.2f), glm::vec3(0.2f, 0.9f, 0.3f), 6);
  ASSERT_EQ(object.meshes.size(), 2u);
  const BakeResult b = bake(object, fs);
  const std::vector<glm::vec3> t = vertexTransfer(object, b.field.proxies, b.field.radius, fs);
  const ReferenceItf r = referenceItf(object, fs, b, t);
  const std::size_t insideCount = std::size_t(std::count(r.inside.begin(), r.inside.end(), 1));
  EXPECT_EQ(insideCount, b.stats.insideSamples);
  EXPECT_EQ(insideCount, std::size_t(samplesPerSphere(fs)));  // sphere 0 (0.5 η) lies inside
  const Gaps g = gaps(b, r);
  ASSERT_GT(g.largest, 0.0);
  EXPECT_LT(g.bake, 1e-5 * g.largest);
  // The check tells the two apart: the nearest vertex's transfer alone misses by far more.
  EXPECT_GT(g.nearest, 1e-3 * g.largest);
}

TEST(RtfBakeInterp, BigTriangleWithOneCoveredCornerTakesItsOpenCornersTransfer) {
  // The truck-roof case: one big upward triangle A B C (4 m × 3.5 m, ρ 0.8) whose corner C lies
  // under a small downward-facing lid (0.5 m square, 2 cm above C, ρ 0.5). Without self-bounces
  // (Eq. 8, bounce 0 only) C's cosine rays escape only below atan(0.02/0.25) ≈ 4.6° elevation
  // (cos²(85.4°) = 0.6 % of them), so t_C ≈ 0 while t_A, t_B are open-sky transfers. The lid's
  // vertices face down, so for a hit on the triangle the old rule's nearest same-facing vertex is
  // A, B or C: every hit nearer C than A and B took t_C ≈ 0 whole, and a sample looking at that
  // part of the triangle saw it black, where the rasteriser shades b_A t_A + b_B t_B there. (Over
  // the whole triangle both lose about a third — each corner's barycentric and Voronoi share — so
  // the difference is where the light goes, sample by sample, not how much.) The bake must match
  // the ray-by-ray interpolated reference to float rounding, and the nearest-vertex field must miss
  // it by far more than rounding or noise: measured 0.22 of the largest |M|.
  ref::SceneDesc object;
  object.materials.push_back(ref::RefMaterial{glm::vec3(0.8f)});
  object.materials.push_back(ref::RefMaterial{glm::vec3(0.5f)});
  ref::RefMesh plate, lid;
  const glm::vec3 C(0.0f, 2.0f, 0.0f);
  plate.positions = {glm::vec3(-2.0f, -1.5f, 0.0f), glm::vec3(2.0f, -1.5f, 0.0f), C};  // CCW seen from +z
  plate.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
  plate.indices = {0, 1, 2};
  plate.material = 0;
  const float h = 0.25f, z = 0.02f;
  lid.positions = {C + glm::vec3(-h, -h, z), C + glm::vec3(h, -h, z), C + glm::vec3(h, h, z), C + glm::vec3(-h, h, z)};
  lid.normals.assign(4, glm::vec3(0.0f, 0.0f, -1.0f));
  lid.indices = {0, 2, 1, 0, 3, 2};  // CW seen from +z: faces −z
  lid.material = 1;
  object.meshes = {plate, lid};

  FieldSettings fs = testing::smallSettings();
  fs.raysPerAxis = 8;
  fs.vertexRaysPerAxis = 8;
  fs.selfBounces = 0;
  const BakeResult b = bake(object, fs);
  const std::vector<glm::vec3> t = vertexTransfer(object, b.field.proxies, b.field.radius, fs);
  const std::size_t stride = std::size_t(fs.proxies) * kShCount;
  // DC transfer (j = 0) summed over the proxies: the covered corner's is under 2 % of the open ones'.
  const auto dc = [&](std::size_t vertex) {
    float sum = 0.0f;
    for (std::size_t k = 0; k < std::size_t(fs.proxies); ++k) sum += t[vertex * stride + k * kShCount].r;
    return sum;
  };
  ASSERT_GT(dc(0), 0.1f);
  ASSERT_GT(dc(1), 0.1f);
  ASSERT_LT(dc(2), 0.02f * std::min(dc(0), dc(1)));

  const ReferenceItf r = referenceItf(object, fs, b, t);
  const Gaps g = gaps(b, r);
  ASSERT_GT(g.largest, 0.0);
  EXPECT_LT(g.bake, 1e-5 * g.largest);
  // Nearest-vertex puts C's zero over the hits nearest C: a tenth of the largest entry at least.
  EXPECT_GT(g.nearest, 0.1 * g.largest);
}

}  // namespace
}  // namespace bounce::gi::rtf
