#include "engine/gi/placement.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

namespace bounce::gi {

Placement place(glm::vec3 centreLocal, float radiusLocal, const glm::mat4& world, const char* who) {
  std::optional<Placement> p = tryPlace(centreLocal, radiusLocal, world);
  if (!p) throw InternalError(std::string(who) + ": singular object transform");
  return *p;
}

std::optional<Placement> tryPlace(glm::vec3 centreLocal, float radiusLocal, const glm::mat4& world) {
  Placement p;
  // In double: in float a uniform scale s has det s³ denormal below s ≈ 2e-13 and 0 below s ≈ 1e-15
  // (the inverse turns to Inf), and the column lengths' squares underflow below s ≈ 1e-19.
  const glm::dmat4 worldD(world);
  const glm::dmat3 m(worldD);
  const glm::dvec3 scale(glm::length(m[0]), glm::length(m[1]), glm::length(m[2]));
  const double det = glm::determinant(m);
  const glm::mat4 worldToLocal(glm::inverse(worldD));
  // Every user maps a world point r to the field's unit frame, q = (worldToLocal·r − c)/R_local, in
  // float (DNRT's and RTF's evaluate, their folded GPU matrices): with the map's entries ≤ 1e30, any
  // r and translation within 1e8 world units gives |q| ≤ ~1e38 < FLT_MAX, so nothing downstream
  // overflows to Inf or makes Inf − Inf = NaN. A smaller object (s·R_local < 1e-30) is refused here.
  const glm::dmat4 toUnit = glm::inverse(worldD) / double(radiusLocal);
  bool finite = std::isfinite(det) && det != 0.0 && std::isfinite(radiusLocal) && radiusLocal > 0.0f;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      finite = finite && std::isfinite(world[c][r]) && std::abs(toUnit[c][r]) <= kMaxToUnit;
  if (!finite || !(scale.x > 0 && scale.y > 0 && scale.z > 0)) return std::nullopt;
  // Rotation from the normalised columns through a quaternion, which re-orthonormalises small
  // shears and rounding so sh::Rotation accepts it. A mirror (det < 0) is no rotation: quat_cast
  // would return an unrelated one. Keep −unit (a rotation) and the flag; shToWorld / shToLocal
  // apply the inversion's (−1)^l.
  // The mirror flag from the double determinant that decided validity above, not a float one of the
  // rounded columns (which can disagree with it for a nearly coplanar, badly conditioned matrix).
  const glm::mat3 columns(glm::dmat3(m[0] / scale.x, m[1] / scale.y, m[2] / scale.z));
  p.mirrored = det < 0.0;
  p.localToWorldRotation = glm::mat3_cast(glm::normalize(glm::quat_cast(p.mirrored ? -columns : columns)));
  p.worldToLocal = worldToLocal;
  p.centreLocal = centreLocal;
  p.radiusLocal = radiusLocal;
  p.centreWorld = glm::vec3(world * glm::vec4(centreLocal, 1.0f));
  p.radiusWorld = radiusLocal * float(std::max({scale.x, scale.y, scale.z}));
  return p;
}

}  // namespace bounce::gi
