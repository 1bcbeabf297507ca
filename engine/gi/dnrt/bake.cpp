#include "engine/gi/dnrt/bake.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "engine/core/cache_entry.hpp"
#include "engine/core/error.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/log.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/progress.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"
#include "engine/ref/surface_albedo.hpp"

namespace bounce::gi::dnrt {

namespace {

// Vertices closer to o than this (units of R) have no usable n_o.
constexpr double kCentreEpsilon = 1e-6;

// Fills every invalid vertex from its valid 26-neighbours, sweep by sweep (Jacobi: a sweep reads
// only vertices valid before it, so the result does not depend on visiting order).
void fillInvalid(int n, int shCount, std::vector<glm::vec3>& values, std::vector<char>& valid) {
  const auto at = [n](int x, int y, int z) { return (std::size_t(z) * n + y) * n + x; };
  bool any = std::find(valid.begin(), valid.end(), 1) != valid.end();
  if (!any) return;  // nothing to fill from: leave zeros
  for (;;) {
    std::vector<std::size_t> filled;
    std::vector<glm::vec3> update;
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const std::size_t v = at(x, y, z);
          if (valid[v]) continue;
          std::vector<glm::vec3> sum(std::size_t(shCount), glm::vec3(0.0f));
          int count = 0;
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const int xx = x + dx, yy = y + dy, zz = z + dz;
                if (xx < 0 || yy < 0 || zz < 0 || xx >= n || yy >= n || zz >= n) continue;
                const std::size_t u = at(xx, yy, zz);
                if (!valid[u]) continue;
                for (int j = 0; j < shCount; ++j) sum[std::size_t(j)] += values[u * shCount + j];
                ++count;
              }
          if (count == 0) continue;
          filled.push_back(v);
          for (auto& s : sum) update.push_back(s / float(count));
        }
    if (filled.empty()) return;
    for (std::size_t i = 0; i < filled.size(); ++i) {
      for (int j = 0; j < shCount; ++j) values[filled[i] * shCount + j] = update[i * shCount + j];
      valid[filled[i]] = 1;
    }
  }
}

}  // namespace

BoundingSphere boundingSphere(const ref::SceneDesc& object) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  std::size_t count = 0;
  for (const auto& m : object.meshes)
    for (const auto& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p), ++count;
  if (count == 0) throw InternalError("dnrt: object has no vertices");
  BoundingSphere s;
  s.centre = 0.5f * (lo + hi);
  for (const auto& m : object.meshes)
    for (const auto& p : m.positions) s.radius = std::max(s.radius, glm::length(p - s.centre));
  return s;
}

FieldSettings occlusionSettings(FieldSettings settings) {
  settings.occlusionOnly = true;
  return settings;
}

namespace {

// The quantised field of `values` (filled where `valid` is 0), with its errors.
BakeResult finish(const FieldSettings& settings, const BoundingSphere& sphere, std::vector<glm::vec3> values,
                  std::vector<char> valid) {
  BakeResult result;
  result.insideVertices = std::size_t(std::count(valid.begin(), valid.end(), 0));
  fillInvalid(settings.grid, settings.shCount, values, valid);
  result.field = quantize(settings, sphere.centre, sphere.radius, values);
  result.quantization = quantizationError(result.field, values);
  result.withinAnalyticBound = rangesWithinAnalyticBound(result.field);
  if (!result.withinAnalyticBound)
    log::warn("dnrt: a coefficient range exceeds the estimator's analytic bound (field.hpp analyticRange, "
              "inside the paper's Table 1): the bake is wrong");
  result.values = std::move(values);
  return result;
}

// `settings`' field, and when `occlusion` is set its occlusion-only field from the same rays.
BakeResult bakeFields(const ref::SceneDesc& object, const FieldSettings& settings, BakeResult* occlusion) {
  checkSettings(settings);
  const BoundingSphere sphere = boundingSphere(object);
  if (!(sphere.radius > 0.0f) || !std::isfinite(sphere.radius))
    throw InternalError("dnrt: object has a degenerate bounding sphere");
  ref::SceneDesc desc;
  desc.meshes = object.meshes;
  desc.materials = object.materials;
  desc.textures = object.textures;
  const ref::SceneBvh bvh(std::move(desc));
  const ref::SceneDesc& scene = bvh.scene();

  const int n = settings.grid, nc = settings.shCount, order = nc == 9 ? 3 : 2;
  const std::size_t nv = std::size_t(n) * n * n;
  const int spa = settings.samplesPerAxis;
  const double samples = double(spa) * spa;
  // Anti-radiance scale per band: π/Â_l in the improved mode (header comment), 1 in the paper's.
  std::array<double, 3> kScale{1.0, 1.0, 1.0};
  if (settings.antiRadiance == AntiRadiance::Improved)
    for (int l = 0; l < 3; ++l) kScale[std::size_t(l)] = math::kPi / sh::cosineLobeBand(l);

  std::vector<glm::vec3> values(nv * std::size_t(nc), glm::vec3(0.0f));
  std::vector<glm::vec3> occlusionValues(occlusion ? values.size() : 0, glm::vec3(0.0f));  // −k_j
  std::vector<char> valid(nv, 0);
  const glm::dvec3 o(sphere.centre);
  const double R = sphere.radius;
  Progress progress("dnrt bake", nv);
  parallelFor(0, nv, [&](std::size_t v) {
    const int x = int(v % std::size_t(n)), y = int((v / std::size_t(n)) % std::size_t(n)), z = int(v / (std::size_t(n) * n));
    const glm::dvec3 q = double(settings.innerExtent) * (-1.0 + 2.0 * glm::dvec3(x, y, z) / double(n - 1));
    const double dist = glm::length(q);
    if (dist < kCentreEpsilon) return progress.advance();  // the vertex at o: filled below
    const glm::dvec3 p = o + R * q;
    const glm::dvec3 no = -q / dist;
    math::Pcg32 rng = math::Pcg32::fromIndex(v);
    const auto us = math::stratified2D(spa, rng);
    std::array<glm::dvec3, 9> t{}, k{};
    std::array<double, sh::kMaxCoeffs> yn{}, yw{};
    int front = 0, back = 0;
    for (const glm::dvec2& u : us) {
      const glm::dvec3 w = math::cosineHemisphere(u, no);
      ref::Hit hit;
      if (!bvh.intersect(glm::vec3(p), glm::vec3(w), 0.0f, std::numeric_limits<float>::infinity(), hit)) continue;
      if (glm::dot(glm::dvec3(hit.geometricNormal), w) > 0.0) {
        ++back;  // seen from inside: p is (probably) inside O
        continue;
      }
      ++front;
      glm::dvec3 ns(hit.shadingNormal);
      if (glm::dot(ns, glm::dvec3(hit.geometricNormal)) < 0.0) ns = -ns;  // outward, like the surface
      const glm::dvec3 rho(ref::surfaceAlbedo(scene, hit));
      sh::evalBasis<double>(order, ns, yn);
      sh::evalBasis<double>(order, w, yw);
      for (int j = 0; j < nc; ++j) {
        const int l = j == 0 ? 0 : (j < 4 ? 1 : 2);
        if (!settings.occlusionOnly) t[std::size_t(j)] += yn[std::size_t(j)] * rho;
        k[std::size_t(j)] += glm::dvec3(yw[std::size_t(j)] * kScale[std::size_t(l)]);
      }
    }
    if (back > front) return progress.advance();  // inside O: filled below
    const double norm = 1.0 / (math::kPi * samples);
    for (int j = 0; j < nc; ++j) values[v * nc + std::size_t(j)] = glm::vec3((t[std::size_t(j)] - k[std::size_t(j)]) * norm);
    if (occlusion)  // t_j = 0: the same expression as an occlusionOnly bake, so the same values
      for (int j = 0; j < nc; ++j) occlusionValues[v * nc + std::size_t(j)] = glm::vec3((glm::dvec3(0.0) - k[std::size_t(j)]) * norm);
    valid[v] = 1;
    progress.advance();
  }, 16);
  progress.finish();
  if (occlusion) *occlusion = finish(occlusionSettings(settings), sphere, std::move(occlusionValues), valid);
  return finish(settings, sphere, std::move(values), std::move(valid));
}

}  // namespace

BakeResult bake(const ref::SceneDesc& object, const FieldSettings& settings) {
  return bakeFields(object, settings, nullptr);
}

BakePair bakeWithOcclusion(const ref::SceneDesc& object, const FieldSettings& settings) {
  BakePair pair;
  pair.field = bakeFields(object, settings, &pair.occlusion);
  return pair;
}

namespace {
// Baker and file format version: bump when either changes. v3: objects keyed by their source.
void hashVersionAndSettings(Hasher& h, const FieldSettings& s) {
  h.str("dnrt-field-v3");
  h.pod(s.shCount).pod(s.grid).pod(s.innerExtent).pod(s.outerExtent).pod(s.samplesPerAxis).pod(s.antiRadiance);
  if (s.occlusionOnly) h.str("occlusion-only");  // only when set: the full fields keep their keys
}
}  // namespace

std::string cacheKey(const std::string& objectSourceKey, const FieldSettings& s) {
  Hasher h;
  hashVersionAndSettings(h, s);
  h.str("source").str(objectSourceKey);
  return h.hex();
}

std::string cacheKey(const ref::SceneDesc& object, const FieldSettings& s) {
  if (!object.sourceKey.empty()) return cacheKey(object.sourceKey, s);
  Hasher h;
  hashVersionAndSettings(h, s);
  ref::hashGeometry(h, object);
  return h.hex();
}

std::filesystem::path cachePath(const ref::SceneDesc& object, const FieldSettings& settings,
                                const std::filesystem::path& cacheDir) {
  return cachePath(cacheKey(object, settings), cacheDir);
}

std::filesystem::path cachePath(const std::string& key, const std::filesystem::path& cacheDir) {
  return cacheDir / ("dnrt-" + key + ".field");
}

Field bakeCached(const ref::SceneDesc& object, const FieldSettings& settings, const std::filesystem::path& cacheDir,
                 bool* fromCache) {
  return loadOrBake(
      cachePath(object, settings, cacheDir), "dnrt: rebaking a corrupt cached field: ",
      [](const std::filesystem::path& p) { return load(p); }, [&] { return bake(object, settings).field; },
      [](const Field& f, const std::filesystem::path& p) { save(f, p); }, fromCache);
}

FieldPair bakeCachedWithOcclusion(const ref::SceneDesc& object, const FieldSettings& settings,
                                  const std::filesystem::path& cacheDir, int* baked) {
  const auto loadField = [](const std::filesystem::path& p) { return load(p); };
  const auto saveField = [](const Field& f, const std::filesystem::path& p) { save(f, p); };
  const std::string warning = "dnrt: rebaking a corrupt cached field: ";
  std::optional<Field> occlusionBaked;  // the second field of a pair baked for the first entry
  const auto bakeBoth = [&] {
    BakePair pair = bakeWithOcclusion(object, settings);
    occlusionBaked = std::move(pair.occlusion.field);
    return std::move(pair.field.field);
  };
  bool fieldCached = false, occlusionCached = false;
  FieldPair out;
  out.field = loadOrBake(cachePath(object, settings, cacheDir), warning, loadField, bakeBoth, saveField, &fieldCached);
  out.occlusion = loadOrBake(
      cachePath(object, occlusionSettings(settings), cacheDir), warning, loadField,
      [&] {
        if (!occlusionBaked) bakeBoth();  // the full field came from the cache: trace once for this one
        return std::move(*occlusionBaked);
      },
      saveField, &occlusionCached);
  if (baked) *baked = (fieldCached ? 0 : 1) + (occlusionCached ? 0 : 1);
  return out;
}

CachedFields bakeCachedFor(const ref::SceneDesc& object, const FieldSettings& settings, bool lightsInAntiRadiance,
                           const std::filesystem::path& cacheDir, int* baked) {
  CachedFields out;
  if (lightsInAntiRadiance) {
    bool cached = false;
    out.field = bakeCached(object, settings, cacheDir, &cached);
    if (baked) *baked = cached ? 0 : 1;
  } else {
    FieldPair pair = bakeCachedWithOcclusion(object, settings, cacheDir, baked);
    out.field = std::move(pair.field);
    out.occlusion = std::move(pair.occlusion);
  }
  return out;
}

}  // namespace bounce::gi::dnrt
