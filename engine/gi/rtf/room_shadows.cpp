#include "engine/gi/rtf/room_shadows.hpp"

#include <algorithm>
#include <limits>

#include "engine/math/sampling.hpp"
#include "engine/math/sh_eval.hpp"
#include "engine/ref/surface_albedo.hpp"

namespace bounce::gi::rtf {

incident::RadianceSH roomShadow(const ref::SceneBvh& level, const PosedOccluders& occluders,
                                std::span<const PosedOccluders::Pose> poses, std::span<const render::LightGpu> lights,
                                glm::vec3 chi, int directions) {
  incident::RadianceSH out{};
  const float weight = float(4.0 * math::kPi) / float(directions);
  for (int s = 0; s < directions; ++s) {
    const glm::vec3 w(math::fibonacciSphere(s, directions));
    ref::Hit hit;
    if (!level.intersect(chi, w, 0.0f, std::numeric_limits<float>::infinity(), hit)) continue;
    const glm::vec3 n = glm::dot(hit.geometricNormal, w) < 0.0f ? hit.geometricNormal : -hit.geometricNormal;
    const glm::vec3 x = hit.position + 1e-4f * n;  // off the surface for its shadow rays
    glm::vec3 lost(0.0f);
    for (const render::LightGpu& light : lights) {
      glm::vec3 toLight;
      float dist = 0.0f;
      const glm::vec3 e = incident::lightIrradiance(light, x, toLight, dist);
      const float cosine = glm::dot(n, toLight);
      if (!(cosine > 0.0f)) continue;
      // What an object blocks is what the probes miss, unless the static level blocks it too (dark in
      // the probes as well). The objects first: their bounding spheres cull most rays, and where nothing
      // is blocked the static ray is not needed.
      const float open = incident::traceVisibility(light, x, 0.0f, [&](glm::vec3 o, glm::vec3 d, float tMax) {
        return occluders.occluded(poses, std::numeric_limits<std::size_t>::max(), o, d, tMax);
      });
      if (!(open < 1.0f)) continue;
      const float seen = incident::traceVisibility(light, x, 0.0f, [&](glm::vec3 o, glm::vec3 d, float tMax) {
        return level.occluded(o, d, 0.0f, tMax);
      });
      lost += e * cosine * seen * (1.0f - open);
    }
    if (lost == glm::vec3(0.0f)) continue;
    const glm::vec3 rho = ref::surfaceAlbedo(level.scene(), hit);  // the texture at the hit, as the probe bake's paths
    const glm::vec3 dL = -(rho / float(math::kPi)) * lost * weight;
    const auto y = sh::evalBasis<float>(3, w);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] += y[i] * dL;
  }
  return out;
}

incident::RadianceSH withRoomShadow(const incident::RadianceSH& L, incident::RadianceSH dL) {
  for (int c = 0; c < 3; ++c)
    if (dL[0][c] < 0.0f && L[0][c] + dL[0][c] < 0.0f) {
      const float k = std::max(L[0][c], 0.0f) / -dL[0][c];  // in [0, 1): what L₀ can give
      for (glm::vec3& v : dL) v[c] *= k;
    }
  incident::RadianceSH out = L;
  for (std::size_t i = 0; i < out.size(); ++i) out[i] += dL[i];
  return out;
}

}  // namespace bounce::gi::rtf
