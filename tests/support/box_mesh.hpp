#pragma once
// A closed axis-aligned box [lo, hi] as 12 triangles (2 per face), outward winding, flat normals,
// one material of albedo rho: the tests' hand-built box (no glTF involved).
#include <cstdint>

#include <glm/glm.hpp>

#include "engine/ref/scene_bvh.hpp"

namespace bounce::testing {

inline ref::SceneDesc boxMesh(glm::vec3 lo, glm::vec3 hi, glm::vec3 rho = glm::vec3(1.0f)) {
  ref::SceneDesc s;
  s.materials.push_back(ref::RefMaterial{rho});
  ref::RefMesh m;
  const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z},
                          {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}};
  // Corner indices of each face, counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    const auto base = std::uint32_t(m.positions.size());
    const glm::vec3 n = glm::normalize(glm::cross(c[f[1]] - c[f[0]], c[f[2]] - c[f[0]]));
    for (int k = 0; k < 4; ++k) m.positions.push_back(c[f[k]]), m.normals.push_back(n);
    for (const std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + k);
  }
  s.meshes.push_back(std::move(m));
  return s;
}

// A square floor [-half, half]² at y = 0 facing +y (2 triangles), one material of albedo rho.
inline ref::SceneDesc floorMesh(float half, glm::vec3 rho) {
  ref::SceneDesc s;
  s.materials.push_back(ref::RefMaterial{rho});
  ref::RefMesh m;
  m.positions = {{-half, 0, -half}, {half, 0, -half}, {-half, 0, half}, {half, 0, half}};
  m.normals.assign(4, glm::vec3(0, 1, 0));
  m.indices = {0, 2, 1, 1, 2, 3};
  s.meshes.push_back(std::move(m));
  return s;
}

}  // namespace bounce::testing
