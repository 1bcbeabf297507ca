// RTF bake (paper §3.2, §4): proxies, Eq. 3 weights, the vertex transfer, ITF and OOF against
// the closed forms of a diffuse sphere under uniform light, CPCA error as reported, the cache.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/math/sh.hpp"
#include "engine/ref/scene_bvh.hpp"
#include "tests/unit/rtf/half_bound.hpp"
#include "tests/unit/rtf/small_field.hpp"

namespace bounce::gi::rtf {
namespace {

constexpr double kPi = 3.14159265358979323846;
const double kY00 = sh::constants::kY00;

TEST(RtfBake, KmeansFindsTheCentresOfSeparatedBlobs) {
  std::vector<glm::vec3> pts;
  const glm::vec3 c[3] = {{0, 0, 0}, {10, 0, 0}, {0, 10, 5}};
  for (const auto& x : c)
    for (const glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0)}) pts.push_back(x + d);
  const auto k = kmeans(pts, 3);
  ASSERT_EQ(k.size(), 3u);
  for (const auto& x : c) {
    float best = 1e30f;
    for (const auto& y : k) best = std::min(best, glm::length(x - y));
    EXPECT_LT(best, 1e-5f);
  }
  EXPECT_EQ(kmeans(std::vector<glm::vec3>(5, glm::vec3(1.0f)), 4).size(), 1u);  // fewer distinct points than m
}

TEST(RtfBake, ProxyWeightsAtAProxyAreOneHotAndSumToOneAtEveryScale) {
  for (float scale : {1e-3f, 1.0f, 1e3f}) {
    const std::vector<glm::vec3> proxies = {scale * glm::vec3(0, 0, 0), scale * glm::vec3(1, 0, 0), scale * glm::vec3(0, 1, 0)};
    // Distance 0 in Eq. 3: the limit puts all the weight on that proxy.
    const auto w = proxyWeights(proxies[1], proxies, scale);
    EXPECT_EQ(w[0], 0.0f);
    EXPECT_EQ(w[1], 1.0f);
    EXPECT_EQ(w[2], 0.0f);
    const auto v = proxyWeights(scale * glm::vec3(0.3f, 0.2f, 0.1f), proxies, scale);
    float sum = 0.0f;
    for (float x : v) {
      EXPECT_TRUE(std::isfinite(x) && x > 0.0f);
      sum += x;
    }
    EXPECT_NEAR(sum, 1.0f, 1e-6f);
    // Eq. 3 by hand: weights proportional to inverse distances.
    EXPECT_NEAR(v[0] / v[1], glm::length(glm::vec3(0.7f, -0.2f, -0.1f)) / glm::length(glm::vec3(0.3f, 0.2f, 0.1f)), 1e-4f);
  }
}

// A textured vertex's albedo is the texture's hat-weighted mean over its triangles (bake.hpp vertexAlbedo):
// on a unit quad (uv = xy) under a 4 × 4 texture whose 12 border texels are 0.9 and 4 inner ones 0.1,
// every vertex's uv lies where the four border texels meet (0.9: what the transfer held until session 19),
// while the surface's mean is the texels' mean 0.7 (REPEAT bilinear over one period). The lumped sum
// Σ_v ρ_v ∫ b_v dA (∫ b_v dA = A/3 per triangle corner) must be that mean: measured 0.700000 (ρ_v 0.786 at
// the two corners in one triangle, 0.657 at the two in both); 1e-4 allows the midpoint rule's error on the
// bilinear texture's kinks at 8² points a triangle. An untextured material's vertices carry its factor.
TEST(RtfBake, TexturedVertexAlbedoIsTheTexturesAreaMean) {
  ref::SceneDesc s;
  ref::RefTexture tex;
  tex.width = tex.height = 4;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) tex.texels.push_back(glm::vec3((x == 0 || x == 3 || y == 0 || y == 3) ? 0.9f : 0.1f));
  s.textures.push_back(tex);
  s.materials.push_back({glm::vec3(1.0f), 0, glm::vec3(0.0f), -1});
  s.materials.push_back({glm::vec3(0.2f, 0.4f, 1.5f), -1, glm::vec3(0.0f), -1});
  ref::RefMesh quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  quad.normals.assign(4, glm::vec3(0, 0, 1));
  quad.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  quad.indices = {0, 1, 2, 1, 3, 2};
  quad.material = 0;
  s.meshes.push_back(quad);
  quad.material = 1;
  s.meshes.push_back(quad);
  const std::vector<glm::vec3> rho = vertexAlbedo(s);
  ASSERT_EQ(rho.size(), 8u);
  for (std::size_t v = 0; v < 4; ++v) EXPECT_FLOAT_EQ(tex.sample(quad.uvs[v]).x, 0.9f);  // the old per-vertex texel
  // ∫ b_v dA: vertices 0 and 3 are in one triangle each, 1 and 2 in both; each triangle's area 1/2.
  const double share[4] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
  double lumped = 0.0;
  for (std::size_t v = 0; v < 4; ++v) lumped += share[v] * double(rho[v].x);
  EXPECT_NEAR(lumped, 0.7, 1e-4);
  for (std::size_t v = 4; v < 8; ++v) EXPECT_EQ(rho[v], glm::vec3(0.2f, 0.4f, 1.0f)) << v;  // clamped factor
}

TEST(RtfBake, ConvexVertexTransferIsAlbedoTimesY00) {
  // A convex object: every cosine-weighted ray escapes, so under l = (2√π L, 0, …) (uniform L) the
  // outgoing radiance is ρ L exactly: Σ_k t⁰_{p,k,0} = ρ Y_00 (Σ_k w_k = 1, no self bounce).
  const glm::vec3 rho(0.7f, 0.5f, 0.3f);
  const ref::SceneDesc s = testing::unitSphere(rho, 8);
  FieldSettings fs = testing::smallSettings();
  fs.proxies = 3;
  const auto proxies = kmeans(s.meshes[0].positions, 3);
  const auto t = vertexTransfer(s, proxies, 1.0f, fs);
  const std::size_t stride = 3 * kShCount;
  ASSERT_EQ(t.size(), s.meshes[0].positions.size() * stride);
  for (std::size_t p = 0; p < t.size() / stride; ++p) {
    glm::vec3 sum(0.0f);
    for (int k = 0; k < 3; ++k) sum += t[p * stride + std::size_t(k) * kShCount];
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(sum[c], rho[c] * kY00, 1e-6) << p;
  }
}

// An open "L": a floor (z = 0, normal +z) and a wall (x = 0, normal +x), n×n quads each, albedo ρ.
ref::SceneDesc corner(float rho, int n) {
  ref::SceneDesc s;
  s.materials.push_back(ref::RefMaterial{glm::vec3(rho)});
  ref::RefMesh m;
  const auto quad = [&](glm::vec3 o, glm::vec3 u, glm::vec3 v, glm::vec3 nrm) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const glm::vec3 a = o + (float(i) * u + float(j) * v) / float(n), b = a + u / float(n), c = a + (u + v) / float(n),
                        d = a + v / float(n);
        for (const glm::vec3& p : {a, b, c, a, c, d}) {
          m.indices.push_back(std::uint32_t(m.positions.size()));
          m.positions.push_back(p);
          m.normals.push_back(nrm);
        }
      }
  };
  quad(glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1));  // floor, CCW seen from +z
  quad(glm::vec3(0, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0));  // wall, CCW seen from +x
  s.meshes.push_back(std::move(m));
  return s;
}

TEST(RtfBake, SelfInterreflectionBouncesConvergeByTheAlbedo) {
  // Eq. 8's self term on a concave object. Bounce b at p is ρ/S Σ_hits t^{b−1}(x): an average of
  // the previous bounce over at most all of p's rays, times ρ, so max_p t^b ≤ ρ max_x t^{b−1}
  // (l = 0 coefficient summed over proxies; exact, no tolerance but float rounding).
  const float rho = 0.7f;
  const ref::SceneDesc s = corner(rho, 6);
  FieldSettings fs = testing::smallSettings();
  const auto proxies = kmeans(s.meshes[0].positions, fs.proxies);
  std::vector<std::vector<float>> dc;  // dc[b][p]: Σ_k t_{p,k,0} with selfBounces = b
  for (int b = 0; b <= 3; ++b) {
    fs.selfBounces = b;
    const auto t = vertexTransfer(s, proxies, 1.0f, fs);
    const std::size_t stride = std::size_t(fs.proxies) * kShCount;
    std::vector<float> v(t.size() / stride, 0.0f);
    for (std::size_t p = 0; p < v.size(); ++p)
      for (int k = 0; k < fs.proxies; ++k) v[p] += t[p * stride + std::size_t(k) * kShCount].r;
    dc.push_back(v);
  }
  std::vector<float> maxBounce;
  for (int b = 0; b <= 3; ++b) {
    float m = 0.0f;
    for (std::size_t p = 0; p < dc[0].size(); ++p) {
      const float bounce = b == 0 ? dc[0][p] : dc[std::size_t(b)][p] - dc[std::size_t(b - 1)][p];
      EXPECT_GE(bounce, -1e-7f) << b;
      m = std::max(m, bounce);
    }
    maxBounce.push_back(m);
  }
  EXPECT_GT(maxBounce[1], 0.0f);  // the corner does reflect light onto itself
  for (int b = 1; b <= 3; ++b) EXPECT_LE(maxBounce[std::size_t(b)], rho * maxBounce[std::size_t(b - 1)] * (1.0f + 1e-5f)) << b;
  // Bounce 0 is the escaping fraction times ρ Y_00: never more than ρ Y_00.
  EXPECT_LE(maxBounce[0], rho * float(kY00) * (1.0f + 1e-6f));
}

TEST(RtfBake, ItfAndOofMatchTheSphereClosedForms) {
  // Uniform radiance L on a sphere of radius R, albedo ρ: at distance d the sphere fills a cap of
  // Ω = 2π(1 − √(1 − (R/d)²)) with radiance ρL, so the l = 0 coefficient of the light reaching q
  // is Y_00 ρ L Ω and the visibility's is Y_00 (4π − Ω). Error sources: the faceted mesh (48
  // rings: edges sit ≤ 0.1 % inside R, Ω ≈ 0.3 % smaller) and the cube-map quadrature (face 24,
  // 3456 directions): texels on the cap's edge count whole or not, an error that does not average
  // out over the (symmetric) samples (measured +2.6 % and +3.2 % of Ω on spheres 1 and 2):
  // bound 5 % of Ω plus 4 mean texels (Δω = 4π/3456) for the small far caps.
  const glm::vec3 rho(0.8f, 0.6f, 0.4f);
  FieldSettings fs = testing::smallSettings();
  fs.raysPerAxis = 24;
  fs.selfBounces = 0;
  const BakeResult b = bake(testing::unitSphere(rho, 48), fs);
  const Field& f = b.field;
  EXPECT_NEAR(f.radius, 1.0f, 1e-5f);
  const std::size_t D = itfDimension(fs), per = std::size_t(samplesPerSphere(fs));
  EXPECT_EQ(b.stats.insideSamples, per);  // sphere 0 (0.5 R) is inside the object
  const double L = 1.0, l0 = 2.0 * std::sqrt(kPi) * L;
  const double texel = 4.0 * kPi / (6.0 * 24.0 * 24.0);
  for (int sphere = 1; sphere < fs.spheres; ++sphere) {
    const double d = sphereRadius(fs, sphere);
    const double omega = 2.0 * kPi * (1.0 - std::sqrt(1.0 - 1.0 / (d * d)));
    const double omegaTol = 0.05 * omega + 4.0 * texel;
    for (std::size_t s = std::size_t(sphere) * per; s < std::size_t(sphere + 1) * per; ++s) {
      for (int c = 0; c < 3; ++c) {
        double i0 = 0.0;
        for (int k = 0; k < fs.proxies; ++k) i0 += b.itf[s * D + itfIndex(k, 0, 0, c)] * l0;
        const double want = kY00 * rho[c] * L * omega;
        EXPECT_NEAR(i0, want, want * omegaTol / omega) << "sphere " << sphere << " sample " << s;
      }
      const double v0 = f.oof[s * kShCount], want = kY00 * (4.0 * kPi - omega);
      EXPECT_NEAR(v0, want, kY00 * omegaTol) << s;
    }
  }
  // Inside: no light arrives, nothing is visible.
  for (std::size_t s = 0; s < per; ++s) {
    EXPECT_EQ(f.oof[s * kShCount], 0.0f);
    EXPECT_EQ(b.itf[s * D], 0.0f);
  }
}

TEST(RtfBake, ReportedCpcaErrorIsTheFieldsErrorAndShrinksWithComponents) {
  FieldSettings fs = testing::smallSettings();
  fs.components = 1;
  const ref::SceneDesc s = dnrt::testing::twoToneSphere(glm::vec3(0.0f), 1.0f, glm::vec3(0.9f, 0.2f, 0.2f), glm::vec3(0.2f, 0.9f, 0.2f), 8);
  const BakeResult few = bake(s, fs);
  fs.clusters = 1;
  fs.components = 95;  // ≥ N − 1 samples: the centred data's rank, so Eq. 9 is exact
  const BakeResult many = bake(s, fs);
  // The stored error is measure() of the stored compression against the raw ITF.
  EXPECT_DOUBLE_EQ(many.field.frobenius, measure(many.field.itf, many.itf).frobenius);
  EXPECT_DOUBLE_EQ(few.field.frobenius, few.stats.frobenius);
  EXPECT_GT(few.stats.frobenius, many.stats.frobenius);
  // Exact in fp32 (< 1e-5, float rounding); the field holds the fp16 rounding (quantize), whose
  // per-entry bound (half_bound.hpp, from the stored values) bounds the rest of the norm.
  EXPECT_TRUE(isQuantized(many.field.itf));
  const std::size_t D = std::size_t(many.field.itf.dimension);
  double bound2 = 0.0, norm2 = 0.0;
  for (std::size_t r = 0; r < many.field.itf.samples(); ++r)
    for (std::size_t d = 0; d < D; ++d) {
      const double b = testing::halfBound(many.field.itf, r, d, true);
      bound2 += b * b, norm2 += double(many.itf[r * D + d]) * many.itf[r * D + d];
    }
  EXPECT_LT(many.stats.frobenius, 1e-5 + std::sqrt(bound2 / norm2));
  // The error is measured after the rounding (fp32 alone: < 1e-5; measured 2.9e-4 against a bound of
  // 2.2e-3), and the bound is small against what too few components cost (0.75 here).
  EXPECT_GT(many.stats.frobenius, 1e-5);
  EXPECT_LT(std::sqrt(bound2 / norm2), 0.01 * few.stats.frobenius);
  EXPECT_DOUBLE_EQ(many.stats.ratio, storedRatio(many.field.itf));
  EXPECT_NEAR(many.stats.rawMB / many.stats.compressedMB, many.stats.ratio, 1e-9 * many.stats.ratio);
}

TEST(RtfBake, ObjectsOfScale1eMinus3And1e3BakeTheSameField) {
  // The field is in units of η: the same object at 1e-3 m and 1e3 m must give the same M and OOF.
  // Float rounding of the scaled vertices can flip a ray grazing the silhouette: 1e-3 of the field's
  // L1 norm allows a few such texels among the ≈ 96·864 rays. Since a hit takes its triangle's
  // interpolated transfer (session 12), a ray through an edge also switches between the corner copies
  // of the two triangles (this mesh has no shared vertices), which differ by their Monte-Carlo noise:
  // at 6² vertex rays that alone gave 3.3e-3 of the norm (the sphere at the origin sends many
  // texel rays exactly through edges), at 24² rays (4× less noise) it is inside 1e-3 again.
  FieldSettings fs = testing::smallSettings();
  fs.vertexRaysPerAxis = 24;
  const BakeResult unit = bake(dnrt::testing::sphere(glm::vec3(0.0f), 1.0f, glm::vec3(0.7f), 8), fs);
  for (float scale : {1e-3f, 1e3f}) {
    const BakeResult b = bake(dnrt::testing::sphere(glm::vec3(scale * 2.0f), scale, glm::vec3(0.7f), 8), fs);
    EXPECT_NEAR(b.field.radius / scale, 1.0f, 1e-5f);
    double diff = 0.0, norm = 0.0;
    for (std::size_t i = 0; i < unit.itf.size(); ++i) diff += std::abs(double(b.itf[i]) - unit.itf[i]), norm += std::abs(double(unit.itf[i]));
    EXPECT_LT(diff, 1e-3 * norm) << scale;
    double vdiff = 0.0, vnorm = 0.0;
    for (std::size_t i = 0; i < unit.field.oof.size(); ++i)
      vdiff += std::abs(double(b.field.oof[i]) - unit.field.oof[i]), vnorm += std::abs(double(unit.field.oof[i]));
    EXPECT_LT(vdiff, 1e-3 * vnorm) << scale;
    for (float x : b.field.itf.basis) ASSERT_TRUE(std::isfinite(x));
  }
}

TEST(RtfBake, CachedBakeIsReusedAndACorruptCacheIsRebaked) {
  const auto dir = std::filesystem::path(BOUNCE_TEST_OUT) / "rtf-cache-test";
  std::filesystem::remove_all(dir);
  const ref::SceneDesc s = testing::unitSphere(glm::vec3(0.5f), 6);
  const FieldSettings fs = testing::smallSettings();
  bool cached = true;
  const Field a = bakeCached(s, fs, dir, &cached);
  EXPECT_FALSE(cached);
  const Field b = bakeCached(s, fs, dir, &cached);
  EXPECT_TRUE(cached);
  EXPECT_EQ(serialize(a), serialize(b));
  const auto path = cachePath(s, fs, dir);
  EXPECT_EQ(path.filename().string().rfind("rtf-", 0), 0u);
  writeFileAtomic(path, std::string("garbage"));
  const Field c = bakeCached(s, fs, dir, &cached);
  EXPECT_FALSE(cached);
  EXPECT_EQ(serialize(c), serialize(a));  // deterministic bake
  // A file of an older format (version 1: fp32 CPCA) found at the key's path: re-baked as well
  // (its own key, rtf-field-v4, already misses; this is the path for a file copied over).
  auto old = serialize(a);
  const std::uint32_t v1 = 1;
  std::memcpy(old.data() + 8, &v1, 4);
  writeFileAtomic(path, std::span<const std::uint8_t>(old));
  const Field d = bakeCached(s, fs, dir, &cached);
  EXPECT_FALSE(cached);
  EXPECT_EQ(serialize(d), serialize(a));
  EXPECT_EQ(load(path).itf.basis, a.itf.basis);  // the cache entry is version 3 again
  FieldSettings other = fs;
  other.proxies = 3;
  EXPECT_NE(cacheKey(s, fs), cacheKey(s, other));
}

}  // namespace
}  // namespace bounce::gi::rtf
