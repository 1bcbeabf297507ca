#include "engine/gi/vlm/reference.hpp"

#include <algorithm>
#include <numbers>

#include "engine/gi/vlm/form_factor.hpp"

namespace bounce::gi::vlm {

glm::dvec3 samplePoint(const VirtualLight& l, int i) {
  const glm::dvec3 c = (glm::dvec3(l.v0) + glm::dvec3(l.v1) + glm::dvec3(l.v2)) / 3.0;
  if (i == 0) return c;
  const glm::vec3 v = i == 1 ? l.v0 : (i == 2 ? l.v1 : l.v2);
  return 0.5 * (c + glm::dvec3(v));
}

glm::dvec3 incidentIrradiance(const render::LightGpu& light, const glm::dvec3& p, glm::dvec3& toLight) {
  const auto type = render::LightType(std::uint32_t(light.positionType.w + 0.5f));
  if (type == render::LightType::Directional) {
    toLight = -glm::dvec3(light.directionRange);
    return glm::dvec3(light.radiance);
  }
  const glm::dvec3 v = glm::dvec3(light.positionType) - p;
  const double d2 = std::max(glm::dot(v, v), 1e-12), d = std::sqrt(d2);
  toLight = v / d;
  glm::dvec3 e = glm::dvec3(light.radiance) / d2;
  if (light.directionRange.w > 0.0f) {  // glTF range window
    const double r = d / light.directionRange.w, w = std::clamp(1.0 - r * r * r * r, 0.0, 1.0);
    e *= w * w;
  }
  if (type == render::LightType::Spot) {
    const double cd = glm::dot(-toLight, glm::dvec3(light.directionRange));
    const double t = std::clamp((cd - light.cone.x) / std::max(double(light.cone.y - light.cone.x), 1e-4), 0.0, 1.0);
    e *= t * t;
  }
  return e;
}

glm::dvec3 emittedRadiance(const VirtualLight& l, std::span<const render::LightGpu> lights, double lift) {
  glm::dvec3 n = glm::cross(glm::dvec3(l.v1) - glm::dvec3(l.v0), glm::dvec3(l.v2) - glm::dvec3(l.v0));
  const double len = glm::length(n);
  if (!(len > 0.0)) return glm::dvec3(0.0);
  n /= len;
  glm::dvec3 e(0.0);
  for (int s = 0; s < kPhase1Samples; ++s) {
    const glm::dvec3 p = samplePoint(l, s) + n * lift;
    for (const auto& light : lights) {
      glm::dvec3 toLight;
      const glm::dvec3 ei = incidentIrradiance(light, p, toLight);
      e += ei * std::max(glm::dot(n, toLight), 0.0);
    }
  }
  return glm::dvec3(l.scale) * (e / double(kPhase1Samples)) / std::numbers::pi;
}

glm::dvec3 irradiance(const glm::dvec3& x, const glm::dvec3& n, std::span<const VirtualLight> lights,
                      std::span<const glm::dvec3> radiance, std::uint32_t tag) {
  glm::dvec3 e(0.0);
  for (std::size_t k = 0; k < lights.size() && k < radiance.size(); ++k) {
    if (tag != 0 && lights[k].tag == tag) continue;
    const double f = formFactor(x, n, glm::dvec3(lights[k].v0), glm::dvec3(lights[k].v1), glm::dvec3(lights[k].v2));
    e += std::numbers::pi * radiance[k] * f;
  }
  return e;
}

}  // namespace bounce::gi::vlm
