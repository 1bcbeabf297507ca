#include "engine/gi/dnrt/evaluate.hpp"

#include <algorithm>
#include <cmath>

#include "engine/core/error.hpp"
#include "engine/math/sh.hpp"

namespace bounce::gi::dnrt {

std::array<glm::vec3, 9> toLocal(const std::array<glm::vec3, 9>& c, const glm::mat3& rot) {
  // sh::Rotation(R) maps f to g(ω) = f(Rᵀω); we want g(n) = f(rot·n), so R = rotᵀ.
  const auto r = sh::Rotationf::fromMatrix(glm::transpose(rot));
  std::array<glm::vec3, 9> out{};
  r.apply<glm::vec3>(std::span<const glm::vec3>(c), std::span<glm::vec3>(out));
  return out;
}

std::array<glm::vec3, 9> toLocal(const std::array<glm::vec3, 9>& c, const Placement& placement) {
  std::array<glm::vec3, 9> out{};
  gi::shToLocal<glm::vec3>(placement, std::span<const glm::vec3>(c), std::span<glm::vec3>(out));
  return out;
}

void sampleField(const Field& f, glm::vec3 q, std::span<glm::vec3> out) {
  const int n = f.n(), nc = f.settings.shCount;
  const float inner = f.settings.innerExtent;
  glm::vec3 g = (glm::clamp(q / inner, -1.0f, 1.0f) + 1.0f) * 0.5f * float(n - 1);
  const glm::ivec3 i0 = glm::clamp(glm::ivec3(glm::floor(g)), 0, n - 2);
  const glm::vec3 w = glm::clamp(g - glm::vec3(i0), 0.0f, 1.0f);
  for (int j = 0; j < nc; ++j) out[std::size_t(j)] = glm::vec3(0.0f);
  std::array<glm::vec3, 9> m{};
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 d(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const glm::vec3 wd = glm::mix(1.0f - w, w, glm::vec3(d));
    const float weight = wd.x * wd.y * wd.z;
    if (weight == 0.0f) continue;
    const glm::ivec3 c = i0 + d;
    f.decodeVertex(f.vertexIndex(c.x, c.y, c.z), m);
    for (int j = 0; j < nc; ++j) out[std::size_t(j)] += weight * m[std::size_t(j)];
  }
}

float falloff(const FieldSettings& s, glm::vec3 q) {
  const glm::vec3 a = glm::abs(q);
  const float u = std::max({a.x, a.y, a.z});
  if (u <= s.innerExtent) return 1.0f;
  if (u >= s.outerExtent) return 0.0f;
  const float floorTerm = (s.innerExtent / s.outerExtent) * (s.innerExtent / s.outerExtent);
  const float inv = (s.innerExtent / u) * (s.innerExtent / u);
  return (inv - floorTerm) / (1.0f - floorTerm);
}

glm::vec3 evaluate(const Field& field, const Placement& pl, const std::array<glm::vec3, 9>& c, glm::vec3 r,
                   glm::vec3 nr, glm::vec3 rho) {
  const glm::vec3 q = (glm::vec3(pl.worldToLocal * glm::vec4(r, 1.0f)) - pl.centreLocal) / pl.radiusLocal;
  const float s = falloff(field.settings, q);
  if (s <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 toO = pl.centreWorld - r;
  const float len = glm::length(toO);
  if (!(len > 1e-6f * pl.radiusWorld)) return glm::vec3(0.0f);  // at o: n_o undefined
  const float lamb = std::max(0.0f, glm::dot(toO / len, nr));
  if (lamb == 0.0f) return glm::vec3(0.0f);
  std::array<glm::vec3, 9> m{};
  sampleField(field, q, m);
  glm::vec3 sum(0.0f);
  for (int j = 0; j < field.settings.shCount; ++j) sum += c[std::size_t(j)] * m[std::size_t(j)];
  return rho * (lamb * s) * sum;
}

}  // namespace bounce::gi::dnrt
