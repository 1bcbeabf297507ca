#include "engine/gi/probes/bake.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <utility>

#include <glm/gtc/packing.hpp>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/log.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/progress.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/oct_map.hpp"
#include "engine/math/sh.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/scene/systems.hpp"

namespace bounce::gi::probes {

void validate(const ProbeSettings& s, const std::string& file, const std::string& where) {
  if (!(s.spacing > 0.0f) || !std::isfinite(s.spacing))
    throwInputError(file, where + "/spacing", "spacing " + std::to_string(s.spacing), "a finite number > 0 (metres)");
  if (s.order < 2 || s.order > 3)
    throwInputError(file, where + "/order", "SH order " + std::to_string(s.order), "2 or 3");
  const auto n = std::uint32_t(std::lround(std::sqrt(double(s.rays))));
  if (s.rays == 0 || n * n != s.rays || n % kVisRes != 0)
    throwInputError(file, where + "/rays", std::to_string(s.rays) + " rays",
                    "a square whose root is a multiple of " + std::to_string(kVisRes) + ": 64, 256, 576, 1024, …");
}

ProbeGrid gridOverBounds(const glm::vec3& lo, const glm::vec3& hi, float spacing) {
  ProbeGrid g;
  g.spacing = spacing;
  for (int a = 0; a < 3; ++a) {
    const float extent = std::max(0.0f, hi[a] - lo[a]);
    g.count[a] = std::max(1, int(std::ceil(extent / spacing)));
    // Centre the cells on the bounds: the first probe half a spacing in from the low side.
    g.origin[a] = 0.5f * (lo[a] + hi[a]) - 0.5f * spacing * float(g.count[a] - 1);
  }
  return g;
}

glm::vec3 virtualOffset(const ref::SceneBvh& bvh, const glm::vec3& p, float spacing) {
  static const std::vector<glm::dvec3> dirs = math::fibonacciSphere(kOffsetDirections);
  const float minDist = kMinSurfaceDistance * spacing, maxOffset = kMaxOffset * spacing;
  const float reach = maxOffset + minDist;  // nothing farther can matter
  glm::vec3 q = p;
  for (int it = 0; it < kOffsetIterations; ++it) {
    int backfaces = 0;
    std::optional<ref::Hit> nearBack, nearFront;
    for (const glm::dvec3& dd : dirs) {
      const glm::vec3 d(dd);
      ref::Hit hit;
      if (!bvh.intersect(q, d, 0.0f, reach, hit)) continue;
      if (glm::dot(hit.geometricNormal, d) > 0.0f) {
        ++backfaces;
        if (!nearBack || hit.t < nearBack->t) nearBack = hit;
      } else if (!nearFront || hit.t < nearFront->t) {
        nearFront = hit;
      }
    }
    // Moves follow the surface's geometric normal (not the sampled ray), so a probe ends exactly
    // minDist off a plane whatever direction found it.
    glm::vec3 next = q;
    if (double(backfaces) > kBackfaceFraction * kOffsetDirections && nearBack) {
      // Out through the nearest back face's plane (n points out of the solid) to minDist beyond it.
      const float in = glm::dot(nearBack->position - q, nearBack->geometricNormal);
      next = q + nearBack->geometricNormal * (in + minDist);
    } else if (nearFront) {
      const float off = glm::dot(q - nearFront->position, nearFront->geometricNormal);  // distance to its plane
      if (off >= minDist) break;
      next = q + nearFront->geometricNormal * (minDist - off);  // straight away from the nearest front face
    } else {
      break;
    }
    const glm::vec3 offset = next - p;
    const float len = glm::length(offset);
    q = len > maxOffset ? p + offset * (maxOffset / len) : next;
    if (len > maxOffset) break;
  }
  return q;
}

ProbeVolume bakeProbes(const ref::SceneBvh& bvh, const ProbeGrid& grid, const ProbeSettings& settings, BakeStats* stats,
                       const std::string& label) {
  validate(settings, "probes", "settings");
  const auto start = std::chrono::steady_clock::now();
  const std::size_t probes = grid.probeCount();
  const int coeffs = settings.order * settings.order;
  const int perAxis = int(std::lround(std::sqrt(double(settings.rays))));
  const float maxDist = kMaxDistance * grid.spacing;
  const std::vector<glm::dvec3> checkDirs = math::fibonacciSphere(kWindowDirections);

  ProbeVolume v;
  v.grid = grid;
  v.order = settings.order;
  v.sh.assign(probes * coeffs, glm::vec3(0.0f));
  v.moments.assign(probes * kVisBins, glm::vec2(0.0f));
  v.valid.assign(probes, 0u);
  v.dirMap.assign(probes * math::kOctMapTexels * 3, glm::packHalf1x16(0.0f));
  std::vector<glm::vec3> texelDirs(math::kOctMapTexels);
  for (int t = 0; t < math::kOctMapTexels; ++t) texelDirs[std::size_t(t)] = math::octTexelDirection(t);
  const double cosKernel = std::cos(kDirMapKernel);
  std::atomic<std::uint64_t> rays{0}, nonFinite{0};
  std::atomic<std::size_t> invalid{0}, moved{0};
  std::optional<Progress> progress;
  if (!label.empty()) progress.emplace(label, probes);

  parallelFor(0, probes, [&](std::size_t i) {
    const glm::vec3 p = virtualOffset(bvh, grid.position(i), grid.spacing);
    if (p != grid.position(i)) ++moved;
    math::Pcg32 rng = math::Pcg32::fromIndex(i);
    std::uint64_t probeRays = 0, bad = 0;
    std::uint32_t backfaces = 0;
    std::array<double, kVisBins> sum{}, sum2{};
    std::array<std::uint32_t, kVisBins> count{};
    std::vector<std::pair<glm::dvec3, glm::dvec3>> traced;  // every ray's (direction, radiance): the map's
    traced.reserve(settings.rays);
    auto radiance = [&](const glm::dvec3& d) {
      const glm::vec3 dir(d);
      ref::Hit hit;
      bool any = false;
      glm::dvec3 l = ref::tracePathFrom(bvh, p, dir, 0.0f, std::numeric_limits<float>::infinity(), settings.bounces,
                                        rng, probeRays, &hit, &any);
      if (any && glm::dot(hit.geometricNormal, dir) > 0.0f) ++backfaces;
      const double dist = any ? std::min(hit.t, maxDist) : maxDist;
      const int b = visBin(dir);
      sum[b] += dist, sum2[b] += dist * dist, ++count[b];
      // A NaN/Inf sample would poison the probe; none is expected, so count and report it.
      if (!std::isfinite(l.x) || !std::isfinite(l.y) || !std::isfinite(l.z)) ++bad, l = glm::dvec3(0.0);
      traced.push_back({d, l});
      return l;
    };
    std::vector<glm::dvec3> l = sh::projectMonteCarlo(radiance, settings.order, perAxis, probeRaySeed(i));
    rays += probeRays;
    nonFinite += bad;
    if (progress) progress->advance();
    if (double(backfaces) > kBackfaceFraction * settings.rays) {
      ++invalid;  // inside geometry: SH, moments and flag stay 0
      return;
    }
    if (settings.window) {
      const std::vector<glm::dvec3> e = sh::convolveCosine<glm::dvec3>(l);
      const std::optional<double> width = sh::minimalWindow(e, sh::Window::Sloan, checkDirs, 0.0);
      // nullopt only when band 0 itself is negative, impossible for non-negative radiance; keep
      // band 0 alone then (width 1), the most a window can do. +inf: already non-negative.
      if (!width || std::isfinite(*width)) l = sh::applyWindow<glm::dvec3>(l, sh::Window::Sloan, width ? *width : 1.0);
    }
    for (int c = 0; c < coeffs; ++c) v.sh[i * coeffs + c] = glm::vec3(l[c]);
    for (int t = 0; t < math::kOctMapTexels; ++t) {  // the direction map (header), from the same rays
      const glm::dvec3 c(texelDirs[std::size_t(t)]);
      glm::dvec3 sum(0.0), nearest(0.0);
      double total = 0.0, bestCos = -2.0;
      for (const auto& [d, radiance] : traced) {
        const double cs = glm::dot(c, d);
        if (cs > bestCos) bestCos = cs, nearest = radiance;
        const double w = cs - cosKernel;
        if (w > 0.0) sum += w * radiance, total += w;
      }
      const glm::dvec3 texel = total > 0.0 ? sum / total : nearest;
      for (int ch = 0; ch < 3; ++ch)
        v.dirMap[(i * math::kOctMapTexels + std::size_t(t)) * 3 + std::size_t(ch)] =
            glm::packHalf1x16(float(std::min(texel[ch], 65504.0)));
    }
    for (int b = 0; b < kVisBins; ++b) {
      // validate() gives every bin rays/kVisBins rays; an empty bin would read as "open".
      v.moments[i * kVisBins + b] =
          count[b] ? glm::vec2(float(sum[b] / count[b]), float(sum2[b] / count[b])) : glm::vec2(maxDist, maxDist * maxDist);
    }
    v.valid[i] = 1u;
  });
  if (progress) progress->finish();
  if (nonFinite > 0) log::warn("probes: " + std::to_string(nonFinite.load()) + " non-finite path samples dropped");
  if (stats) {
    stats->probes = probes;
    stats->rays = rays.load();
    stats->invalid = invalid.load();
    stats->moved = moved.load();
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return v;
}

scene::Level staticLevel(const scene::Level& level) {
  // Dynamic entities and, transitively, their children (a child of a moving entity moves too).
  std::set<std::string> moving;
  for (bool grew = true; grew;) {
    grew = false;
    for (const auto& e : level.entities) {
      if (moving.count(e.id)) continue;
      if (e.dynamic || e.motion || (e.parent && moving.count(*e.parent))) moving.insert(e.id), grew = true;
    }
  }
  scene::Level out = level;
  out.entities.clear();
  for (const auto& e : level.entities)
    if (!moving.count(e.id)) out.entities.push_back(e);
  return out;
}

namespace {

void hashScene(Hasher& h, const ref::SceneDesc& s) {
  h.u64(s.meshes.size());
  for (const auto& m : s.meshes) {
    h.u64(m.positions.size()).bytes(m.positions.data(), m.positions.size() * sizeof(glm::vec3));
    h.bytes(m.normals.data(), m.normals.size() * sizeof(glm::vec3));
    h.u64(m.uvs.size()).bytes(m.uvs.data(), m.uvs.size() * sizeof(glm::vec2));
    h.u64(m.indices.size()).bytes(m.indices.data(), m.indices.size() * sizeof(std::uint32_t)).u64(m.material);
  }
  h.u64(s.materials.size());
  for (const auto& m : s.materials) h.pod(m.albedo).pod(m.albedoTexture).pod(m.emissive).pod(m.emissiveTexture);
  h.u64(s.textures.size());
  for (const auto& t : s.textures) h.u64(t.width).u64(t.height).bytes(t.texels.data(), t.texels.size() * sizeof(glm::vec3));
  h.u64(s.lights.size());
  for (const auto& l : s.lights)
    h.pod(l.type).pod(l.position).pod(l.direction).pod(l.radiance).pod(l.range).pod(l.cosOuter).pod(l.cosInner);
  h.pod(s.background);
}

}  // namespace

ProbeSettings settingsFrom(const scene::Level& level) {
  ProbeSettings s;
  s.spacing = level.probes.spacing;
  s.order = level.probes.order;
  s.rays = level.probes.rays;
  validate(s, level.source.string(), "/probes");
  return s;
}

ref::SceneDesc staticScene(const scene::Level& level, const std::filesystem::path& cookCache,
                           std::vector<std::string>* assetKeys, bool withTextures) {
  const scene::Level stat = staticLevel(level);
  ecs::Registry registry;
  scene::instantiate(stat, registry);
  scene::transformSystem(registry);
  ref::ReferenceAssets assets;
  assets.load(registry, cookCache);
  // Each asset's content key (never its path): what the probe bake's cache key hashes, sorted.
  if (assetKeys)
    for (const auto& [key, entry] : assets.entries()) assetKeys->push_back(entry.contentKey);
  return ref::extractScene(registry, stat, assets, withTextures);
}

BakeInput prepare(const scene::Level& level, const std::filesystem::path& cookCache, const ProbeSettings& settings) {
  validate(settings, level.source.string(), "/probes");
  BakeInput in;
  in.settings = settings;
  in.source = level.source;
  const scene::Level stat = staticLevel(level);
  std::vector<std::string> assetKeys;
  in.scene = staticScene(level, cookCache, &assetKeys);

  Hasher h;
  h.str("bounce-probes").u64(kBakerVersion).u64(ref::kTracerVersion).u64(kProbeFormatVersion);
  if (!level.source.empty() && std::filesystem::exists(level.source)) {
    const auto bytes = readFileBytes(level.source);
    h.u64(bytes.size()).bytes(bytes.data(), bytes.size());
    in.files.push_back(level.source);
  }
  // The assets by content (source bytes, referenced files, cook options), sorted — never by their
  // absolute paths, so a moved or second checkout finds the same entries.
  std::sort(assetKeys.begin(), assetKeys.end());
  h.u64(assetKeys.size());
  for (const std::string& k : assetKeys) h.str(k);
  for (const auto& e : stat.entities)
    if (e.mesh && std::find(in.files.begin(), in.files.end(), e.mesh->asset) == in.files.end())
      in.files.push_back(e.mesh->asset);
  hashScene(h, in.scene);
  h.pod(settings.spacing).pod(settings.order).u64(settings.rays).u64(settings.bounces).u64(settings.window);
  in.key = h.hex();
  return in;
}

std::filesystem::path cachePath(const BakeInput& input, const std::filesystem::path& probeCache) {
  return probeCache / (input.key + ".bin");
}

std::optional<ProbeVolume> loadCached(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) return std::nullopt;
  try {
    return deserialize(readFileBytes(file), file.string());
  } catch (const InputError& e) {
    log::warn(std::string("probes: re-baking: ") + e.what());
    return std::nullopt;
  }
}

ProbeGrid gridOf(const BakeInput& input) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const auto& m : input.scene.meshes)
    for (const glm::vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  if (lo.x > hi.x) lo = hi = glm::vec3(0.0f);  // no static geometry: one probe at the origin
  return gridOverBounds(lo, hi, input.settings.spacing);
}

LoadResult bakeToCache(const BakeInput& input, const std::filesystem::path& probeCache, bool logBake) {
  LoadResult r;
  r.file = cachePath(input, probeCache);
  const ProbeGrid grid = gridOf(input);
  if (grid.probeCount() > (1u << 22))
    throwInputError(input.source.string(), "/probes/spacing",
                    std::to_string(grid.probeCount()) + " probes over the static bounds", "a larger spacing");
  const ref::SceneBvh bvh{ref::SceneDesc(input.scene)};  // a copy: the input stays reusable
  r.volume = bakeProbes(bvh, grid, input.settings, &r.stats);
  if (logBake)
    log::info("probes: " + std::to_string(r.stats.probes) + " probes × " + std::to_string(input.settings.rays) +
              " rays in " + std::to_string(r.stats.seconds) + " s (" + std::to_string(r.stats.msPerProbe()) +
              " ms/probe, " + std::to_string(r.stats.moved) + " moved out of or off geometry, " +
              std::to_string(r.stats.invalid) + " inside it)");
  writeFileAtomic(r.file, serialize(r.volume));
  return r;
}

LoadResult loadOrBake(const scene::Level& level, const std::filesystem::path& cookCache,
                      const std::filesystem::path& probeCache, const ProbeSettings& settings) {
  const BakeInput input = prepare(level, cookCache, settings);
  LoadResult r;
  r.file = cachePath(input, probeCache);
  if (auto cached = loadCached(r.file)) {
    r.volume = std::move(*cached);
    r.fromCache = true;
    return r;
  }
  return bakeToCache(input, probeCache);
}

}  // namespace bounce::gi::probes
