#include "engine/gi/placement.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

namespace bounce::gi {

Placement place(glm::vec3 centreLocal, float radiusLocal, const glm::mat4& world, const char* who) {
  Placement p;
  const glm::mat3 m(world);
  const glm::vec3 scale(glm::length(m[0]), glm::length(m[1]), glm::length(m[2]));
  const float det = glm::determinant(m);
  if (!std::isfinite(det) || std::abs(det) < 1e-30f || !(scale.x > 0 && scale.y > 0 && scale.z > 0))
    throw InternalError(std::string(who) + ": singular object transform");
  // Rotation from the normalised columns through a quaternion, which re-orthonormalises small
  // shears and rounding so sh::Rotation accepts it.
  // A mirror (det < 0) is no rotation: quat_cast would return an unrelated one. Keep −unit (a
  // rotation) and the flag; shToWorld / shToLocal apply the inversion's (−1)^l.
  const SignedRotation unit = splitMirror(glm::mat3(m[0] / scale.x, m[1] / scale.y, m[2] / scale.z));
  p.mirrored = unit.mirrored;
  p.localToWorldRotation = glm::mat3_cast(glm::normalize(glm::quat_cast(unit.rotation)));
  p.worldToLocal = glm::inverse(world);
  p.centreLocal = centreLocal;
  p.radiusLocal = radiusLocal;
  p.centreWorld = glm::vec3(world * glm::vec4(centreLocal, 1.0f));
  p.radiusWorld = radiusLocal * std::max({scale.x, scale.y, scale.z});
  return p;
}

}  // namespace bounce::gi
