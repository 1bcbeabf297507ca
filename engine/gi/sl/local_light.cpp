#include "engine/gi/sl/local_light.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/math/sampling.hpp"
#include "engine/math/sh_rotate.hpp"

namespace bounce::gi::sl {
namespace {
// A blocker covering the whole light leaves this much of it (log 0 would be −∞; e^{w log} stays
// continuous in w): far below what an 8-bit display shows.
constexpr double kMinVisible = 1e-6;
}  // namespace

double localBlockerWeight(const Sphere& adjusted, double d, const LocalLight& light, double dx) {
  const double r = adjusted.radius;
  if (!(r > 0.0)) return 0.0;
  const double closer = std::clamp((dx - d) / r, 0.0, 1.0);
  const double gap = glm::length(adjusted.centre - light.position) - r - std::max(light.radius, 0.0);
  return closer * std::clamp(gap / r, 0.0, 1.0);
}

double capOverlapFraction(double a, double b, double c) {
  if (!(b > 0.0) || c >= a + b) return 0.0;
  if (c <= b - a) return 1.0;                                              // the light's cap inside b's
  if (c <= a - b) return (1.0 - std::cos(b)) / (1.0 - std::cos(a));         // b's cap inside the light's
  // The lens of two caps on the unit sphere: 2[π − C − cos a·A − cos b·B], with C the angle between
  // the two great circles through the intersection points and A, B the half-angles the lens subtends
  // at each centre (spherical law of cosines).
  const double ca = std::cos(a), cb = std::cos(b), cc = std::cos(c), sa = std::sin(a), sb = std::sin(b), sc = std::sin(c);
  const auto acosc = [](double x) { return std::acos(std::clamp(x, -1.0, 1.0)); };
  const double area = 2.0 * (math::kPi - acosc((cc - ca * cb) / (sa * sb)) - ca * acosc((cb - cc * ca) / (sc * sa)) -
                             cb * acosc((ca - cc * cb) / (sc * sb)));
  return std::clamp(area / (2.0 * math::kPi * (1.0 - ca)), 0.0, 1.0);
}

double localLightVisibility(std::span<const Sphere> spheres, const LocalLight& light, const glm::dvec3& p,
                            const glm::dvec3& n, int order, double influence, LocalForm form, sh::LogKind kind,
                            std::span<const double> share, std::span<const double> shadowScale) {
  const glm::dvec3 toLight = light.position - p;
  const double dx = glm::length(toLight);
  if (!(dx > 0.0)) return 1.0;
  const sh::ExpTables& tables = sh::expTables(order, kind);
  const std::size_t nc = std::size_t(order) * order;
  const double a = std::asin(std::min(1.0, std::max(light.radius, 0.0) / dx));  // the light's angular radius
  std::vector<double> sum(nc, 0.0);
  double logV = 0.0;  // Cap form
  bool any = false;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const Sphere& s = spheres[i];
    const Adjusted adj = adjustForReceiver(s, p, n, influence);
    const double d = glm::length(adj.sphere.centre - p);
    if (adj.culled || !(d > 0.0)) continue;
    const double w = localBlockerWeight(adj.sphere, d, light, dx);
    if (!(w > 0.0)) continue;
    const double b = std::asin(std::min(1.0, adj.sphere.radius / d));
    if (form == LocalForm::Cap) {
      const double c = std::acos(std::clamp(glm::dot(adj.sphere.centre - p, toLight) / (d * dx), -1.0, 1.0));
      // The cap shrunk to the set's shadow scale of its solid angle (1 − cos b' = s (1 − cos b)).
      const double scale = i < shadowScale.size() ? shadowScale[i] : 1.0;
      const double sinB = std::min(1.0, adj.sphere.radius / d), oneMinusCos = scale * sinB * sinB / (1.0 + std::sqrt(1.0 - sinB * sinB));
      const double bs = 2.0 * std::asin(std::sqrt(0.5 * oneMinusCos));
      const double u = i < share.size() ? share[i] : 1.0;
      logV += u * w * std::log(std::max(1.0 - capOverlapFraction(a, bs, c), kMinVisible));
      continue;
    }
    const auto g = tables.logBlocker(b, (adj.sphere.centre - p) / d);
    for (std::size_t k = 0; k < nc; ++k) sum[k] += w * g[k];
    any = true;
  }
  if (form == LocalForm::Cap) return std::exp(logV);
  if (!any) return 1.0;
  const auto v = sh::expHybrid(sum, nullptr, kind);  // Eq. 6 over the closer SLs
  // The light's cap, K/sin²θ: the exact cap ZH (sh_exp.hpp capVisibilityZonal's complement) with
  // sin²θ divided out; its limit at θ → 0 is z_l = ½√((2l + 1)π) (then ⟨f⟩ = f(dir)).
  const double theta = a;
  const double s2 = std::sin(theta) * std::sin(theta);
  std::vector<double> z(static_cast<std::size_t>(order), 0.0);
  if (s2 > 1e-12) {
    z = sh::capVisibilityZonal(theta, order);
    z[0] = std::sqrt(4.0 * math::kPi) - z[0];
    for (int l = 1; l < order; ++l) z[l] = -z[l];
    for (double& x : z) x /= s2;
  } else {
    for (int l = 0; l < order; ++l) z[std::size_t(l)] = 0.5 * std::sqrt((2.0 * l + 1.0) * math::kPi);
  }
  const auto cap = sh::rotateZonal<double>(z, toLight / dx);
  double dot = 0.0;
  for (std::size_t k = 0; k < nc; ++k) dot += v[k] * cap[k];
  return std::clamp(dot / (std::sqrt(4.0 * math::kPi) * cap[0]), 0.0, 1.0);
}

}  // namespace bounce::gi::sl
