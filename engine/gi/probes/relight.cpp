#include "engine/gi/probes/relight.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/log.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/progress.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh.hpp"

namespace bounce::gi::probes {

namespace glsl {
using namespace glm;
// lights.glsl, sh.glsl and relight.glsl compiled as C++ (as engine/gi/incident/incident.cpp does):
// the CPU reference runs the pass's own light and projection code.
using Light = render::LightGpu;
#define BOUNCE_LIGHTS_HOST
#define LIGHTS_OUT(T) T&
#include "shaders/common/lights.glsl"
#define in
#define out
#define inout
#include "shaders/common/sh.glsl"
#include "shaders/probes/relight.glsl"
#undef inout
#undef out
#undef in
#undef LIGHTS_OUT
#undef BOUNCE_LIGHTS_HOST
}  // namespace glsl

std::vector<Surfel> sampleSurfels(const ref::SceneDesc& scene, std::uint32_t count, std::uint64_t seed) {
  struct Tri {
    std::size_t mesh, first;
  };
  std::vector<Tri> tris;
  std::vector<double> cdf;
  double total = 0.0;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const ref::RefMesh& mesh = scene.meshes[m];
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      const glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                      c = mesh.positions[mesh.indices[i + 2]];
      const double area = 0.5 * double(glm::length(glm::cross(b - a, c - a)));
      if (!(area > 0.0)) continue;
      total += area;
      tris.push_back({m, i});
      cdf.push_back(total);
    }
  }
  std::vector<Surfel> out;
  if (tris.empty() || count == 0) return out;
  math::Pcg32 rng(seed);
  out.reserve(count);
  for (std::uint32_t k = 0; k < count; ++k) {
    // Stratified over the area CDF: sample k lies in [k, k+1)/count of the total area.
    const double u = (double(k) + rng.nextDouble()) / double(count) * total;
    const std::size_t t = std::min<std::size_t>(std::size_t(std::lower_bound(cdf.begin(), cdf.end(), u) - cdf.begin()),
                                                tris.size() - 1);
    const ref::RefMesh& mesh = scene.meshes[tris[t].mesh];
    const std::uint32_t i0 = mesh.indices[tris[t].first], i1 = mesh.indices[tris[t].first + 1],
                        i2 = mesh.indices[tris[t].first + 2];
    float r1 = rng.nextFloat();
    const float r2 = rng.nextFloat();
    r1 = std::sqrt(r1);
    const float w0 = 1.0f - r1, w1 = r1 * (1.0f - r2), w2 = r1 * r2;  // uniform barycentrics
    Surfel s;
    s.position = w0 * mesh.positions[i0] + w1 * mesh.positions[i1] + w2 * mesh.positions[i2];
    // The triangle's front side (the path tracer's geometric normal: counter-clockwise winding).
    s.normal = glm::normalize(glm::cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]));
    const ref::RefMaterial& mat = scene.materials[mesh.material];
    glm::vec3 albedo = mat.albedo;
    if (mat.albedoTexture >= 0 && !mesh.uvs.empty())
      albedo *= scene.textures[std::size_t(mat.albedoTexture)].sample(w0 * mesh.uvs[i0] + w1 * mesh.uvs[i1] + w2 * mesh.uvs[i2]);
    s.albedo = glm::clamp(albedo, 0.0f, 1.0f);
    s.area = float(total / double(count));
    out.push_back(s);
  }
  return out;
}

namespace {

// The nearest surfel facing a direction, found through a uniform grid over the surfels instead of
// a scan of all of them. The scan made the bake O(probes · R · surfels): 2744 probes × 256 rays ×
// 4096 surfels = 2.9·10⁹ distance tests on the characters level (60–116 s a volume, stop 25), and
// 7× that on its 0.125 m accuracy grids. With cells of about twice the surfels' mean spacing
// (√(area/count): they lie on surfaces) a query visits a few cells: O(probes · R · a few dozen).
// The result is the scan's exactly: the same nearest (squared distance, ties to the lower index).
class SurfelGrid {
 public:
  explicit SurfelGrid(std::span<const Surfel> surfels) : surfels_(surfels) {
    if (surfels.empty()) return;
    lo_ = hi_ = surfels[0].position;
    double area = 0.0;
    for (const Surfel& s : surfels) {
      lo_ = glm::min(lo_, s.position), hi_ = glm::max(hi_, s.position);
      area += double(s.area);
    }
    const glm::vec3 extent = hi_ - lo_;
    // Cell edge: 2·√(area per surfel), at least 1/256 of the largest extent (bounded cell count);
    // a degenerate set (zero area) gets one cell per axis.
    float h = float(2.0 * std::sqrt(area / double(surfels.size())));
    h = std::max(h, std::max({extent.x, extent.y, extent.z}) / 256.0f);
    if (!(h > 0.0f)) h = 1.0f;
    cell_ = h;
    dims_ = glm::max(glm::ivec3(glm::floor(extent / h)) + 1, glm::ivec3(1));
    const std::size_t cells = std::size_t(dims_.x) * std::size_t(dims_.y) * std::size_t(dims_.z);
    start_.assign(cells + 1, 0u);
    for (const Surfel& s : surfels) ++start_[index(cellOf(s.position)) + 1];
    for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
    items_.resize(surfels.size());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < surfels.size(); ++i) items_[fill[index(cellOf(surfels[i].position))]++] = std::uint32_t(i);
  }

  // The surfel with n·dir < 0 nearest to q (kRelightMiss when none faces dir).
  std::uint32_t nearestFacing(const glm::vec3& q, const glm::vec3& dir) const {
    if (surfels_.empty()) return kRelightMiss;
    // q may lie outside the surfels' box (a hit on a face with no surfel): the distance bound below
    // is then taken from the clamped cell, which is still a lower bound per shell.
    const glm::ivec3 c = cellOf(q);
    const glm::vec3 qc = glm::clamp(q, lo_, hi_);
    const float outside = glm::length(q - qc);  // every surfel is at least this far
    float best = std::numeric_limits<float>::max();
    std::uint32_t bestIndex = kRelightMiss;
    const int maxShell = std::max({dims_.x, dims_.y, dims_.z});
    for (int r = 0; r <= maxShell; ++r) {
      for (int z = c.z - r; z <= c.z + r; ++z) {
        if (z < 0 || z >= dims_.z) continue;
        for (int y = c.y - r; y <= c.y + r; ++y) {
          if (y < 0 || y >= dims_.y) continue;
          const bool rimYZ = z == c.z - r || z == c.z + r || y == c.y - r || y == c.y + r;
          for (int x = c.x - r; x <= c.x + r; x += (rimYZ || r == 0) ? 1 : 2 * r) {
            if (x < 0 || x >= dims_.x) continue;
            const std::size_t cell = index(glm::ivec3(x, y, z));
            for (std::uint32_t k = start_[cell]; k < start_[cell + 1]; ++k) {
              const std::uint32_t s = items_[k];
              const Surfel& sf = surfels_[s];
              if (glm::dot(sf.normal, dir) >= 0.0f) continue;  // must face the ray (towards the probe)
              const glm::vec3 v = sf.position - q;
              const float dd = glm::dot(v, v);
              if (dd < best || (dd == best && s < bestIndex)) best = dd, bestIndex = s;
            }
          }
        }
      }
      // A surfel in a cell outside shell r differs from cell c by more than r cells on some axis,
      // so it is at least r·h from the clamped point qc (which lies in cell c) on that axis; and
      // as qc is q's projection onto the surfels' box, |q − s|² ≥ |q − qc|² + |qc − s|². Stop
      // once best is strictly within that (an equally near surfel of lower index cannot remain).
      const float reach2 = outside * outside + (float(r) * cell_) * (float(r) * cell_);
      if (bestIndex != kRelightMiss && best < reach2) break;
    }
    return bestIndex;
  }

 private:
  glm::ivec3 cellOf(const glm::vec3& p) const {
    return glm::clamp(glm::ivec3(glm::floor((p - lo_) / cell_)), glm::ivec3(0), dims_ - 1);
  }
  std::size_t index(const glm::ivec3& c) const {
    return (std::size_t(c.z) * std::size_t(dims_.y) + std::size_t(c.y)) * std::size_t(dims_.x) + std::size_t(c.x);
  }
  std::span<const Surfel> surfels_;
  glm::vec3 lo_{0.0f}, hi_{0.0f};
  float cell_ = 1.0f;
  glm::ivec3 dims_{1};
  std::vector<std::uint32_t> start_, items_;
};

}  // namespace

std::uint32_t nearestFacingSurfel(std::span<const Surfel> surfels, const glm::vec3& q, const glm::vec3& dir) {
  float best = std::numeric_limits<float>::max();
  std::uint32_t bestIndex = kRelightMiss;
  for (std::size_t s = 0; s < surfels.size(); ++s) {
    const Surfel& sf = surfels[s];
    if (glm::dot(sf.normal, dir) >= 0.0f) continue;  // must face the ray (towards the probe)
    const glm::vec3 v = sf.position - q;
    const float dd = glm::dot(v, v);
    if (dd < best) best = dd, bestIndex = std::uint32_t(s);
  }
  return bestIndex;
}

std::vector<std::uint32_t> nearestFacingSurfels(std::span<const Surfel> surfels, std::span<const glm::vec3> q,
                                                std::span<const glm::vec3> dir) {
  const SurfelGrid g(surfels);
  std::vector<std::uint32_t> out(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) out[i] = g.nearestFacing(q[i], dir[i]);
  return out;
}

namespace {
// Probe i's R ray directions as the probe bake draws them: sh::projectMonteCarlo's strata with
// bakeProbes' seed (probeRaySeed, bake.hpp), so ray k here is its ray k. Regenerated on load rather than stored
// (kRelightVersion 2: a 0.125 m volume of 19 683 probes kept 60 MB of directions in its file).
void probeRayDirections(std::size_t i, std::uint32_t rays, glm::vec3* out) {
  const int perAxis = int(std::lround(std::sqrt(double(rays))));
  math::Pcg32 rng(probeRaySeed(i));
  const std::vector<glm::dvec2> strata = math::stratified2D(perAxis, rng);
  for (std::size_t k = 0; k < rays; ++k) out[k] = k < strata.size() ? glm::vec3(math::uniformSphere(strata[k])) : glm::vec3(0.0f);
}
}  // namespace

RelightData bakeRelight(const ref::SceneBvh& bvh, const ProbeGrid& grid, const ProbeSettings& settings,
                        std::uint32_t surfelCount, const std::string& label) {
  RelightData d;
  d.surfels = sampleSurfels(bvh.scene(), surfelCount);
  const SurfelGrid surfelGrid(d.surfels);
  d.rays = settings.rays;
  const std::size_t probes = grid.probeCount();
  d.dirs.assign(probes * d.rays, glm::vec3(0.0f));
  d.hit.assign(probes * d.rays, kRelightMiss);
  std::optional<Progress> progress;
  if (!label.empty()) progress.emplace(label, probes);
  parallelFor(0, probes, [&](std::size_t i) {
    // The probe bake's point and directions: its virtual offset and its ray k.
    const glm::vec3 p = virtualOffset(bvh, grid.position(i), grid.spacing);
    probeRayDirections(i, d.rays, d.dirs.data() + i * d.rays);
    for (std::size_t k = 0; k < d.rays; ++k) {
      const glm::vec3 dir = d.dirs[i * d.rays + k];
      ref::Hit hit;
      if (!bvh.intersect(p, dir, 0.0f, std::numeric_limits<float>::infinity(), hit)) continue;
      if (glm::dot(hit.geometricNormal, dir) > 0.0f) continue;  // a back face: inside geometry
      d.hit[i * d.rays + k] = surfelGrid.nearestFacing(hit.position, dir);
    }
    if (progress) progress->advance();
  });
  if (progress) progress->finish();
  return d;
}

namespace {
constexpr char kMagic[4] = {'B', 'R', 'L', 'T'};
struct Header {
  char magic[4];
  std::uint32_t version, surfels, rays;
  std::uint64_t probes;
};
template <class T>
void append(std::vector<std::uint8_t>& out, const T* data, std::size_t n) {
  const std::size_t at = out.size();
  out.resize(at + n * sizeof(T));
  if (n) std::memcpy(out.data() + at, data, n * sizeof(T));
}
}  // namespace

std::vector<std::uint8_t> serializeRelight(const RelightData& d) {
  Header h{};
  std::memcpy(h.magic, kMagic, 4);
  h.version = kRelightVersion;
  h.surfels = std::uint32_t(d.surfels.size());
  h.rays = d.rays;
  h.probes = d.probes();
  std::vector<std::uint8_t> out;
  append(out, &h, 1);
  append(out, d.surfels.data(), d.surfels.size());
  append(out, d.hit.data(), d.hit.size());  // the directions are regenerated on load (probeRayDirections)
  const std::uint64_t sum = hashBytes(out);
  append(out, &sum, 1);
  return out;
}

RelightData deserializeRelight(std::span<const std::uint8_t> bytes, const std::string& name) {
  auto fail = [&](const std::string& what) { throwInputError(name, "relight data", what, "a relight cache written by this build"); };
  if (bytes.size() < sizeof(Header) + sizeof(std::uint64_t)) fail("file too short");
  Header h;
  std::memcpy(&h, bytes.data(), sizeof h);
  if (std::memcmp(h.magic, kMagic, 4) != 0) fail("bad magic");
  if (h.version != kRelightVersion) fail("version " + std::to_string(h.version));
  if (h.probes > (1u << 24) || h.rays > 65536 || h.surfels > (1u << 24)) fail("bad header");
  const std::size_t n = std::size_t(h.probes) * h.rays;
  const std::size_t expected = sizeof(Header) + h.surfels * sizeof(Surfel) + n * sizeof(std::uint32_t) + sizeof(std::uint64_t);
  if (bytes.size() != expected) fail("size " + std::to_string(bytes.size()) + ", header implies " + std::to_string(expected));
  std::uint64_t sum;
  std::memcpy(&sum, bytes.data() + expected - sizeof sum, sizeof sum);
  if (sum != hashBytes(bytes.first(expected - sizeof sum))) fail("checksum mismatch");
  RelightData d;
  d.rays = h.rays;
  d.surfels.resize(h.surfels);
  d.dirs.resize(n);
  d.hit.resize(n);
  const std::uint8_t* p = bytes.data() + sizeof(Header);
  std::memcpy(d.surfels.data(), p, h.surfels * sizeof(Surfel));
  p += h.surfels * sizeof(Surfel);
  std::memcpy(d.hit.data(), p, n * sizeof(std::uint32_t));
  for (std::uint32_t x : d.hit)
    if (x != kRelightMiss && x >= h.surfels) fail("surfel index out of range");
  parallelFor(0, std::size_t(h.probes), [&](std::size_t i) { probeRayDirections(i, d.rays, d.dirs.data() + i * d.rays); });
  return d;
}

std::filesystem::path relightCachePath(const BakeInput& input, const ProbeGrid& grid, const std::filesystem::path& probeCache) {
  Hasher h;
  h.str("bounce-probes-relight").u64(kRelightVersion).str(input.key).u64(kRelightSurfels);
  h.pod(grid.origin).pod(grid.spacing).pod(grid.count);
  return probeCache / (input.key + "-relight-" + h.hex() + ".bin");
}

std::optional<RelightData> loadCachedRelight(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) return std::nullopt;
  try {
    return deserializeRelight(readFileBytes(file), file.string());
  } catch (const InputError& e) {
    log::warn(std::string("probes.relight: re-baking: ") + e.what());
    return std::nullopt;
  }
}

RelightData bakeRelightToCache(const BakeInput& input, const ProbeGrid& grid, const std::filesystem::path& probeCache) {
  const ref::SceneBvh bvh{ref::SceneDesc(input.scene)};
  RelightData d = bakeRelight(bvh, grid, input.settings);
  writeFileAtomic(relightCachePath(input, grid, probeCache), serializeRelight(d));
  return d;
}

RelightData loadOrBakeRelight(const BakeInput& input, const ProbeGrid& grid, const std::filesystem::path& probeCache) {
  if (auto cached = loadCachedRelight(relightCachePath(input, grid, probeCache))) return std::move(*cached);
  return bakeRelightToCache(input, grid, probeCache);
}

std::vector<float> staticVisibility(const ref::SceneBvh& bvh, std::span<const Surfel> surfels,
                                    std::span<const render::LightGpu> lights) {
  std::vector<float> v(surfels.size() * lights.size(), 1.0f);
  parallelFor(0, surfels.size(), [&](std::size_t s) {
    const glm::vec3 p = surfels[s].position + 1e-3f * surfels[s].normal;
    for (std::size_t l = 0; l < lights.size(); ++l) {
      glm::vec3 toLight;
      float dist;
      glsl::incidentIrradiance(lights[l], p, toLight, dist);
      const float tMax = dist >= 1e29f ? std::numeric_limits<float>::infinity() : dist * (1.0f - 1e-4f);
      v[s * lights.size() + l] = bvh.occluded(p, toLight, 0.0f, tMax) ? 0.0f : 1.0f;
    }
  });
  return v;
}

glm::vec3 surfelDirectLoss(const Surfel& s, std::size_t index, std::span<const render::LightGpu> lights,
                           std::span<const float> vNow, std::span<const float> vStatic) {
  glm::vec3 e(0.0f);
  for (std::size_t l = 0; l < lights.size(); ++l)
    e += glsl::relightDirectLoss(lights[l], s.position, s.normal, vNow[index * lights.size() + l],
                                 vStatic[index * lights.size() + l]);
  return e;
}

void gatherProbe(const RelightData& data, std::size_t probe, std::span<const glm::vec3> surfelRadiance, glm::vec3 sh[9]) {
  for (int i = 0; i < 9; ++i) sh[i] = glm::vec3(0.0f);
  const float w = float(4.0 * math::kPi / double(data.rays));
  for (std::size_t k = 0; k < data.rays; ++k) {
    const std::uint32_t s = data.hit[probe * data.rays + k];
    if (s == kRelightMiss) continue;
    glsl::relightGatherAdd(data.dirs[probe * data.rays + k], surfelRadiance[s], w, sh);
  }
}

void relightReference(const RelightData& data, const ProbeVolume& volume, std::span<const render::LightGpu> lights,
                      std::span<const float> vNow, std::span<const float> vStatic, int iterations,
                      std::vector<glm::vec3>& delta, std::vector<glm::vec3>* surfelRadiance,
                      std::span<const glm::vec3> slBounce) {
  const std::size_t probes = volume.grid.probeCount();
  delta.resize(probes * 9, glm::vec3(0.0f));
  std::vector<glm::vec3> direct(data.surfels.size()), radiance(data.surfels.size());
  for (std::size_t s = 0; s < data.surfels.size(); ++s) {
    direct[s] = surfelDirectLoss(data.surfels[s], s, lights, vNow, vStatic);
    if (s < slBounce.size()) direct[s] += slBounce[s];  // relight.comp: ΔE += E_SL (sl.relight_bounce)
  }
  ProbeVolume dv = volume;  // the lookup of ΔSH: the volume's grid, weights and visibility, ΔSH as its SH
  dv.order = 3;
  for (int it = 0; it < iterations; ++it) {
    dv.sh = delta;
    for (std::size_t s = 0; s < data.surfels.size(); ++s) {
      const Surfel& sf = data.surfels[s];
      radiance[s] = glsl::relightSurfelRadiance(sf.albedo, direct[s] + dv.irradiance(sf.position, sf.normal));
    }
    for (std::size_t p = 0; p < probes; ++p) {
      glm::vec3 sh[9];
      gatherProbe(data, p, radiance, sh);
      for (int i = 0; i < 9; ++i) delta[p * 9 + std::size_t(i)] = volume.valid[p] != 0u ? sh[i] : glm::vec3(0.0f);
    }
  }
  if (surfelRadiance) *surfelRadiance = radiance;
}

}  // namespace bounce::gi::probes
