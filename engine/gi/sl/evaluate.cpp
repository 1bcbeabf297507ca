#include "engine/gi/sl/evaluate.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>

#include "engine/core/error.hpp"
#include "engine/math/quadrature.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_convolve.hpp"
#include "engine/math/sh_exp.hpp"
#include "engine/math/sh_product.hpp"
#include "engine/math/sh_rotate.hpp"

namespace bounce::gi::sl {
namespace {

constexpr double kPi = math::kPi;
constexpr int kThetaEntries = kAverageRadianceEntries;  // w_θ table, θ in [0, π/2]
constexpr int kGaussNodes = 96;     // over the lit cap; the integrand is smooth there
// Below this unoccluded Eq. 23 Ṽ (sr) the ratio is not formed: the cap is at the horizon or a few
// 1e-9 of a steradian, and the exact Ṽ alone is used (continuous: both tend to 0 together).
constexpr double kMinOpen = 1e-9;

class RadianceTable {
 public:
  explicit RadianceTable(int order) : order_(order), table_(std::size_t(kThetaEntries) * order, 0.0) {
    const auto gl = math::gaussLegendre(kGaussNodes);
    for (int i = 0; i < kThetaEntries; ++i) {
      const double theta = 0.5 * kPi * i / (kThetaEntries - 1);
      const double s = std::sin(theta);
      double* row = table_.data() + std::size_t(i) * order;
      if (i == kThetaEntries - 1) {  // p on the sphere: only the point facing p is seen
        for (int l = 0; l < order; ++l) row[l] = std::sqrt((2.0 * l + 1.0) / (4.0 * kPi));
        continue;
      }
      double norm = 0.0;
      std::vector<double> acc(std::size_t(order), 0.0);
      for (const auto& q : gl) {
        const double u = s + (1.0 - s) * 0.5 * (q.x + 1.0);  // cos α in [sin θ, 1]
        const double w = 0.5 * (1.0 - s) * q.weight;
        const double cg = std::max(0.0, (u - s) / std::sqrt(std::max(1e-300, 1.0 - 2.0 * s * u + s * s)));
        double pl[4] = {1.0, u, 0.5 * (3.0 * u * u - 1.0), 0.5 * u * (5.0 * u * u - 3.0)};  // Legendre P_0..P_3
        for (int l = 0; l < order; ++l) acc[l] += w * cg * std::sqrt((2.0 * l + 1.0) / (4.0 * kPi)) * pl[l];
        norm += w * cg;
      }
      // Both integrals carry the same 2π (azimuth), which cancels.
      for (int l = 0; l < order; ++l) row[l] = acc[l] / norm;
    }
  }
  std::span<const double> rows() const { return table_; }
  std::vector<double> lookup(double theta) const {
    const double x = std::clamp(theta, 0.0, 0.5 * kPi) / (0.5 * kPi) * (kThetaEntries - 1);
    const int i0 = std::min(static_cast<int>(x), kThetaEntries - 2);
    const double w = x - i0;
    std::vector<double> z(static_cast<std::size_t>(order_));
    for (int l = 0; l < order_; ++l)
      z[l] = (1.0 - w) * table_[std::size_t(i0) * order_ + l] + w * table_[std::size_t(i0 + 1) * order_ + l];
    return z;
  }

 private:
  int order_;
  std::vector<double> table_;
};

const RadianceTable& radianceTable(int order) {
  if (order == 3) {
    static const RadianceTable t(3);
    return t;
  }
  if (order == 4) {
    static const RadianceTable t(4);
    return t;
  }
  throw InternalError("sl: order " + std::to_string(order) + " (expected 3 or 4)");
}

// Per light at this receiver.
struct Prepared {
  bool culled = true;
  Sphere s;         // adjusted
  double dist = 0;  // |centre − p| after adjustment
  std::vector<double> log;  // G_i, world space
  double exactOpen = 0.0;  // Ṽ of the unoccluded cap: exact projection / Eq. 23 (Ratio form)
  double eq23Open = 0.0;
  std::vector<double> cap;  // K_i: the cap's indicator projected (sh::capVisibilityZonal's complement), world space
};

// ⟨f⟩ over light i's cap: ∫_cap f dω / |cap| = (f · K_i) / (√(4π) K_i,00) for a band-limited f
// (per-object blocking's visible fraction, evaluate.hpp).
double capAverage(const std::vector<double>& f, const std::vector<double>& cap) {
  double dot = 0.0;
  for (std::size_t k = 0; k < f.size(); ++k) dot += f[k] * cap[k];
  return dot / std::max(std::sqrt(4.0 * kPi) * cap[0], 1e-30);
}

void addTo(std::vector<double>& a, const std::vector<double>& b) {
  for (std::size_t i = 0; i < a.size(); ++i) a[i] += b[i];
}

// Eq. 23's visibility SH of one light given the summed logs of its blockers.
std::vector<double> eq23(const std::vector<double>& blockers, const std::vector<double>& own, sh::LogKind kind) {
  std::vector<double> with = blockers;
  addTo(with, own);
  auto v = sh::expHybrid(blockers, nullptr, kind);
  const auto v2 = sh::expHybrid(with, nullptr, kind);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] -= v2[i];
  return v;
}

bool intersects(const Light& a, const Light& b) {
  return a.object == b.object &&
         glm::length(a.sphere.centre - b.sphere.centre) < a.sphere.radius + b.sphere.radius;
}

}  // namespace

Adjusted adjustForReceiver(const Sphere& s, const glm::dvec3& p, const glm::dvec3& n, double influence) {
  Adjusted out{s, false};
  const double d = glm::length(s.centre - p);
  double r = std::max(0.0, s.radius);
  // Rule 0: influence.
  if (influence > 0.0 && d > 0.5 * influence * r) r *= std::clamp((influence - d / r) / (0.5 * influence), 0.0, 1.0);
  // Rule 1: containment.
  if (d < r) {
    const double t = d / r;
    r = d * std::clamp((t - kCullFraction) / (1.0 - kCullFraction), 0.0, 1.0);
  }
  // Rule 2: tangent plane.
  const double h = glm::dot(n, s.centre - p);
  glm::dvec3 c = s.centre;
  if (h < r) {
    const double top = h + r;
    if (top <= 0.0) {
      out.culled = true;
      out.sphere.radius = 0.0;
      return out;
    }
    const double r2 = 0.5 * top;
    c += (r2 - h) * n;
    r = r2;
  }
  out.sphere = {c, r};
  out.culled = !(r > 0.0);
  return out;
}

double cosGamma(double alpha, double theta) {
  const double s = std::sin(theta), u = std::cos(alpha);
  return std::max(0.0, (u - s) / std::sqrt(std::max(1e-300, 1.0 - 2.0 * s * u + s * s)));
}

std::vector<double> averageRadianceZonal(double theta, int order) { return radianceTable(order).lookup(theta); }

std::span<const double> averageRadianceTable(int order) { return radianceTable(order).rows(); }

Evaluation evaluate(std::span<const Light> lights, const glm::dvec3& p, const glm::dvec3& n,
                    const EvalSettings& settings) {
  const int order = settings.order;
  const sh::ExpTables& tables = sh::expTables(order, settings.log);
  const RadianceTable& wTable = radianceTable(order);
  const std::size_t nc = std::size_t(order) * order;
  Evaluation out;
  out.terms.resize(lights.size());

  std::vector<Prepared> prep(lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    if (lights[i].intensity.size() != nc) throw InternalError("sl::evaluate: intensity has the wrong SH count");
    const Adjusted a = adjustForReceiver(lights[i].sphere, p, n, settings.influence);
    Prepared& q = prep[i];
    q.s = a.sphere;
    q.dist = glm::length(a.sphere.centre - p);
    q.culled = a.culled || !(q.dist > 0.0);
    out.terms[i].culled = q.culled;
    if (q.culled) continue;
    const glm::dvec3 dir = (a.sphere.centre - p) / q.dist;
    const double theta = std::asin(std::min(1.0, a.sphere.radius / q.dist));
    out.terms[i].theta = theta;
    q.log = tables.logBlocker(theta, dir);
    // Ṽ of the cap alone, exact (its ZH projection, visibility 1 − cap → cap = √(4π)δ_l0 − g_l).
    auto z = sh::capVisibilityZonal(theta, order);
    z[0] = std::sqrt(4.0 * kPi) - z[0];
    for (int l = 1; l < order; ++l) z[l] = -z[l];
    q.cap = sh::rotateZonal<double>(z, dir);
    q.exactOpen = sh::evalIrradiance<double, double>(std::span<const double>(q.cap), n);
    if (settings.visibility == VisibilityForm::Ratio && settings.blocking == Blocking::PerSphere) {
      // And as Eq. 23 sees it (1 − exp(G_i)).
      const std::vector<double> none(nc, 0.0);
      const auto v = eq23(none, q.log, settings.log);
      q.eq23Open = sh::evalIrradiance<double, double>(std::span<const double>(v), n);
    }
    // Eq. 18: the weight rotated to the SL-local direction from its centre to p (§7.1).
    const glm::dvec3 toP = glm::transpose(lights[i].rotation) * (-dir);
    const auto w = sh::rotateZonal<double>(wTable.lookup(theta), toP);
    glm::dvec3 avg(0.0);
    for (std::size_t k = 0; k < nc; ++k) avg += w[k] * lights[i].intensity[k];
    out.terms[i].average = avg;
  }

  // Closest first (centre distance after adjustment); ties by index, so the order is deterministic.
  std::vector<std::size_t> order_(lights.size());
  std::iota(order_.begin(), order_.end(), 0);
  std::stable_sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) { return prep[a].dist < prep[b].dist; });

  auto finish = [&](std::size_t i, const std::vector<double>& blockers) {
    const auto v = eq23(blockers, prep[i].log, settings.log);
    double vis = sh::evalIrradiance<double, double>(std::span<const double>(v), n);  // Eq. 24
    if (settings.visibility == VisibilityForm::Ratio) {
      // Eq. 23's visible fraction times the exact unoccluded Ṽ (evaluate.hpp).
      const Prepared& q = prep[i];
      vis = q.eq23Open > kMinOpen ? vis * (q.exactOpen / q.eq23Open) : q.exactOpen;
    }
    out.terms[i].visibility = vis;
    out.irradiance += out.terms[i].average * out.terms[i].visibility;
  };

  if (settings.blocking == Blocking::PerSphere) {
    for (std::size_t a = 0; a < order_.size(); ++a) {
      const std::size_t i = order_[a];
      if (prep[i].culled) continue;
      std::vector<double> blockers(nc, 0.0);
      for (std::size_t b = 0; b < a; ++b) {
        const std::size_t j = order_[b];
        if (prep[j].culled || intersects(lights[i], lights[j])) continue;
        addTo(blockers, prep[j].log);
      }
      finish(i, blockers);
    }
  } else {
    // Per-object blocking (§7.2), one exp per object (evaluate.hpp "Per-object blocking"): objects by
    // the distance from p to the mean of their sphere centres.
    std::map<int, std::pair<glm::dvec3, int>> centres;
    for (const Light& l : lights) {
      auto& c = centres[l.object];
      c.first += l.sphere.centre;
      c.second += 1;
    }
    std::vector<std::pair<double, int>> objects;
    for (const auto& [id, c] : centres) objects.push_back({glm::length(c.first / double(c.second) - p), id});
    std::stable_sort(objects.begin(), objects.end());
    std::vector<double> closerObjects(nc, 0.0);
    for (const auto& [dist, id] : objects) {
      const auto expCloser = sh::expHybrid(closerObjects, nullptr, settings.log);  // once per object
      std::vector<double> objectSum(nc, 0.0);
      for (std::size_t a = 0; a < order_.size(); ++a) {
        const std::size_t i = order_[a];
        if (lights[i].object != id || prep[i].culled) continue;
        const Prepared& q = prep[i];
        const double fraction = std::clamp(capAverage(expCloser, q.cap), 0.0, 1.0);
        out.terms[i].visibility = q.exactOpen * fraction;
        out.irradiance += out.terms[i].average * out.terms[i].visibility;
        addTo(objectSum, q.log);
      }
      addTo(closerObjects, objectSum);
    }
  }
  return out;
}

std::vector<glm::dvec3> intensityFromSamples(std::span<const glm::dvec3> sampleRadiance,
                                             std::span<const std::vector<float>> basis, std::span<const float> albedo,
                                             int order) {
  const std::size_t nc = std::size_t(order) * order;
  if (sampleRadiance.size() != basis.size() || albedo.size() != nc * 3)
    throw InternalError("sl::intensityFromSamples: sizes do not match");
  std::vector<glm::dvec3> out(nc, glm::dvec3(0.0));
  for (int ch = 0; ch < 3; ++ch) {
    std::vector<double> ls(nc, 0.0), c(nc);
    for (std::size_t j = 0; j < basis.size(); ++j) {
      if (basis[j].size() != nc) throw InternalError("sl::intensityFromSamples: basis size");
      for (std::size_t k = 0; k < nc; ++k) ls[k] += sampleRadiance[j][ch] * basis[j][k];  // Eq. 10
    }
    for (std::size_t k = 0; k < nc; ++k) c[k] = albedo[k * 3 + std::size_t(ch)];
    const auto lc = sh::product<double>(ls, c, order);  // Eq. 11
    for (std::size_t k = 0; k < nc; ++k) out[k][ch] = lc[k];
  }
  return out;
}

std::vector<double> environmentVisibility(std::span<const Light> lights, const glm::dvec3& p, const glm::dvec3& n,
                                          int order, sh::LogKind kind, double influence) {
  const sh::ExpTables& tables = sh::expTables(order, kind);
  std::vector<double> sum(std::size_t(order) * order, 0.0);
  for (const Light& l : lights) {
    const Adjusted a = adjustForReceiver(l.sphere, p, n, influence);
    const double d = glm::length(a.sphere.centre - p);
    if (a.culled || !(d > 0.0)) continue;
    addTo(sum, tables.logBlocker(std::asin(std::min(1.0, a.sphere.radius / d)), (a.sphere.centre - p) / d));
  }
  return sh::expHybrid(sum, nullptr, kind);  // Eq. 6
}

}  // namespace bounce::gi::sl
