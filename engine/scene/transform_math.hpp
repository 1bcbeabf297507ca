#pragma once
// Transform and quaternion helpers shared by the scene systems and the renderer.
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/scene/components.hpp"

namespace bounce::scene {

// T * R * S (column vectors): scale, then rotate, then translate.
glm::mat4 toMatrix(const Transform& t);

// Rotation by `angleRad` about unit `axis`, right-handed (counter-clockwise looking down -axis).
glm::quat axisAngle(const glm::vec3& axis, float angleRad);

// Quaternion from glTF-ordered components [x, y, z, w].
glm::quat quatFromXyzw(float x, float y, float z, float w);

// Rotation from Euler angles in degrees applied about X first, then Y, then Z (fixed axes):
// q = qZ * qY * qX.
glm::quat quatFromEulerDeg(const glm::vec3& degrees);

// Spherical linear interpolation along the shorter arc: q and -q are the same rotation, so b is
// negated when dot(a, b) < 0. Falls back to normalised lerp when the quaternions are nearly
// parallel (sin θ → 0). Inputs must be unit quaternions; s in [0, 1].
glm::quat slerpShortest(const glm::quat& a, const glm::quat& b, float s);

// Angle of the rotation q in [0, π], radians.
float rotationAngle(const glm::quat& q);

}  // namespace bounce::scene
