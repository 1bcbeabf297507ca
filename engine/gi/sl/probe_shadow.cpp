#include "engine/gi/sl/probe_shadow.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/math/oct_map.hpp"
#include "engine/math/sh_convolve.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_exp.hpp"
#include "engine/math/sh_product.hpp"

namespace bounce::gi::sl {

ProbeShadow probeShadow(std::span<const Light> lights, const glm::dvec3& p, const glm::dvec3& n,
                        std::span<const glm::dvec3> radiance, const ShadowSettings& settings) {
  const int lOrder = sh::orderFromCount(radiance.size());
  if (lOrder != 2 && lOrder != 3)
    throw InternalError("sl::probeShadow: the probes' SH has " + std::to_string(radiance.size()) + " coefficients (expected 4 or 9)");
  const int order = settings.order;
  ProbeShadow out;
  out.unshadowed = sh::evalIrradiance<glm::dvec3, double>(radiance, n);

  // Eq. 6: V with every SL as a blocker.
  const std::vector<double> v = environmentVisibility(lights, p, n, order, settings.log, settings.influence);
  // P = V ∗ ĉ_n onto L's order; E_s = Σ L_j P_j (Eq. 3's triple product).
  std::vector<double> lobe(9, 0.0);
  const auto y = sh::evalBasis<double>(3, n);
  for (int l = 0; l < 3; ++l)
    for (int m = -l; m <= l; ++m) lobe[std::size_t(sh::index(l, m))] = sh::cosineLobeBand(l) * y[std::size_t(sh::index(l, m))];
  const bool atSphere = settings.blocked == BlockedLight::Sphere;
  const bool mapRead = atSphere && settings.read == BlockedRead::Map;
  if (atSphere && !mapRead && settings.sphereRadiance.size() != lights.size())
    throw InternalError("sl::probeShadow: blocked light read at the spheres needs one radiance SH per light");
  if (mapRead && settings.sphereMap.size() != lights.size())
    throw InternalError("sl::probeShadow: blocked light read from the maps needs one direction map per light");
  glm::dvec3 shadowed = out.unshadowed;  // atSphere: E_u − E_s is set below
  if (!atSphere) {
    const std::vector<double> transfer = sh::product<double>(v, lobe, lOrder);
    shadowed = glm::dvec3(0.0);
    for (std::size_t j = 0; j < radiance.size(); ++j) shadowed += radiance[j] * transfer[j];
  }
  // BlockedLight::Sphere: Σ X_j L_j(d_j) and Σ u_o X_j L_j(d_j) (probe_shadow.hpp).
  glm::dvec3 readExact(0.0), readShared(0.0), sphereBlocked(0.0);

  if (settings.form == ShadowForm::Ratio || atSphere) {
    // k = Σ X_j / Σ A_j over the blockers left after the receiver rules (probe_shadow.hpp).
    const sh::ExpTables& tables = sh::expTables(order, settings.log);
    double exact = kShadowEpsilon, shared = kShadowEpsilon, approx = kShadowEpsilon;
    for (std::size_t li = 0; li < lights.size(); ++li) {
      const Light& l = lights[li];
      const Adjusted a = adjustForReceiver(l.sphere, p, n, settings.influence);
      const double d = glm::length(a.sphere.centre - p);
      if (a.culled || !(d > 0.0)) continue;
      const glm::dvec3 dir = (a.sphere.centre - p) / d;
      const double s = std::min(1.0, a.sphere.radius / d);
      const double share =
          l.object >= 0 && std::size_t(l.object) < settings.objectShare.size() ? settings.objectShare[std::size_t(l.object)] : 1.0;
      const double silhouette = l.object >= 0 && std::size_t(l.object) < settings.objectSilhouette.size()
                                    ? settings.objectSilhouette[std::size_t(l.object)]
                                    : 1.0;
      const double x = silhouette * math::kPi * s * s * std::max(0.0, glm::dot(n, dir));
      exact += x;
      shared += share * x;
      if (atSphere) {
        glm::dvec3 read(0.0);
        if (mapRead) {
          const std::vector<glm::dvec3>& map = settings.sphereMap[li];
          if (map.size() != std::size_t(math::kOctMapTexels))
            throw InternalError("sl::probeShadow: a sphere's direction map needs math::kOctMapTexels texels");
          read = map[std::size_t(math::octTexel(glm::vec3(dir)))];  // the texel the shader picks (float)
        } else {
          const std::vector<glm::dvec3>& Lj = settings.sphereRadiance[li];
          if (Lj.size() != 9) throw InternalError("sl::probeShadow: a sphere's radiance SH needs 9 coefficients");
          const auto yd = sh::evalBasis<double>(3, dir);
          for (std::size_t k = 0; k < 9; ++k) read += Lj[k] * yd[k];
        }
        read = glm::max(read, glm::dvec3(0.0));
        readExact += x * read;
        readShared += share * x * read;
      }
      const auto one = sh::expHybrid(tables.logBlocker(std::asin(s), dir), nullptr, settings.log);
      approx += math::kPi - sh::evalIrradiance<double, double>(std::span<const double>(one), n);
    }
    // σ: how additive exp is here (1: linear regime, the far field; → 0: saturated, near the
    // objects, where exp already discounts the overlaps), from its blocked amount under uniform light.
    const double blockedUniform = math::kPi - std::inner_product(v.begin(), v.begin() + 9, lobe.begin(), 0.0);
    out.additive = std::sqrt(std::clamp((blockedUniform + kShadowEpsilon) / approx, 0.0, 1.0));
    const double target = out.additive * shared + (1.0 - out.additive) * exact;
    if (settings.form == ShadowForm::Ratio) out.ratio = std::clamp(target / approx, 1.0 / kShadowMaxRatio, kShadowMaxRatio);
    if (atSphere) sphereBlocked = blockedUniform * (out.additive * readShared + (1.0 - out.additive) * readExact) / target;
  }
  const glm::dvec3 blocked = atSphere ? sphereBlocked : out.unshadowed - shadowed;
  for (int c = 0; c < 3; ++c)
    out.delta[c] = std::clamp(-out.ratio * blocked[c], -std::max(out.unshadowed[c], 0.0), 0.0);
  return out;
}

double unionShare(std::span<const Sphere> spheres) {
  if (spheres.size() < 2) return 1.0;
  double unionArea = 0.0, sumArea = 0.0;
  for (int k = 0; k < kShareDirections; ++k) {
    const glm::dvec3 d = math::fibonacciSphere(k, kShareDirections);
    const glm::dvec3 a = glm::normalize(glm::cross(d, std::abs(d.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 b = glm::cross(d, a);
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const Sphere& s : spheres) {
      const double u = glm::dot(s.centre, a), v = glm::dot(s.centre, b);
      lo[0] = std::min(lo[0], u - s.radius), hi[0] = std::max(hi[0], u + s.radius);
      lo[1] = std::min(lo[1], v - s.radius), hi[1] = std::max(hi[1], v + s.radius);
      sumArea += math::kPi * s.radius * s.radius;
    }
    const double cell = std::max(hi[0] - lo[0], hi[1] - lo[1]) / kShareGrid;
    if (!(cell > 0.0)) continue;
    int covered = 0;
    for (int y = 0; y < kShareGrid; ++y)
      for (int x = 0; x < kShareGrid; ++x) {
        const double u = lo[0] + (x + 0.5) * cell, v = lo[1] + (y + 0.5) * cell;
        for (const Sphere& s : spheres) {
          const double du = u - glm::dot(s.centre, a), dv = v - glm::dot(s.centre, b);
          if (du * du + dv * dv < s.radius * s.radius) {
            ++covered;
            break;
          }
        }
      }
    unionArea += covered * cell * cell;
  }
  return sumArea > 0.0 ? std::clamp(unionArea / sumArea, 0.0, 1.0) : 1.0;
}

}  // namespace bounce::gi::sl
