#include "engine/math/sh_project.hpp"

#include <cmath>
#include <string>

#include "engine/core/error.hpp"

namespace bounce::sh {

glm::dvec3 cubeTexelDirection(int face, int x, int y, int size) {
  // Face coordinates (sc, tc) in [-1, 1] at the texel centre; the Vulkan table gives, per face,
  // the major axis and which axes (with which signs) sc and tc run along.
  const double u = 2.0 * (x + 0.5) / size - 1.0;
  const double v = 2.0 * (y + 0.5) / size - 1.0;
  glm::dvec3 d;
  switch (face) {
    case 0: d = {1.0, -v, -u}; break;    // +X: sc = -z, tc = -y
    case 1: d = {-1.0, -v, u}; break;    // -X: sc = +z, tc = -y
    case 2: d = {u, 1.0, v}; break;      // +Y: sc = +x, tc = +z
    case 3: d = {u, -1.0, -v}; break;    // -Y: sc = +x, tc = -z
    case 4: d = {u, -v, 1.0}; break;     // +Z: sc = +x, tc = -y
    case 5: d = {-u, -v, -1.0}; break;   // -Z: sc = -x, tc = -y
    default: throw InternalError("cubeTexelDirection: face " + std::to_string(face) + " outside 0..5");
  }
  return glm::normalize(d);
}

double cubeTexelSolidAngle(int x, int y, int size) {
  const auto area = [](double u, double v) { return std::atan2(u * v, std::sqrt(u * u + v * v + 1.0)); };
  const double u0 = 2.0 * x / size - 1.0, u1 = 2.0 * (x + 1) / size - 1.0;
  const double v0 = 2.0 * y / size - 1.0, v1 = 2.0 * (y + 1) / size - 1.0;
  return area(u0, v0) - area(u0, v1) - area(u1, v0) + area(u1, v1);
}

std::vector<glm::dvec3> projectCubeMap(std::span<const glm::vec3> texels, int size, int order) {
  checkOrder(order);
  if (size < 1 || size > 1 << 14 ||
      texels.size() != static_cast<std::size_t>(kCubeFaces) * static_cast<std::size_t>(size) * size)
    throw InternalError("projectCubeMap: " + std::to_string(texels.size()) + " texels for face size " +
                        std::to_string(size) + " (expected 6·size²)");
  std::vector<glm::dvec3> c(static_cast<std::size_t>(coeffCount(order)), glm::dvec3(0.0));
  std::array<double, kMaxCoeffs> yb{};
  std::size_t t = 0;
  for (int face = 0; face < kCubeFaces; ++face)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x, ++t) {
        evalBasis<double>(order, cubeTexelDirection(face, x, y, size), yb);
        const glm::dvec3 value = glm::dvec3(texels[t]) * cubeTexelSolidAngle(x, y, size);
        for (std::size_t i = 0; i < c.size(); ++i) c[i] += value * yb[i];
      }
  return c;
}

}  // namespace bounce::sh
