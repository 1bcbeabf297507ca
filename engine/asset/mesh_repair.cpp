// Repairs made while cooking a primitive. Each one is counted and reported with log::warn, so
// a test (or a user) can tell a repaired asset from a clean one:
//
//  1. Triangles with a NaN or infinite vertex position are dropped; afterwards the vertices no
//     remaining triangle uses are removed (so no non-finite position survives into bounds,
//     normals or the GPU).
//  2. Zero-area (degenerate) triangles are dropped: two equal indices, or a cross product of the
//     edge vectors that is exactly zero in double precision (collinear or coincident corners).
//     They draw nothing, and they would add nothing but rounding noise to generated normals.
//  3. Missing normals are generated, area-weighted (areaWeightedNormals()).
//  4. Triangle strips and fans are converted to lists; points and lines are skipped
//     (gltf_import.cpp warns about those).
#include "engine/asset/mesh_repair.hpp"

#include <cmath>
#include <limits>

namespace bounce::asset::detail {

std::vector<std::uint32_t> toTriangleList(int mode, std::vector<std::uint32_t> indices) {
  if (mode == kModeTriangles) return indices;
  std::vector<std::uint32_t> out;
  if (indices.size() < 3) return out;
  out.reserve((indices.size() - 2) * 3);
  for (std::size_t i = 0; i + 2 < indices.size(); ++i) {
    if (mode == kModeTriangleStrip) {
      // Odd triangles swap their first two corners to keep a consistent winding.
      if (i % 2 == 0) out.insert(out.end(), {indices[i], indices[i + 1], indices[i + 2]});
      else out.insert(out.end(), {indices[i + 1], indices[i], indices[i + 2]});
    } else {  // fan around the first vertex
      out.insert(out.end(), {indices[0], indices[i + 1], indices[i + 2]});
    }
  }
  return out;
}

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

template <class T>
void keepVertices(std::vector<T>& v, const std::vector<std::uint32_t>& newIndex, std::size_t kept) {
  if (v.empty()) return;
  std::vector<T> out(kept);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (newIndex[i] != std::numeric_limits<std::uint32_t>::max()) out[newIndex[i]] = v[i];
  v.swap(out);
}

}  // namespace

RepairCounts repairTriangles(Primitive& p) {
  RepairCounts counts;
  bool anyNonFinite = false;
  for (const auto& q : p.positions) anyNonFinite = anyNonFinite || !finite(q);
  std::vector<std::uint32_t> kept;
  kept.reserve(p.indices.size());
  for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
    const std::uint32_t a = p.indices[t], b = p.indices[t + 1], c = p.indices[t + 2];
    const glm::vec3 pa = p.positions[a], pb = p.positions[b], pc = p.positions[c];
    if (!finite(pa) || !finite(pb) || !finite(pc)) {
      ++counts.nonFinite;
      continue;
    }
    const glm::dvec3 e1 = glm::dvec3(pb) - glm::dvec3(pa), e2 = glm::dvec3(pc) - glm::dvec3(pa);
    const glm::dvec3 n = glm::cross(e1, e2);
    if (a == b || b == c || a == c || (n.x == 0.0 && n.y == 0.0 && n.z == 0.0)) {
      ++counts.degenerate;
      continue;
    }
    kept.insert(kept.end(), {a, b, c});
  }
  p.indices.swap(kept);
  if (!anyNonFinite) return counts;

  const std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> newIndex(p.positions.size(), none);
  std::size_t next = 0;
  for (std::uint32_t& i : p.indices) {
    if (newIndex[i] == none) newIndex[i] = std::uint32_t(next++);
    i = newIndex[i];
  }
  counts.removedVertices = p.positions.size() - next;
  keepVertices(p.positions, newIndex, next);
  keepVertices(p.normals, newIndex, next);
  keepVertices(p.uv0, newIndex, next);
  keepVertices(p.joints, newIndex, next);
  keepVertices(p.weights, newIndex, next);
  keepVertices(p.joints1, newIndex, next);
  keepVertices(p.weights1, newIndex, next);
  for (auto& t : p.targets) {
    keepVertices(t.positions, newIndex, next);
    keepVertices(t.normals, newIndex, next);
  }
  return counts;
}

std::vector<glm::vec3> areaWeightedNormals(const std::vector<glm::vec3>& positions,
                                          const std::vector<std::uint32_t>& indices) {
  std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const glm::dvec3 a(positions[indices[t]]), b(positions[indices[t + 1]]), c(positions[indices[t + 2]]);
    const glm::dvec3 n = glm::cross(b - a, c - a);  // |n| = 2 · area: the weight
    for (int k = 0; k < 3; ++k) sum[indices[t + k]] += n;
  }
  std::vector<glm::vec3> out(positions.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double len = glm::length(sum[i]);
    out[i] = len > 0.0 && std::isfinite(len) ? glm::vec3(sum[i] / len) : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  return out;
}

Bounds meshBounds(const std::vector<Primitive>& primitives) {
  Bounds b{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(-std::numeric_limits<float>::max())};
  bool any = false;
  for (const auto& p : primitives)
    for (const auto& q : p.positions) {
      b.min = glm::min(b.min, q);
      b.max = glm::max(b.max, q);
      any = true;
    }
  return any ? b : Bounds{};
}

}  // namespace bounce::asset::detail
