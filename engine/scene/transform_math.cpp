#include "engine/scene/transform_math.hpp"

#include <algorithm>
#include <cmath>

namespace bounce::scene {

glm::mat4 toMatrix(const Transform& t) {
  const glm::mat3 r = glm::mat3_cast(t.rotation);
  glm::mat4 m(1.0f);
  for (int c = 0; c < 3; ++c) m[c] = glm::vec4(r[c] * t.scale[c], 0.0f);
  m[3] = glm::vec4(t.translation, 1.0f);
  return m;
}

glm::quat axisAngle(const glm::vec3& axis, float angleRad) {
  const float h = 0.5f * angleRad;
  const float s = std::sin(h);
  return glm::quat(std::cos(h), axis.x * s, axis.y * s, axis.z * s);
}

glm::quat quatFromXyzw(float x, float y, float z, float w) { return glm::quat(w, x, y, z); }

glm::quat quatFromEulerDeg(const glm::vec3& degrees) {
  const glm::vec3 r = glm::radians(degrees);
  const glm::quat qx = axisAngle({1, 0, 0}, r.x);
  const glm::quat qy = axisAngle({0, 1, 0}, r.y);
  const glm::quat qz = axisAngle({0, 0, 1}, r.z);
  return glm::normalize(qz * qy * qx);
}

glm::quat slerpShortest(const glm::quat& a, glm::quat const& bIn, float s) {
  glm::quat b = bIn;
  float cosTheta = glm::dot(a, b);
  if (cosTheta < 0.0f) {
    b = -b;
    cosTheta = -cosTheta;
  }
  // Below this angle sin θ loses precision; lerp and slerp differ by O(θ³) there.
  constexpr float kNlerpCos = 0.9995f;
  if (cosTheta > kNlerpCos) return glm::normalize(a * (1.0f - s) + b * s);
  const float theta = std::acos(std::min(cosTheta, 1.0f));
  const float sinTheta = std::sin(theta);
  const float wa = std::sin((1.0f - s) * theta) / sinTheta;
  const float wb = std::sin(s * theta) / sinTheta;
  return glm::normalize(a * wa + b * wb);
}

float rotationAngle(const glm::quat& q) {
  return 2.0f * std::acos(std::clamp(std::abs(q.w), 0.0f, 1.0f));
}

}  // namespace bounce::scene
