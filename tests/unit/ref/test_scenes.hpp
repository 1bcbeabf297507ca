#pragma once
// Hand-built analytic scenes for the reference tracer tests (no glTF, no cooking).
#include <cmath>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/ref/scene_bvh.hpp"
#include "engine/ref/tracer.hpp"

namespace bounce::ref::test {

// A planar quad with corners c, c+u, c+u+v, c+v (two triangles), normal u×v.
inline RefMesh quad(glm::vec3 c, glm::vec3 u, glm::vec3 v, std::uint32_t material) {
  RefMesh m;
  m.positions = {c, c + u, c + u + v, c + v};
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  m.normals.assign(4, n);
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = material;
  return m;
}

// The inside of the cube [-h, h]³: six quads with normals pointing inwards. Corners on shared
// edges have bit-identical coordinates, which is what Embree's robust mode needs to be watertight.
inline std::vector<RefMesh> insideOfCube(float h, std::uint32_t material) {
  const glm::vec3 x(2 * h, 0, 0), y(0, 2 * h, 0), z(0, 0, 2 * h), lo(-h), hi(h);
  return {quad(lo, z, x, material), quad(hi, -z, -y, material),   // floor y=-h (normal +Y), x=+h (normal -X)
          quad(lo, x, y, material), quad(hi, -x, -z, material),   // back z=-h (normal +Z), ceiling y=+h (normal -Y)
          quad(lo, y, z, material), quad(hi, -y, -x, material)};  // x=-h (normal +X), front z=+h (normal -Z)
}

// Camera at `eye` looking at `target` (world matrix = inverse of the view matrix).
inline RefCamera lookAt(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float yfovDeg) {
  RefCamera c;
  c.world = glm::inverse(glm::lookAtRH(eye, target, up));
  c.yfovRad = glm::radians(yfovDeg);
  c.near = 0.01f;
  c.far = 100.0f;
  return c;
}

inline TraceSettings settings(std::uint32_t size, std::uint32_t spp, std::uint32_t bounces) {
  TraceSettings s;
  s.width = s.height = size;
  s.spp = spp;
  s.bounces = bounces;
  s.label.clear();  // no progress output in tests
  return s;
}

// Where the camera ray of pixel (x, y) meets the plane y = 0; false when it does not (upwards).
inline bool hitFloor(const RefCamera& camera, std::uint32_t size, std::uint32_t x, std::uint32_t y, glm::dvec3& p) {
  const CameraRay r = cameraRay(camera, size, size, x, y);
  if (r.direction.y >= 0.0f) return false;
  const double t = -double(r.origin.y) / double(r.direction.y);
  p = glm::dvec3(r.origin) + t * glm::dvec3(r.direction);
  return true;
}

inline glm::vec3 pixel(const gpu::FloatImage& img, std::uint32_t x, std::uint32_t y) {
  const float* p = &img.rgb[3 * (std::size_t(y) * img.width + x)];
  return {p[0], p[1], p[2]};
}

}  // namespace bounce::ref::test
