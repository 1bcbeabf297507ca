#include "tests/unit/dnrt/test_meshes.hpp"

#include <array>
#include <cmath>
#include <utility>

namespace bounce::gi::dnrt::testing {

namespace {

ref::SceneDesc build(glm::vec3 c, float r, int rings, bool twoTone, glm::vec3 rhoA, glm::vec3 rhoB) {
  ref::SceneDesc s;
  s.materials.push_back(ref::RefMaterial{rhoA});
  s.materials.push_back(ref::RefMaterial{rhoB});
  ref::RefMesh mesh[2];
  mesh[0].material = 0;
  mesh[1].material = 1;
  const double pi = 3.14159265358979323846;
  const int segs = 2 * rings;
  const auto dir = [&](int i, int k) {
    const double th = pi * i / rings, ph = 2.0 * pi * k / segs;
    return glm::dvec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
  };
  for (int i = 0; i < rings; ++i)
    for (int k = 0; k < segs; ++k) {
      const glm::dvec3 q[4] = {dir(i, k), dir(i + 1, k), dir(i + 1, k + 1), dir(i, k + 1)};
      const glm::dvec3 mid = glm::normalize(q[0] + q[1] + q[2] + q[3]);
      ref::RefMesh& m = mesh[twoTone && mid.z < 0.0 ? 1 : 0];
      for (const auto& tri : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
        glm::dvec3 a = q[tri[0]], b = q[tri[1]], d = q[tri[2]];
        if (glm::length(glm::cross(b - a, d - a)) < 1e-12) continue;  // degenerate at the poles
        if (glm::dot(glm::cross(b - a, d - a), a + b + d) < 0.0) std::swap(b, d);  // outward winding
        for (const glm::dvec3& p : {a, b, d}) {
          m.indices.push_back(std::uint32_t(m.positions.size()));
          m.positions.push_back(c + r * glm::vec3(p));
          m.normals.push_back(glm::vec3(p));
        }
      }
    }
  for (auto& m : mesh)
    if (!m.indices.empty()) s.meshes.push_back(std::move(m));
  return s;
}

}  // namespace

ref::SceneDesc sphere(glm::vec3 c, float r, glm::vec3 rho, int rings) { return build(c, r, rings, false, rho, rho); }

ref::SceneDesc twoToneSphere(glm::vec3 c, float r, glm::vec3 rhoTop, glm::vec3 rhoBottom, int rings) {
  return build(c, r, rings, true, rhoTop, rhoBottom);
}

glm::vec3 sphereClosedForm(glm::vec3 rhoR, glm::vec3 L, double dOverR, glm::vec3 rhoS) {
  return rhoR * L * float(1.0 / (dOverR * dOverR)) * (rhoS - 1.0f);
}

}  // namespace bounce::gi::dnrt::testing
