#pragma once
// Shared helpers for the math tests: deterministic random directions, rotations, coefficients.
#include <cmath>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/math/sampling.hpp"

namespace bounce::testutil {

inline glm::dvec3 randomDirection(math::Pcg32& rng) { return math::uniformSphere(rng.next2D()); }

// Uniformly distributed rotation (Shoemake 1992, "Uniform random rotations", Graphics Gems III).
inline glm::dquat randomQuaternion(math::Pcg32& rng) {
  const double u1 = rng.nextDouble(), u2 = rng.nextDouble(), u3 = rng.nextDouble();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double t1 = 2.0 * math::kPi * u2, t2 = 2.0 * math::kPi * u3;
  return glm::dquat(b * std::cos(t2), a * std::sin(t1), a * std::cos(t1), b * std::sin(t2));  // (w, x, y, z)
}

inline glm::dmat3 randomRotation(math::Pcg32& rng) { return glm::mat3_cast(randomQuaternion(rng)); }

inline std::vector<double> randomCoeffs(math::Pcg32& rng, int count) {
  std::vector<double> c(static_cast<std::size_t>(count));
  for (auto& x : c) x = 2.0 * rng.nextDouble() - 1.0;
  return c;
}

// A rotation taking +Z to the unit vector d: R = I + [k]× + [k]×²/(1 + c), k = ez × d, c = d.z
// (Rodrigues with the sine folded into k); d = -Z takes the half turn about X.
inline glm::dmat3 rotationZTo(const glm::dvec3& d) {
  if (d.z < -1.0 + 1e-12) return glm::dmat3(1, 0, 0, 0, -1, 0, 0, 0, -1);
  const glm::dvec3 k(-d.y, d.x, 0.0);
  // glm is column-major: K's columns are K·ex, K·ey, K·ez with K·v = k × v.
  const glm::dmat3 K(glm::cross(k, {1, 0, 0}), glm::cross(k, {0, 1, 0}), glm::cross(k, {0, 0, 1}));
  return glm::dmat3(1.0) + K + K * K * (1.0 / (1.0 + d.z));
}

}  // namespace bounce::testutil
