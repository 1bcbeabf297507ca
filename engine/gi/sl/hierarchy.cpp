#include "engine/gi/sl/hierarchy.hpp"

#include <algorithm>
#include <map>

#include "engine/core/error.hpp"
#include "engine/math/sh_rotate.hpp"

namespace bounce::gi::sl {
namespace {

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Rule 0's radius scale s (evaluate.hpp): 1 up to F/2 radii, 0 from F on.
double influenceScale(const Sphere& s, const glm::dvec3& p, double influence) {
  if (!(influence > 0.0) || !(s.radius > 0.0)) return 1.0;
  const double t = glm::length(s.centre - p) / s.radius;
  return std::clamp((influence - t) / (0.5 * influence), 0.0, 1.0);
}

// m_o(p): the share of object `object`'s children (weighted at the cluster centre) the cut took away.
double cutShare(std::span<const Light> lights, int object, std::span<const double> share, const glm::dvec3& p,
                double influence) {
  double m = 0.0;
  std::size_t k = 0;
  for (const Light& l : lights) {
    if (l.object != object) continue;
    if (k >= share.size()) throw InternalError("sl: hierarchy parents do not match the lights");
    const double s = influenceScale(l.sphere, p, influence);
    m += (1.0 - s * s) * share[k++];
  }
  return m;
}

std::map<int, std::vector<std::size_t>> lightsByObject(std::span<const Light> lights) {
  std::map<int, std::vector<std::size_t>> byObject;
  for (std::size_t i = 0; i < lights.size(); ++i) byObject[lights[i].object].push_back(i);
  return byObject;
}

void normalise(std::vector<double>& share) {
  double total = 0.0;
  for (double s : share) total += s;
  for (double& s : share) s = total > 0.0 ? s / total : 1.0 / double(share.size());
}

}  // namespace

Sphere parentSphere(std::span<const Sphere> children) {
  if (children.empty()) throw InternalError("sl::parentSphere: no children");
  glm::dvec3 c(0.0);
  for (const Sphere& s : children) c += s.centre;
  c /= double(children.size());
  double r = 0.0;
  for (const Sphere& s : children) r = std::max(r, glm::length(s.centre - c) + s.radius);
  return {c, r};
}

Light parentOf(std::span<const Light> children) {
  if (children.empty()) throw InternalError("sl::parentOf: no children");
  Light parent;
  parent.object = children.front().object;
  std::vector<Sphere> spheres;
  for (const Light& l : children) {
    if (l.object != parent.object) throw InternalError("sl::parentOf: children of different objects");
    spheres.push_back(l.sphere);
  }
  parent.sphere = parentSphere(spheres);
  const double r = parent.sphere.radius;
  parent.rotation = glm::dmat3(1.0);
  const std::size_t nc = children.front().intensity.size();
  parent.intensity.assign(nc, glm::dvec3(0.0));
  if (!(r > 0.0)) return parent;
  for (const Light& l : children) {
    if (l.intensity.size() != nc) throw InternalError("sl::parentOf: children of different orders");
    // Local → world (sh_rotate.hpp: apply(R) moves light from ω to Rω), weighted by the area ratio.
    const auto world = sh::Rotation<double>::fromMatrix(l.rotation).apply(l.intensity);
    const double w = (l.sphere.radius / r) * (l.sphere.radius / r);
    for (std::size_t k = 0; k < nc; ++k) parent.intensity[k] += w * world[k];
  }
  return parent;
}

std::vector<Parent> clusterParents(std::span<const Light> lights, const glm::dvec3& xC, const glm::dvec3& nC,
                                   const EvalSettings& settings) {
  EvalSettings flat = settings;
  flat.influence = 0.0;
  const Evaluation children = evaluate(lights, xC, nC, flat);  // Eq. 25's numerator terms, uncut, blocked
  std::vector<Parent> out;
  for (const auto& [id, idx] : lightsByObject(lights)) {
    std::vector<Light> kids;
    for (std::size_t i : idx) kids.push_back(lights[i]);
    Parent p;
    p.light = parentOf(kids);
    glm::dvec3 num(0.0);
    for (std::size_t i : idx) {
      const glm::dvec3 term = children.terms[i].average * children.terms[i].visibility;
      num += term;
      p.share.push_back(std::max(0.0, luminance(term)));
    }
    normalise(p.share);
    const Light one[1] = {p.light};
    const glm::dvec3 den = evaluate(one, xC, nC, flat).irradiance;  // L̃_P Ṽ_P, alone
    for (int ch = 0; ch < 3; ++ch)
      p.ratio[ch] = std::clamp(den[ch] > kMinParentTerm ? num[ch] / den[ch] : 1.0, 0.0, kMaxParentRatio);  // Eq. 25
    out.push_back(std::move(p));
  }
  return out;
}

glm::dvec3 evaluateHierarchy(std::span<const Light> lights, std::span<const Parent> parents, const glm::dvec3& p,
                             const glm::dvec3& n, const EvalSettings& settings) {
  glm::dvec3 e = evaluate(lights, p, n, settings).irradiance;  // the children, cut by rule 0
  if (!(settings.influence > 0.0)) return e;
  EvalSettings flat = settings;
  flat.influence = 0.0;
  for (const Parent& par : parents) {
    const double m = cutShare(lights, par.light.object, par.share, p, settings.influence);
    if (!(m > 0.0)) continue;
    const Light one[1] = {par.light};
    e += m * par.ratio * evaluate(one, p, n, flat).irradiance;  // Eq. 26
  }
  return e;
}

std::vector<ShadowParent> clusterShadowParents(std::span<const Light> lights, const glm::dvec3& xC,
                                               const glm::dvec3& nC, std::span<const glm::dvec3> radianceC,
                                               const ShadowSettings& settings) {
  ShadowSettings flat = settings;
  flat.influence = 0.0;
  std::vector<ShadowParent> out;
  for (const auto& [id, idx] : lightsByObject(lights)) {
    std::vector<Light> kids;
    ShadowParent sp;
    for (std::size_t i : idx) {
      kids.push_back(lights[i]);
      // X_j at x_C (probe_shadow.hpp), the raw sphere: the far field needs no receiver rules.
      const glm::dvec3 to = lights[i].sphere.centre - xC;
      const double d = glm::length(to);
      const double s = d > 0.0 ? std::min(1.0, lights[i].sphere.radius / d) : 1.0;
      sp.share.push_back(d > 0.0 ? s * s * std::max(0.0, glm::dot(nC, to / d)) : 0.0);
    }
    normalise(sp.share);
    sp.light = parentOf(kids);
    const glm::dvec3 num = probeShadow(kids, xC, nC, radianceC, flat).delta;
    const Light one[1] = {sp.light};
    const glm::dvec3 den = probeShadow(one, xC, nC, radianceC, flat).delta;
    for (int ch = 0; ch < 3; ++ch)
      sp.ratio[ch] = std::clamp(std::abs(den[ch]) > kMinParentTerm ? num[ch] / den[ch] : 1.0, 0.0, kMaxParentRatio);
    out.push_back(std::move(sp));
  }
  return out;
}

glm::dvec3 probeShadowHierarchy(std::span<const Light> lights, std::span<const ShadowParent> parents,
                                const glm::dvec3& p, const glm::dvec3& n, std::span<const glm::dvec3> radiance,
                                const ShadowSettings& settings) {
  const ProbeShadow cut = probeShadow(lights, p, n, radiance, settings);
  glm::dvec3 delta = cut.delta;
  if (!(settings.influence > 0.0)) return delta;
  ShadowSettings flat = settings;
  flat.influence = 0.0;
  for (const ShadowParent& par : parents) {
    const double m = cutShare(lights, par.light.object, par.share, p, settings.influence);
    if (!(m > 0.0)) continue;
    const Light one[1] = {par.light};
    delta += m * par.ratio * probeShadow(one, p, n, radiance, flat).delta;
  }
  for (int ch = 0; ch < 3; ++ch) delta[ch] = std::clamp(delta[ch], -std::max(cut.unshadowed[ch], 0.0), 0.0);
  return delta;
}

}  // namespace bounce::gi::sl
