#include "engine/gi/sl/bounce_scale.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/gi/sl/evaluate.hpp"
#include "engine/math/sampling.hpp"

namespace bounce::gi::sl {

BounceScales fitBounceScale(const SphereSet& set, const ref::SceneBvh& bvh) {
  const int order = set.settings.order;
  const std::size_t nc = std::size_t(order) * order;
  if (set.spheres.empty() || !(set.boundRadius > 0.0f)) return {};
  // White albedo: c_S = √(4π) Y_00's coefficient, i.e. the constant 1 (Eq. 11 then leaves L_S as is).
  std::vector<float> white(nc * 3, 0.0f);
  for (int ch = 0; ch < 3; ++ch) white[std::size_t(ch)] = float(std::sqrt(4.0 * math::kPi));
  std::vector<Light> lights;
  for (const SlSphere& s : set.spheres) {
    std::vector<glm::dvec3> ones(s.samples.size(), glm::dvec3(1.0));
    std::vector<std::vector<float>> basis;
    for (const SurfaceSample& x : s.samples) basis.push_back(x.basis);
    Light l;
    l.sphere = {glm::dvec3(s.centre), double(s.radius)};
    l.intensity = intensityFromSamples(ones, basis, white, order);
    l.object = 0;
    lights.push_back(std::move(l));
  }
  EvalSettings settings;
  settings.order = order;
  const glm::dvec3 c(set.boundCentre);
  const double R = set.boundRadius;
  double mesh = 0.0, sl = 0.0, unionOmega = 0.0;
  for (double shell : {1.1, 2.0})
    for (int k = 0; k < kBounceScaleDirections; ++k) {
      const glm::dvec3 axis = math::fibonacciSphere(k, kBounceScaleDirections);
      const glm::dvec3 p = c + shell * R * axis, n = -axis;
      for (int i = 0; i < kBounceScaleRays; ++i) {
        const glm::dvec3 d = math::fibonacciSphere(i, kBounceScaleRays);
        const double cs = glm::dot(d, n);
        if (!(cs > 0.0)) continue;
        if (bvh.occluded(glm::vec3(p), glm::vec3(d), 1e-5f * float(R), std::numeric_limits<float>::max()))
          mesh += cs * 4.0 * math::kPi / kBounceScaleRays;
        for (const Light& l : lights) {
          const glm::dvec3 oc = l.sphere.centre - p;
          const double b = glm::dot(oc, d);
          if (b > 0.0 && glm::dot(oc, oc) - b * b < l.sphere.radius * l.sphere.radius) {
            unionOmega += cs * 4.0 * math::kPi / kBounceScaleRays;
            break;
          }
        }
      }
      sl += evaluate(lights, p, n, settings).irradiance.x;
    }
  BounceScales out;
  if (sl > 0.0) out.bounce = std::clamp(mesh / sl, kMinBounceScale, 1.0);
  if (unionOmega > 0.0) out.shadow = std::clamp(mesh / unionOmega, kMinBounceScale, 1.0);
  return out;
}

}  // namespace bounce::gi::sl
