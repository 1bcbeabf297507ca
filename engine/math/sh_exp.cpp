#include "engine/math/sh_exp.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <string>

#include "engine/core/error.hpp"
#include "engine/math/quadrature.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_eval.hpp"
#include "engine/math/sh_product.hpp"
#include "engine/math/sh_rotate.hpp"
#include "engine/math/sh_window.hpp"

namespace bounce::sh {
namespace {

constexpr double kPi = math::kPi;
const double kSqrt4Pi = std::sqrt(4.0 * kPi);  // the constant function 1 has DC coefficient √(4π)
// e^x overflows double above ~709; DC terms of log-visibility are ≤ 0, a larger one is a caller bug
// that we keep finite rather than propagate as inf.
constexpr double kMaxExponent = 700.0;

// Legendre P_0..P_{n} at t.
void legendre(double t, int n, double* p) {
  p[0] = 1.0;
  if (n >= 1) p[1] = t;
  for (int l = 2; l <= n; ++l) p[l] = ((2 * l - 1) * t * p[l - 1] - (l - 1) * p[l - 2]) / l;
}

// Y_l0(t) = √((2l+1)/(4π)) P_l(t) at the Gauss–Legendre nodes, cached (256 nodes, l ≤ 3).
struct ZonalQuadrature {
  static constexpr int kNodes = 256;
  std::vector<double> t, w;                     // nodes in cos θ, weights (sum 2)
  std::vector<std::array<double, kMaxOrder>> y;  // Y_l0 at each node
  ZonalQuadrature() {
    for (const auto& q : math::gaussLegendre(kNodes)) {
      t.push_back(q.x);
      w.push_back(q.weight);
      double p[kMaxOrder + 1];
      legendre(q.x, kMaxOrder, p);
      std::array<double, kMaxOrder> row{};
      for (int l = 0; l < kMaxOrder; ++l) row[l] = std::sqrt((2.0 * l + 1.0) / (4.0 * kPi)) * p[l];
      y.push_back(row);
    }
  }
};
const ZonalQuadrature& zonalQuadrature() {
  static const ZonalQuadrature q;
  return q;
}

// Nodes and basis values of sphereQuadrature(degree), cached per degree.
struct SphereQuadrature {
  std::vector<math::SphereNode> nodes;
  std::vector<std::array<double, kMaxCoeffs>> y;
};
const SphereQuadrature& sphereQuadratureCached(int degree) {
  static std::mutex mutex;
  static std::vector<std::unique_ptr<SphereQuadrature>> cache(201);
  if (degree < 0 || degree > 200) throw InternalError("sh::expExact: degree " + std::to_string(degree));
  std::lock_guard lock(mutex);
  auto& slot = cache[std::size_t(degree)];
  if (!slot) {
    slot = std::make_unique<SphereQuadrature>();
    slot->nodes = math::sphereQuadrature(degree);
    for (const auto& n : slot->nodes) slot->y.push_back(evalBasis<double>(kMaxOrder, n.dir));
  }
  return *slot;
}

// The cap's indicator projected to ZH (√(4π)·δ_l0 − g_l), then windowed (Sloan 2017's sinc⁴, the
// least filtering found by bisection on the width) so its reconstruction is ≥ 0 on every node in
// cos θ: a ringing-free blocker "density".
std::vector<double> nonNegativeCap(std::span<const double> g) {
  const int n = static_cast<int>(g.size());
  std::vector<double> cap(g.begin(), g.end());
  cap[0] = kSqrt4Pi - g[0];
  for (int l = 1; l < n; ++l) cap[l] = -g[l];
  const auto& q = zonalQuadrature();
  auto minValue = [&](double width) {
    double m = 1e300;
    for (std::size_t i = 0; i < q.t.size(); ++i) {
      double v = 0.0;
      for (int l = 0; l < n; ++l) v += windowWeight(Window::Sloan, l, width) * cap[l] * q.y[i][l];
      m = std::min(m, v);
    }
    // Plus the poles, where zonal ringing peaks.
    for (double t : {-1.0, 1.0}) {
      double p[kMaxOrder + 1];
      legendre(t, n, p);
      double v = 0.0;
      for (int l = 0; l < n; ++l)
        v += windowWeight(Window::Sloan, l, width) * cap[l] * std::sqrt((2.0 * l + 1.0) / (4.0 * kPi)) * p[l];
      m = std::min(m, v);
    }
    return m;
  };
  if (minValue(1e30) >= 0.0) return cap;
  double lo = 1.0, hi = 64.0;  // width 1 keeps band 0 only (≥ 0); 64 barely filters
  if (minValue(hi) >= 0.0) lo = hi;
  for (int it = 0; it < 60 && hi - lo > 1e-6 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (minValue(mid) >= 0.0 ? lo : hi) = mid;
  }
  for (int l = 0; l < n; ++l) cap[l] *= windowWeight(Window::Sloan, l, lo);
  return cap;
}

// The log of one blocker's visibility: f_θ = −λ c_w, with c_w the cap's indicator windowed to be
// ≥ 0 everywhere (nonNegativeCap): the projection of a clamped pointwise log of depth λ inside a
// softened blocker (Ren et al.'s log of a binary function must be clamped), λ minimising
// ‖exp(f_θ) − g_θ‖₂ by golden section (the error is unimodal in λ, so λ(θ) and the table are
// continuous in θ). f ≤ 0 everywhere keeps exp of ANY sum of blockers in (0, 1].
// Rejected, measured with tests/unit/sl:
//  - exp(f) = g_θ solved exactly (n equations, n unknowns), or λ(g − 1) unwindowed: f inherits the
//    truncated cap's ringing as positive lobes away from the blocker; summed over 16–64 blockers
//    they dominate and exp blows up (RMS error 3–6 at 64 blockers), and Eq. 23's difference of two
//    exps exceeded the unoccluded visibility in the blocker test;
//  - λ matching g_θ's DC (exact blocked solid angle): the blocker shadow test then over-darkens by
//    30 % (0.083 vs 0.121 brute force), against 1 % for least squares;
//  - a Nelder–Mead fit of all n coefficients under f ≤ 0: neighbouring θ converge to different
//    local optima and the table jumps (a 10 % step in E per 1e-4 R of motion).
constexpr double kMaxLambda = 200.0;
double fitLambda(std::span<const double> g, LogKind kind, std::vector<double>& f) {
  const int n = static_cast<int>(g.size());
  std::vector<double> cap;
  if (kind == LogKind::Raw) {
    cap.assign(g.begin(), g.end());
    cap[0] = kSqrt4Pi - g[0];
    for (int l = 1; l < n; ++l) cap[l] = -g[l];
  } else {
    cap = nonNegativeCap(g);
  }
  auto scaled = [&](double lambda) {
    std::vector<double> x(static_cast<std::size_t>(n));
    for (int l = 0; l < n; ++l) x[l] = -lambda * cap[l];
    return x;
  };
  auto err = [&](double lambda) {
    const auto e = expZonalExact(scaled(lambda));
    double s = 0.0;
    for (int l = 0; l < n; ++l) s += (e[l] - g[l]) * (e[l] - g[l]);
    return s;
  };
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = 0.0, b = kMaxLambda;
  double c = b - phi * (b - a), d = a + phi * (b - a);
  double fc = err(c), fd = err(d);
  for (int it = 0; it < 120; ++it) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - phi * (b - a), fc = err(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + phi * (b - a), fd = err(d);
    }
  }
  const double lambda = cap[0] > 0.0 ? 0.5 * (a + b) : 0.0;
  f = scaled(lambda);
  return std::sqrt(err(lambda));
}

int checkedExpOrder(std::size_t count) {
  const int order = orderFromCount(count);
  if (order != 3 && order != 4)
    throw InternalError("sh exponentiation: order " + std::to_string(order) + " (expected 3 or 4)");
  return order;
}

}  // namespace

std::vector<double> capVisibilityZonal(double theta, int order) {
  checkOrder(order);
  const double c = std::cos(std::clamp(theta, 0.0, kPi));
  double p[kMaxOrder + 2];
  legendre(c, order, p);
  std::vector<double> g(std::size_t(order), 0.0);
  g[0] = std::sqrt(kPi) * (1.0 + c);
  for (int l = 1; l < order; ++l) g[l] = std::sqrt(kPi * (2.0 * l + 1.0)) * (p[l + 1] - p[l - 1]) / (2.0 * l + 1.0);
  return g;
}

std::vector<double> expZonalExact(std::span<const double> zonal) {
  const int n = static_cast<int>(zonal.size());
  checkOrder(n);
  const auto& q = zonalQuadrature();
  std::vector<double> out(std::size_t(n), 0.0);
  for (std::size_t i = 0; i < q.t.size(); ++i) {
    double fv = 0.0;
    for (int l = 0; l < n; ++l) fv += zonal[l] * q.y[i][l];
    const double e = 2.0 * kPi * q.w[i] * std::exp(std::min(fv, kMaxExponent));
    for (int l = 0; l < n; ++l) out[l] += e * q.y[i][l];
  }
  return out;
}

std::vector<double> expExact(std::span<const double> f, int degree) {
  const int order = orderFromCount(f.size());
  const auto& q = sphereQuadratureCached(degree);
  std::vector<double> out(f.size(), 0.0);
  for (std::size_t i = 0; i < q.nodes.size(); ++i) {
    double fv = 0.0;
    for (std::size_t k = 0; k < f.size(); ++k) fv += f[k] * q.y[i][k];
    const double e = q.nodes[i].weight * std::exp(std::min(fv, kMaxExponent));
    for (std::size_t k = 0; k < f.size(); ++k) out[k] += e * q.y[i][k];
  }
  (void)order;
  return out;
}

ExpTables::ExpTables(int order, LogKind kind) : order_(order), kind_(kind) {
  if (order != 3 && order != 4) throw InternalError("sh::ExpTables: order " + std::to_string(order));
  // log(g_θ) per θ (fitLambda); θ = 0 gives g = 1 and f = 0.
  logTable_.assign(std::size_t(kThetaEntries) * order, 0.0);
  std::vector<double> f(std::size_t(order), 0.0);
  for (int i = 0; i < kThetaEntries; ++i) {
    const double theta = 0.5 * kPi * i / (kThetaEntries - 1);
    const auto g = capVisibilityZonal(theta, order);
    logResidual_ = std::max(logResidual_, fitLambda(g, kind, f));
    std::copy(f.begin(), f.end(), logTable_.begin() + std::ptrdiff_t(i) * order);
  }

  // Optimal linear table. Training directions u (unit, DC-free): sums of K ∈ {1, 2, 4, 8} rotated
  // single-blocker logs with θ uniform in [0.05, 1.5] rad and uniform directions (fixed seed, so
  // the table is deterministic). For magnitude m, with t = exp(m·u) (exact quadrature):
  //   min Σ_u ‖a 1 + b m u − t‖²  ⇒  a = mean(t_0)/√(4π),  b = Σ_u (u · t̂) / (count · m)
  // (1 ⟂ u, so the two unknowns separate).
  constexpr int kTraining = 48;
  const int nc = order * order;
  std::vector<std::vector<double>> train;
  math::Pcg32 rng(2006);
  for (int s = 0; s < kTraining; ++s) {
    const int k = 1 << (s % 4);
    std::vector<double> sum(std::size_t(nc), 0.0);
    for (int b = 0; b < k; ++b) {
      const double theta = 0.05 + 1.45 * rng.nextDouble();
      const glm::dvec3 d = math::uniformSphere(rng.next2D());
      const auto lb = logBlocker(theta, d);
      for (int c = 0; c < nc; ++c) sum[c] += lb[c];
    }
    sum[0] = 0.0;
    double norm = 0.0;
    for (double x : sum) norm += x * x;
    norm = std::sqrt(norm);
    if (norm < 1e-12) continue;
    for (double& x : sum) x /= norm;
    train.push_back(std::move(sum));
  }
  olTable_.assign(std::size_t(kMagEntries) * 2, 0.0);
  for (int i = 0; i < kMagEntries; ++i) {
    const double m = kMaxMagnitude * i / (kMagEntries - 1);
    if (i == 0) {  // exp(εu) = 1 + εu + O(ε²): a = b = 1
      olTable_[0] = olTable_[1] = 1.0;
      continue;
    }
    double sumA = 0.0, sumB = 0.0;
    for (const auto& u : train) {
      std::vector<double> x(u.size());
      for (std::size_t c = 0; c < u.size(); ++c) x[c] = m * u[c];
      const auto t = expExact(x);
      sumA += t[0];
      for (std::size_t c = 1; c < u.size(); ++c) sumB += u[c] * t[c];
    }
    olTable_[2 * i] = sumA / (double(train.size()) * kSqrt4Pi);
    olTable_[2 * i + 1] = sumB / (double(train.size()) * m);
  }
}

std::vector<double> ExpTables::logZonal(double theta) const {
  const double x = std::clamp(theta, 0.0, 0.5 * kPi) / (0.5 * kPi) * (kThetaEntries - 1);
  const int i0 = std::min(static_cast<int>(x), kThetaEntries - 2);
  const double w = x - i0;
  std::vector<double> f(static_cast<std::size_t>(order_));
  for (int l = 0; l < order_; ++l)
    f[l] = (1.0 - w) * logTable_[std::size_t(i0) * order_ + l] + w * logTable_[std::size_t(i0 + 1) * order_ + l];
  return f;
}

std::vector<double> ExpTables::logBlocker(double theta, const glm::dvec3& d) const {
  const auto z = logZonal(theta);
  return rotateZonal<double>(z, d);
}

std::array<double, 2> ExpTables::olCoefficients(double magnitude) const {
  const double x = std::clamp(magnitude, 0.0, kMaxMagnitude) / kMaxMagnitude * (kMagEntries - 1);
  const int i0 = std::min(static_cast<int>(x), kMagEntries - 2);
  const double w = x - i0;
  return {(1.0 - w) * olTable_[2 * i0] + w * olTable_[2 * i0 + 2],
          (1.0 - w) * olTable_[2 * i0 + 1] + w * olTable_[2 * i0 + 3]};
}

const ExpTables& expTables(int order, LogKind kind) {
  const bool raw = kind == LogKind::Raw;
  if (order == 3) {
    if (raw) {
      static const ExpTables r3(3, LogKind::Raw);
      return r3;
    }
    static const ExpTables w3(3, LogKind::Windowed);
    return w3;
  }
  if (order == 4) {
    if (raw) {
      static const ExpTables r4(4, LogKind::Raw);
      return r4;
    }
    static const ExpTables w4(4, LogKind::Windowed);
    return w4;
  }
  throw InternalError("sh::expTables: order " + std::to_string(order) + " (expected 3 or 4)");
}

namespace {

// e^{f_0 Y_00}: the DC part of f is the constant function f_0/√(4π).
double dcFactor(double f0) { return std::exp(std::min(f0 / kSqrt4Pi, kMaxExponent)); }

// a 1 + b f̂ for the DC-free part of f (f̂ = f with f[0] ignored).
std::vector<double> olNoDc(const ExpTables& t, std::span<const double> f, double magnitude) {
  const auto [a, b] = t.olCoefficients(magnitude);
  std::vector<double> g(f.size());
  g[0] = a * kSqrt4Pi;
  for (std::size_t i = 1; i < f.size(); ++i) g[i] = b * f[i];
  return g;
}

double dcFreeNorm(std::span<const double> f) {
  double s = 0.0;
  for (std::size_t i = 1; i < f.size(); ++i) s += f[i] * f[i];
  return std::sqrt(s);
}

}  // namespace

std::vector<double> expOl(std::span<const double> f, LogKind kind) {
  const ExpTables& t = expTables(checkedExpOrder(f.size()), kind);
  auto g = olNoDc(t, f, dcFreeNorm(f));
  const double s = dcFactor(f[0]);
  for (double& x : g) x *= s;
  return g;
}

std::vector<double> expHybrid(std::span<const double> f, int* squarings, LogKind kind) {
  const int order = checkedExpOrder(f.size());
  const ExpTables& t = expTables(order, kind);
  double m = dcFreeNorm(f);
  int k = 0;
  while (m > ExpTables::kMaxMagnitude && k < 30) {
    m *= 0.5;
    ++k;
  }
  std::vector<double> h(f.begin(), f.end());
  const double scale = std::ldexp(1.0, -k);
  for (std::size_t i = 1; i < h.size(); ++i) h[i] *= scale;
  auto g = olNoDc(t, h, m);
  // Continuity at the switch (sh_exp.hpp): blend towards one more halving as m nears the OL range's end.
  const double x = std::clamp((m - ExpTables::kHybridBlendStart) / (ExpTables::kMaxMagnitude - ExpTables::kHybridBlendStart), 0.0, 1.0);
  const double w = x * x * (3.0 - 2.0 * x);
  if (w > 0.0) {
    std::vector<double> half(h);
    for (std::size_t i = 1; i < half.size(); ++i) half[i] *= 0.5;
    auto q = olNoDc(t, half, 0.5 * m);
    q = product<double>(q, q, order);
    for (std::size_t i = 0; i < g.size(); ++i) g[i] = (1.0 - w) * g[i] + w * q[i];
  }
  for (int i = 0; i < k; ++i) g = product<double>(g, g, order);  // exp(2x) = exp(x)²
  const double s = dcFactor(f[0]);
  for (double& x : g) x *= s;
  if (squarings) *squarings = k;
  return g;
}

}  // namespace bounce::sh
