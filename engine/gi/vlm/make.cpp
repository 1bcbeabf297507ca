// Subtractive VLM creation, the geometry part (make.hpp describes the steps).
#include "engine/gi/vlm/make.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/core/error.hpp"

namespace bounce::gi::vlm {
namespace {

// A vertex on a crease sharper than acos(kMinCos) ≈ 78° off its mean normal would need an
// unbounded push to clear every face plane by `offset`; it is pushed offset / kMinCos instead.
constexpr float kMinCos = 0.2f;
// meshopt target error (relative to the mesh extent): the budget is the constraint, so any
// deformation is allowed on the way down to it (the artist judges the result, §3.7).
constexpr float kAnyError = 1.0f;

glm::vec3 faceCross(const std::vector<glm::vec3>& p, const std::uint32_t* t) {
  return glm::cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
}

// Positions welded (exact matches become one vertex, so hard-edge seams can collapse) and
// zero-area triangles dropped.
void weld(const MakeSource& s, std::vector<glm::vec3>& pos, std::vector<std::uint32_t>& idx) {
  std::vector<std::uint32_t> remap(s.positions.size());
  const std::size_t unique = meshopt_generateVertexRemap(remap.data(), s.indices.data(), s.indices.size(),
                                                         s.positions.data(), s.positions.size(), sizeof(glm::vec3));
  pos.resize(unique);
  meshopt_remapVertexBuffer(pos.data(), s.positions.data(), s.positions.size(), sizeof(glm::vec3), remap.data());
  std::vector<std::uint32_t> all(s.indices.size());
  meshopt_remapIndexBuffer(all.data(), s.indices.data(), s.indices.size(), remap.data());
  idx.clear();
  for (std::size_t t = 0; t + 2 < all.size(); t += 3)
    if (glm::length(faceCross(pos, &all[t])) > 0.0f) idx.insert(idx.end(), &all[t], &all[t] + 3);
}

// Angle-weighted vertex normals of a triangle list (the pseudo-normal: independent of how the faces
// around a vertex are triangulated, so a cube corner gets exactly (±1, ±1, ±1)/√3); `firstFace`
// gets the first incident face normal (for vertices whose faces cancel out).
std::vector<glm::vec3> vertexNormals(const std::vector<glm::vec3>& p, const std::vector<std::uint32_t>& idx,
                                     std::vector<glm::vec3>* firstFace = nullptr) {
  std::vector<glm::vec3> n(p.size(), glm::vec3(0.0f));
  if (firstFace) firstFace->assign(p.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    const glm::vec3 f = glm::normalize(faceCross(p, &idx[t]));
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = idx[t + std::size_t(k)];
      const glm::vec3 a = glm::normalize(p[idx[t + std::size_t((k + 1) % 3)]] - p[v]);
      const glm::vec3 b = glm::normalize(p[idx[t + std::size_t((k + 2) % 3)]] - p[v]);
      n[v] += f * std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f));
      if (firstFace && (*firstFace)[v] == glm::vec3(0.0f)) (*firstFace)[v] = f;
    }
  }
  return n;
}

// `idx` reduced to at most `target` triangles (make.hpp, step 2).
std::vector<std::uint32_t> simplify(const std::vector<glm::vec3>& pos, const std::vector<std::uint32_t>& idx,
                                    std::size_t target) {
  if (idx.size() / 3 <= target) return idx;
  std::vector<std::uint32_t> out(idx.size());
  out.resize(meshopt_simplify(out.data(), idx.data(), idx.size(), &pos[0].x, pos.size(), sizeof(glm::vec3), target * 3,
                              kAnyError, 0, nullptr));
  if (out.size() / 3 <= target && !out.empty()) return out;
  std::vector<std::uint32_t> sloppy(idx.size());
  sloppy.resize(meshopt_simplifySloppy(sloppy.data(), idx.data(), idx.size(), &pos[0].x, pos.size(), sizeof(glm::vec3),
                                       target * 3, kAnyError, nullptr));
  if (sloppy.size() / 3 <= target && !sloppy.empty()) return sloppy;
  // Last resort: the `target` largest triangles of the topology-preserving result.
  const std::vector<std::uint32_t>& from = out.empty() ? idx : out;
  std::vector<std::size_t> order(from.size() / 3);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return glm::length(faceCross(pos, &from[3 * a])) > glm::length(faceCross(pos, &from[3 * b]));
  });
  order.resize(target);
  std::sort(order.begin(), order.end());
  std::vector<std::uint32_t> kept;
  for (std::size_t t : order) kept.insert(kept.end(), &from[3 * t], &from[3 * t] + 3);
  return kept;
}

// Shares of the budget, proportional to each source's surface area (light is emitted per unit area:
// a large wall needs more virtual lights than a small detailed prop), at least 1 each, water-filled:
// sources are served in increasing order of triangles per area, so what one cannot use (it has
// fewer triangles than its share) goes to the others.
std::vector<std::size_t> shares(const std::vector<std::size_t>& counts, const std::vector<double>& areas, std::size_t budget) {
  std::vector<std::size_t> order(counts.size()), out(counts.size(), 0);
  std::iota(order.begin(), order.end(), 0);
  auto density = [&](std::size_t i) { return areas[i] > 0.0 ? double(counts[i]) / areas[i] : HUGE_VAL; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return density(a) < density(b); });
  std::size_t left = budget;
  double total = std::accumulate(areas.begin(), areas.end(), 0.0);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k], after = order.size() - k - 1;
    const double fair = total > 0.0 ? double(left) * areas[i] / total : 0.0;
    out[i] = std::clamp<std::size_t>(std::min(counts[i], std::size_t(fair)), 1, left - after);  // left ≥ after + 1 holds
    left -= out[i];
    total -= areas[i];
  }
  return out;
}

}  // namespace

MakeResult makeVlm(std::span<const MakeSource> sources, const MakeOptions& options, const std::string& what) {
  if (sources.empty()) throwInputError(what, "sources", "no real geometry to start from", "at least one mesh");
  if (options.triangles < sources.size())
    throwInputError(what, "--triangles", std::to_string(options.triangles) + " is below the " +
                                             std::to_string(sources.size()) + " source meshes",
                    "a budget of at least one triangle per source");
  if (!std::isfinite(options.offset) || options.offset < 0.0f)
    throwInputError(what, "--offset", "offset " + std::to_string(options.offset), "a finite distance >= 0 in metres");

  std::vector<std::vector<glm::vec3>> welded(sources.size());
  std::vector<std::vector<std::uint32_t>> indices(sources.size());
  std::vector<std::size_t> counts;
  std::vector<double> areas;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    for (std::uint32_t v : sources[i].indices)
      if (v >= sources[i].positions.size())
        throwInputError(what, sources[i].name, "index " + std::to_string(v) + " out of range",
                        "indices below " + std::to_string(sources[i].positions.size()));
    weld(sources[i], welded[i], indices[i]);
    counts.push_back(indices[i].size() / 3);
    double area = 0.0;
    for (std::size_t t = 0; t < indices[i].size(); t += 3) area += 0.5 * double(glm::length(faceCross(welded[i], &indices[i][t])));
    areas.push_back(area);
  }
  const std::vector<std::size_t> share = shares(counts, areas, options.triangles);

  std::uint32_t nextTag = 1;
  for (const auto& s : sources) nextTag = std::max(nextTag, s.tag + 1);
  MakeResult r;
  for (std::size_t i = 0; i < sources.size(); ++i) {
    const auto& pos = welded[i];
    const std::vector<std::uint32_t> kept = simplify(pos, indices[i], share[i]);
    // meshoptimizer 0.18 can leave a few folded-over slivers where border edges of a flat region
    // collapse: a kept triangle facing away from the source surface at its corners (the sum of the
    // source's vertex normals there) would emit backwards, so it is dropped.
    const std::vector<glm::vec3> sourceNormals = vertexNormals(pos, indices[i]);
    MadeMesh m;
    m.source = sources[i].name;
    m.albedo = sources[i].albedo;
    m.tagAssigned = sources[i].tag == 0;
    m.tag = m.tagAssigned ? nextTag++ : sources[i].tag;
    m.inputTriangles = sources[i].indices.size() / 3;
    // Compact to the vertices the kept triangles use.
    std::vector<std::uint32_t> newIndex(pos.size(), UINT32_MAX);
    std::vector<glm::vec3> p;
    for (std::size_t t = 0; t + 2 < kept.size(); t += 3) {
      const glm::vec3 f = faceCross(pos, &kept[t]);
      if (!(glm::length(f) > 0.0f)) continue;  // zero-area sliver
      if (glm::dot(f, sourceNormals[kept[t]] + sourceNormals[kept[t + 1]] + sourceNormals[kept[t + 2]]) <= 0.0f) continue;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = kept[t + std::size_t(k)];
        if (newIndex[v] == UINT32_MAX) {
          newIndex[v] = std::uint32_t(p.size());
          p.push_back(pos[v]);
        }
        m.indices.push_back(newIndex[v]);
      }
    }
    // Vertex normals of the simplified mesh, then the smallest cosine to an incident face (step 3).
    std::vector<glm::vec3> firstFace;
    std::vector<glm::vec3> n = vertexNormals(p, m.indices, &firstFace);
    std::vector<float> minCos(p.size(), 1.0f);
    for (std::size_t v = 0; v < p.size(); ++v)
      n[v] = glm::length(n[v]) > 0.0f ? glm::normalize(n[v]) : firstFace[v];  // opposite faces cancel: use one
    for (std::size_t t = 0; t < m.indices.size(); t += 3) {
      const glm::vec3 f = glm::normalize(faceCross(p, &m.indices[t]));
      for (int k = 0; k < 3; ++k) minCos[m.indices[t + k]] = std::min(minCos[m.indices[t + k]], glm::dot(n[m.indices[t + k]], f));
    }
    for (std::size_t v = 0; v < p.size(); ++v) p[v] -= n[v] * (options.offset / std::max(minCos[v], kMinCos));
    m.positions = std::move(p);
    m.normals = std::move(n);
    r.inputTriangles += m.inputTriangles;
    r.outputTriangles += m.indices.size() / 3;
    r.meshes.push_back(std::move(m));
  }
  return r;
}

}  // namespace bounce::gi::vlm
