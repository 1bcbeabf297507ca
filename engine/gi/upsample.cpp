#include "engine/gi/upsample.hpp"

#include <algorithm>
#include <cmath>

namespace bounce::gi {

UpsampleTaps upsampleTaps(glm::ivec2 pixel, int step, glm::ivec2 reduced, glm::ivec2 full) {
  UpsampleTaps t;
  const glm::ivec2 j0 = pixel / step;  // pixel ≥ 0: the floor
  t.f = glm::dvec2(pixel - step * j0) / double(step);
  for (int k = 0; k < 4; ++k) {
    t.j[std::size_t(k)] = glm::min(j0 + glm::ivec2(k & 1, k >> 1), reduced - 1);
    t.q[std::size_t(k)] = glm::min(step * t.j[std::size_t(k)], full - 1);
  }
  return t;
}

double upsampleMatch(const glm::dvec3& p, const glm::dvec3& n, double eye, const UpsampleSample& s) {
  const double plane = std::abs(glm::dot(n, s.p - p)) / (eye * kUpsamplePlaneScale);
  const double c = std::max(glm::dot(n, s.n), 0.0), c2 = c * c, c4 = c2 * c2;  // c^kUpsampleNormalPower
  static_assert(kUpsampleNormalPower == 8.0, "upsample.glsl squares three times");
  return s.valid ? std::exp(-plane * plane) * (c4 * c4) : 0.0;
}

glm::dvec3 upsampleBlend(const glm::dvec3& p, const glm::dvec3& n, double eye, glm::dvec2 f,
                         const std::array<UpsampleSample, 4>& taps) {
  glm::dvec3 sum(0.0), best(0.0);
  double weight = 0.0, bestMatch = 0.0;
  for (int k = 0; k < 4; ++k) {
    const UpsampleSample& s = taps[std::size_t(k)];
    const double match = upsampleMatch(p, n, eye, s);
    const double bilinear = ((k & 1) ? f.x : 1.0 - f.x) * ((k >> 1) ? f.y : 1.0 - f.y);
    sum += bilinear * match * s.e;
    weight += bilinear * match;
    if (match > bestMatch) {
      bestMatch = match;
      best = s.e;
    }
  }
  return weight > kUpsampleMinWeight ? sum / weight : best;
}

}  // namespace bounce::gi
