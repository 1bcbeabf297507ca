#include "engine/gi/rtf/bake.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include "engine/core/cache_entry.hpp"
#include "engine/core/error.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/log.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/progress.hpp"
#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/rtf/dense.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"
#include "engine/ref/surface_albedo.hpp"

namespace bounce::gi::rtf {

namespace {

// The object's vertices flattened over its meshes, with outward normals and albedo.
struct Vertices {
  std::vector<glm::vec3> position, normal, albedo;
  std::vector<std::uint32_t> meshOffset;  // a mesh's first vertex here
};

// Sub-triangles per triangle side for a textured vertex's albedo (kAlbedoSubdivision² points a triangle).
constexpr int kAlbedoSubdivision = 8;

// A vertex's albedo. Untextured: the material's factor. Textured: the texture's mean over the triangles
// around the vertex, each point weighted by the vertex's barycentric (hat) weight b_v:
//   ρ_v = Σ_tri ∫ b_v ρ dA / Σ_tri ∫ b_v dA,
// the lumped-mass projection of ρ onto the per-vertex values the transfer carries and the field
// interpolates over a hit's triangle, so Σ_v ρ_v ∫ b_v dA = ∫ ρ dA: the surface reflects the texture's
// area mean, not the texels that happen to lie at the vertices' uvs (until session 19: textured box 0.658
// against its area mean 0.455, truck 0.238 against 0.414; README "RTF's textured albedo and the bouncing
// step's cost, session 19").
// Each integral by the midpoint rule over the triangle's kAlbedoSubdivision² equal sub-triangles (exact for
// a linear ρ); each point's ρ clamped as gbuffer.frag clamps a pixel's. A vertex in no triangle keeps its
// own uv's texel.
void meshAlbedo(const ref::SceneDesc& o, const ref::RefMesh& m, std::vector<glm::vec3>& out) {
  const ref::RefMaterial* mat = m.material < o.materials.size() ? &o.materials[m.material] : nullptr;
  const bool textured = mat && mat->albedoTexture >= 0 && std::size_t(mat->albedoTexture) < o.textures.size() &&
                        m.uvs.size() == m.positions.size();
  if (!textured) {
    out.insert(out.end(), m.positions.size(), glm::clamp(mat ? mat->albedo : glm::vec3(1.0f), glm::vec3(0.0f), glm::vec3(1.0f)));
    return;
  }
  const auto rho = [&](glm::vec2 uv) { return ref::surfaceAlbedo(o, m.material, uv); };
  for (std::size_t i = 0; i < m.positions.size(); ++i) out.push_back(rho(m.uvs[i]));
  const std::size_t first = out.size() - m.positions.size();
  std::vector<glm::dvec3> sum(m.positions.size(), glm::dvec3(0.0));
  std::vector<double> weight(m.positions.size(), 0.0);
  constexpr int n = kAlbedoSubdivision;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::uint32_t c[3] = {m.indices[t], m.indices[t + 1], m.indices[t + 2]};
    const double area = 0.5 * double(glm::length(glm::cross(m.positions[c[1]] - m.positions[c[0]], m.positions[c[2]] - m.positions[c[0]])));
    if (!(area > 0.0)) continue;
    const auto point = [&](double u, double v) {  // barycentrics (1 − u − v, u, v) of corners 0, 1, 2
      const double b[3] = {1.0 - u - v, u, v};
      const glm::dvec3 r(rho(float(b[0]) * m.uvs[c[0]] + float(b[1]) * m.uvs[c[1]] + float(b[2]) * m.uvs[c[2]]));
      for (int k = 0; k < 3; ++k) sum[c[k]] += area * b[k] * r, weight[c[k]] += area * b[k];
    };
    // The centroids of the n² sub-triangles: n(n+1)/2 pointing like the triangle, n(n−1)/2 the other way.
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        point((double(i) + 1.0 / 3.0) / n, (double(j) + 1.0 / 3.0) / n);
        if (i + j + 1 < n) point((double(i) + 2.0 / 3.0) / n, (double(j) + 2.0 / 3.0) / n);
      }
  }
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    if (weight[i] > 0.0) out[first + i] = glm::vec3(sum[i] / weight[i]);
}

Vertices flatten(const ref::SceneDesc& o) {
  Vertices v;
  for (const auto& m : o.meshes) {
    v.meshOffset.push_back(std::uint32_t(v.position.size()));
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      v.position.push_back(m.positions[i]);
      const glm::vec3 n = i < m.normals.size() ? m.normals[i] : glm::vec3(0.0f);
      v.normal.push_back(glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f, 0.0f, 1.0f));
    }
    meshAlbedo(o, m, v.albedo);
  }
  return v;
}

}  // namespace

std::vector<glm::vec3> vertexAlbedo(const ref::SceneDesc& object) { return flatten(object).albedo; }

namespace {

// The hit point's transfer as the renderer shades it: the rasteriser interpolates the per-vertex
// transfer across a triangle (Sloan et al. 2002 §5, per-vertex PRT), so a ray's hit takes
// Σ_c b_c t_{v_c} over its triangle's three corners with Embree's barycentrics b (Eq. 6–8 at the
// hit point). Until session 12 the hit took its NEAREST vertex's t: piecewise constant in the
// ray direction, which made M_q jump as a sample moved (README "CPCA: interpolated transfer").
struct Corner {
  std::uint32_t vertex;  // index into Vertices (flattened over the meshes)
  float weight;          // barycentric b_c
};
std::array<Corner, 3> corners(const Vertices& v, const ref::SceneDesc& o, const ref::Hit& hit) {
  const std::uint32_t* tri = &o.meshes[hit.mesh].indices[3 * std::size_t(hit.triangle)];
  const std::uint32_t base = v.meshOffset[hit.mesh];
  return {Corner{base + tri[0], hit.barycentric[0]}, Corner{base + tri[1], hit.barycentric[1]},
          Corner{base + tri[2], hit.barycentric[2]}};
}

ref::SceneBvh makeBvh(const ref::SceneDesc& object) {
  ref::SceneDesc desc;
  desc.meshes = object.meshes;
  desc.materials = object.materials;
  desc.textures = object.textures;
  return ref::SceneBvh(std::move(desc));
}

}  // namespace

std::vector<glm::vec3> kmeans(std::span<const glm::vec3> points, int m, int iterations) {
  if (points.empty() || m < 1) throw InternalError("rtf::kmeans: no points or m < 1");
  std::vector<glm::vec3> centres{points[0]};
  std::vector<float> nearest(points.size(), std::numeric_limits<float>::infinity());
  while (int(centres.size()) < m) {
    std::size_t far = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const glm::vec3 d = points[i] - centres.back();
      nearest[i] = std::min(nearest[i], glm::dot(d, d));
      if (nearest[i] > nearest[far]) far = i;
    }
    if (!(nearest[far] > 0.0f)) break;  // fewer distinct points than m
    centres.push_back(points[far]);
  }
  std::vector<std::size_t> owner(points.size(), 0);
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t i = 0; i < points.size(); ++i) {
      float bd = std::numeric_limits<float>::infinity();
      for (std::size_t k = 0; k < centres.size(); ++k) {
        const glm::vec3 d = points[i] - centres[k];
        if (const float d2 = glm::dot(d, d); d2 < bd) bd = d2, owner[i] = k;
      }
    }
    std::vector<glm::dvec3> sum(centres.size(), glm::dvec3(0.0));
    std::vector<std::size_t> count(centres.size(), 0);
    for (std::size_t i = 0; i < points.size(); ++i) sum[owner[i]] += glm::dvec3(points[i]), ++count[owner[i]];
    for (std::size_t k = 0; k < centres.size(); ++k)
      if (count[k] > 0) centres[k] = glm::vec3(sum[k] / double(count[k]));
  }
  return centres;
}

std::vector<float> proxyWeights(glm::vec3 p, std::span<const glm::vec3> proxies, float scale) {
  std::vector<float> w(proxies.size(), 0.0f);
  const float eps = 1e-6f * scale;
  std::size_t onProxy = 0;
  for (std::size_t k = 0; k < proxies.size(); ++k)
    if (glm::length(p - proxies[k]) <= eps) w[k] = 1.0f, ++onProxy;
  if (onProxy > 0) {
    for (float& x : w) x /= float(onProxy);
    return w;
  }
  double sum = 0.0;
  std::vector<double> inv(proxies.size());
  for (std::size_t k = 0; k < proxies.size(); ++k) sum += inv[k] = 1.0 / double(glm::length(p - proxies[k]));
  for (std::size_t k = 0; k < proxies.size(); ++k) w[k] = float(inv[k] / sum);
  return w;
}

std::vector<glm::vec3> vertexTransfer(const ref::SceneDesc& object, std::span<const glm::vec3> proxies, float radius,
                                      const FieldSettings& s) {
  const Vertices v = flatten(object);
  const ref::SceneBvh bvh = makeBvh(object);
  const std::size_t nv = v.position.size(), m = proxies.size(), stride = m * kShCount;
  const int spa = s.vertexRaysPerAxis;
  const double S = double(spa) * spa;
  const float tMin = 1e-4f * radius;
  std::vector<glm::vec3> direct(nv * stride, glm::vec3(0.0f));
  std::vector<std::vector<Corner>> hits(nv);  // front-face hits' triangle corners
  Progress progress("rtf vertex transfer", nv);
  parallelFor(0, nv, [&](std::size_t p) {
    math::Pcg32 rng = math::Pcg32::fromIndex(p);
    const glm::dvec3 n(v.normal[p]);
    std::array<double, kShCount> y{}, sum{};
    for (const glm::dvec2& u : math::stratified2D(spa, rng)) {
      const glm::dvec3 w = math::cosineHemisphere(u, n);
      ref::Hit hit;
      if (!bvh.intersect(v.position[p], glm::vec3(w), tMin, std::numeric_limits<float>::infinity(), hit)) {
        sh::evalBasis<double>(kShOrder, w, y);
        for (int j = 0; j < kShCount; ++j) sum[std::size_t(j)] += y[std::size_t(j)];
      } else if (glm::dot(glm::dvec3(hit.geometricNormal), w) < 0.0) {
        for (const Corner& c : corners(v, object, hit)) hits[p].push_back(c);
      }  // a back face: light from inside the object, none
    }
    const std::vector<float> wk = proxyWeights(v.position[p], proxies, radius);
    for (std::size_t k = 0; k < m; ++k)
      for (int j = 0; j < kShCount; ++j)
        direct[p * stride + k * kShCount + std::size_t(j)] = v.albedo[p] * float(wk[k] * sum[std::size_t(j)] / S);
    progress.advance();
  }, 16);
  progress.finish();
  std::vector<glm::vec3> total = direct, previous = direct;
  for (int b = 0; b < s.selfBounces; ++b) {
    std::vector<glm::vec3> next(nv * stride, glm::vec3(0.0f));
    parallelFor(0, nv, [&](std::size_t p) {
      for (const Corner& c : hits[p])
        for (std::size_t e = 0; e < stride; ++e) next[p * stride + e] += c.weight * previous[std::size_t(c.vertex) * stride + e];
      for (std::size_t e = 0; e < stride; ++e) next[p * stride + e] *= v.albedo[p] / float(S);
    }, 64);
    for (std::size_t e = 0; e < total.size(); ++e) total[e] += next[e];
    previous = std::move(next);
  }
  return total;
}

BakeResult bake(const ref::SceneDesc& object, const FieldSettings& s) {
  checkSettings(s);
  const auto start = std::chrono::steady_clock::now();
  const dnrt::BoundingSphere bs = dnrt::boundingSphere(object);
  if (!(bs.radius > 0.0f) || !std::isfinite(bs.radius)) throw InternalError("rtf: object has a degenerate bounding sphere");
  const Vertices v = flatten(object);
  BakeResult result;
  Field& f = result.field;
  f.settings = s;
  f.centre = bs.centre;
  f.radius = bs.radius;
  f.proxies = kmeans(v.position, s.proxies);
  while (f.proxies.size() < std::size_t(s.proxies)) f.proxies.push_back(f.proxies.back());  // < m distinct vertices
  const std::vector<glm::vec3> t = vertexTransfer(object, f.proxies, bs.radius, s);

  const ref::SceneBvh bvh = makeBvh(object);
  const std::size_t N = sampleCount(s), D = itfDimension(s), m = std::size_t(s.proxies), stride = m * kShCount;
  const int perSphere = samplesPerSphere(s), n2 = s.faceSize * s.faceSize;
  // The projection directions: one cube map's texel centres with their exact solid angles (§4:
  // "6 × 64 × 64 directions on a unit cubemap"), the SAME for every sample, so the integration
  // error varies smoothly from sample to sample (CPCA compresses it) instead of as noise.
  struct Direction {
    glm::dvec3 w;
    double solidAngle;
    std::array<double, kShCount> y;
  };
  std::vector<Direction> directions;
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < s.raysPerAxis; ++y)
      for (int x = 0; x < s.raysPerAxis; ++x) {
        Direction d{sh::cubeTexelDirection(face, x, y, s.raysPerAxis), sh::cubeTexelSolidAngle(x, y, s.raysPerAxis), {}};
        sh::evalBasis<double>(kShOrder, d.w, d.y);
        directions.push_back(d);
      }
  result.itf.assign(N * D, 0.0f);
  f.oof.assign(N * kShCount, 0.0f);
  std::vector<char> inside(N, 0);
  // Eq. 6–7 regrouped by the vertex a ray's hit takes its transfer from:
  //   M^{ij}_{q,k} = Σ_ω Δω y_i(ω) t^j_{p(ω),k} = Σ_v a_{q,v}^i t^j_{v,k},  a_{q,v}^i = Σ_{ω → v} Δω y_i(ω),
  // so a sample costs 16·m·48 multiply-adds per distinct vertex seen instead of per ray (rays that
  // reach the same vertex add their a first), done as one rank-n update in float (dense.hpp).
  const float* tFloats = &t[0].x;  // glm::vec3 rows, m·16·3 floats per vertex: [(k·16 + j)·3 + c]
  const std::size_t width = stride * 3, nVertices = v.position.size();
  constexpr std::size_t kSamplesPerTask = 8;
  Progress progress("rtf field", N);
  parallelFor(0, (N + kSamplesPerTask - 1) / kSamplesPerTask, [&](std::size_t task) {
    std::vector<float> a(nVertices * kShCount, 0.0f);  // a_{q,v}^i, only the touched vertices non-zero
    std::vector<std::uint32_t> seen;
    std::vector<float> packedA, Mi(kShCount * width);  // Mi: [i][(k·16 + j)·3 + c]
    std::vector<const float*> tRows;
    for (std::size_t sample = task * kSamplesPerTask; sample < std::min(N, (task + 1) * kSamplesPerTask); ++sample) {
      const int sphere = int(sample / std::size_t(perSphere)), rest = int(sample % std::size_t(perSphere));
      const int face = rest / n2, x = rest % n2 % s.faceSize, y = rest % n2 / s.faceSize;
      const glm::dvec3 q = glm::dvec3(bs.centre) +
                           double(bs.radius) * double(sphereRadius(s, sphere)) * sh::cubeTexelDirection(face, x, y, s.faceSize);
      std::array<double, kShCount> V{};
      int front = 0, back = 0;
      seen.clear();
      for (const Direction& dir : directions) {
        const glm::dvec3& w = dir.w;
        ref::Hit hit;
        if (!bvh.intersect(glm::vec3(q), glm::vec3(w), 0.0f, std::numeric_limits<float>::infinity(), hit)) {
          for (int i = 0; i < kShCount; ++i) V[std::size_t(i)] += dir.y[std::size_t(i)] * dir.solidAngle;
          continue;
        }
        if (glm::dot(glm::dvec3(hit.geometricNormal), w) > 0.0) {
          ++back;
          continue;
        }
        ++front;
        for (const Corner& c : corners(v, object, hit)) {
          if (!(c.weight > 0.0f)) continue;  // on the opposite edge
          float* av = a.data() + std::size_t(c.vertex) * kShCount;
          if (std::all_of(av, av + kShCount, [](float e) { return e == 0.0f; })) seen.push_back(c.vertex);
          for (int i = 0; i < kShCount; ++i) av[i] += float(dir.y[std::size_t(i)] * dir.solidAngle * double(c.weight));
        }
      }
      if (back > front) {
        inside[sample] = 1;  // M = 0, V = 0: no light reaches a point inside the object
      } else {
        std::sort(seen.begin(), seen.end());  // a fixed summation order: the same field on any thread
        seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
        packedA.resize(seen.size() * kShCount);
        tRows.resize(seen.size());
        for (std::size_t u = 0; u < seen.size(); ++u) {
          std::copy(a.begin() + std::ptrdiff_t(seen[u] * kShCount), a.begin() + std::ptrdiff_t((seen[u] + 1) * kShCount),
                    packedA.begin() + std::ptrdiff_t(u * kShCount));
          tRows[u] = tFloats + std::size_t(seen[u]) * width;
        }
        std::fill(Mi.begin(), Mi.end(), 0.0f);
        dense::addOuter(packedA.data(), tRows.data(), seen.size(), kShCount, width, Mi.data());
        float* out = result.itf.data() + sample * D;
        for (std::size_t k = 0; k < m; ++k)
          for (int i = 0; i < kShCount; ++i)
            std::copy_n(Mi.data() + std::size_t(i) * width + k * kShCount * 3, kShCount * 3, out + itfIndex(int(k), i, 0, 0));
        for (int i = 0; i < kShCount; ++i) f.oof[sample * kShCount + std::size_t(i)] = float(V[std::size_t(i)]);
      }
      for (std::uint32_t vertex : seen) std::fill_n(a.begin() + std::ptrdiff_t(std::size_t(vertex) * kShCount), kShCount, 0.0f);
      progress.advance();
    }
  });
  progress.finish();
  result.stats.insideSamples = std::size_t(std::count(inside.begin(), inside.end(), 1));

  CpcaSettings cs;
  cs.clusters = s.clusters;
  cs.components = s.components;
  f.itf = compress(result.itf, D, cs);
  quantize(f.itf, s.byteComponents);  // what the field file holds; the error below is the stored field's
  const CpcaError e = measure(f.itf, result.itf);
  f.frobenius = e.frobenius;
  result.stats.frobenius = e.frobenius;
  result.stats.ratio = e.stored;
  result.stats.rawMB = double(N * D) * 4.0 / 1e6;
  result.stats.compressedMB = result.stats.rawMB / e.stored;
  result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::string cacheKey(const ref::SceneDesc& object, const FieldSettings& s) {
  Hasher h;
  h.str("rtf-field-v9");  // baker and file format version: bump when either changes (v2: cube-map projection directions; v3: warm-started CPCA; v4: CPCA on lines, k-means++ seeds, float products; v5: fp16 basis and α, file version 2; v6: burned by two unmerged session-11 experiments; v7: a hit's transfer interpolated over its triangle, not its nearest vertex's; v8: byteComponents, file version 3; v9: a textured vertex's albedo the texture's hat-weighted mean over its triangles, not its uv's texel)
  h.pod(s.proxies).pod(s.spheres).pod(s.faceSize).pod(s.innerRadius).pod(s.outerRadius).pod(s.raysPerAxis);
  h.pod(s.vertexRaysPerAxis).pod(s.selfBounces).pod(s.clusters).pod(s.components).pod(s.byteComponents);
  ref::hashGeometry(h, object);
  return h.hex();
}

std::filesystem::path cachePath(const ref::SceneDesc& object, const FieldSettings& s, const std::filesystem::path& dir) {
  return dir / ("rtf-" + cacheKey(object, s) + ".field");
}

Field bakeCached(const ref::SceneDesc& object, const FieldSettings& s, const std::filesystem::path& dir, bool* fromCache) {
  return loadOrBake(
      cachePath(object, s, dir), "rtf: rebaking a corrupt cached field: ",
      [](const std::filesystem::path& p) { return load(p); }, [&] { return bake(object, s).field; },
      [](const Field& f, const std::filesystem::path& p) { save(f, p); }, fromCache);
}

}  // namespace bounce::gi::rtf
