#include "engine/gi/vlm/reference.hpp"

#include <algorithm>
#include <numbers>

#include "engine/gi/incident/incident.hpp"
#include "engine/gi/vlm/form_factor.hpp"

namespace bounce::gi::vlm {

glm::dvec3 samplePoint(const VirtualLight& l, int i) {
  const glm::dvec3 c = (glm::dvec3(l.v0) + glm::dvec3(l.v1) + glm::dvec3(l.v2)) / 3.0;
  if (i == 0) return c;
  const glm::vec3 v = i == 1 ? l.v0 : (i == 2 ? l.v1 : l.v2);
  return 0.5 * (c + glm::dvec3(v));
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
      // The one CPU copy of lights.glsl's irradiance (engine/gi/incident), in float as the pass.
      glm::vec3 toLight;
      float dist = 0.0f;
      const glm::dvec3 ei(incident::lightIrradiance(light, glm::vec3(p), toLight, dist));
      e += ei * std::max(glm::dot(n, glm::dvec3(toLight)), 0.0);
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
