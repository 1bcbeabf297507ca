#pragma once
// SH exponentiation of log-visibility (Ren, Wang, Snyder et al. 2006, "Real-time soft shadows in
// dynamic scenes using spherical harmonic exponentiation"; used by Guerrero et al. 2008, the SL
// paper, Eq. 6, 21–23). Orders 3 and 4 (9 or 16 coefficients), double precision.
//
// Definitions (orthonormal real SH of sh_eval.hpp; "1" is the constant function, coefficients
// (√(4π), 0, …)):
//  - exp(f) := the order-n projection of the pointwise e^{f(ω)} (Ren et al.'s definition);
//  - a spherical blocker of angular radius θ around +Z has visibility v_θ(ω) = 0 when ω·Z > cos θ,
//    else 1. Its zonal (ZH) projection g_θ has the closed form
//      g_0 = √π (1 + cos θ),  g_l = √(π(2l+1)) (P_{l+1}(cos θ) − P_{l−1}(cos θ)) / (2l+1),  l ≥ 1
//    (g_l = 2π ∫_{−1}^{cos θ} Y_l0(t) dt and ∫_{−1}^{c} P_l = (P_{l+1}(c) − P_{l−1}(c))/(2l+1));
//  - log(g_θ) := −λ_θ c_θ (LogKind below): c_θ the cap's indicator projection, windowed (Sloan's
//    sinc⁴, least width) to be ≥ 0 everywhere or raw; a clamped pointwise log of depth λ_θ inside the
//    blocker, λ_θ minimising ‖exp(f_θ) − g_θ‖₂ (why this and not an exact inverse or a DC-exact depth:
//    sh_exp.cpp, fitLambda). Tabulated by θ as the SL paper does (§5.1, "precompute the log G_θ …
//    for any angular radius θ"); Eq. 22 rotates it to the blocker's direction.
//  - expOl(f): DC isolation plus the optimal linear approximation (Ren et al.):
//      exp(f) ≈ e^{f_0 Y_00} (a(‖f̂‖) 1 + b(‖f̂‖) f̂),  f̂ = f without its DC term,
//    a and b tabulated by ‖f̂‖ by least squares against exp on a training set of log-visibility
//    directions (sums of 1–8 rotated single-blocker logs, fixed seed), see ExpTables;
//  - expHybrid(f): for ‖f̂‖ above the table's range, f̂ is halved k times until it fits, OL is
//    applied, and the result is squared k times with sh::product (Ren et al.'s "hybrid"). Ren et
//    al.'s switch is not continuous: where ‖f̂‖/2^k reaches kMaxMagnitude, OL(f̂) ≠ OL(f̂/2)² (a
//    step of 18–37 % of ‖exp‖ at ‖f̂‖ = 32 in tests/unit/sl/sh_exp_test.cpp). Ours: with m = ‖f̂‖/2^k in
//    (kMaxMagnitude/2, kMaxMagnitude], OL(f̂/2^k) is blended towards OL(f̂/2^{k+1})² by
//    w = smoothstep((m − kHybridBlendStart)/(kMaxMagnitude − kHybridBlendStart)), then squared k
//    times: at m = kMaxMagnitude it is exactly the k + 1 result the next magnitude starts from. Cost:
//    one more OL and one squaring inside the band only.
#include <array>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace bounce::sh {

// Which clamped log the tables hold (sh_exp.cpp, fitLambda, has the measurements):
//  - Windowed (default): −λ c_w, c_w the cap windowed to be ≥ 0. f ≤ 0 everywhere, so the exact
//    exp of ANY sum of blockers stays in (0, 1] (stable for dense clusters: RMS 0.75 at 64 heavily overlapping
//    blockers), but one small cap is blurred (its Ṽ is off by up to 37 %, corrected in sl::evaluate by
//    the Ratio form);
//  - Raw: λ(g_θ − 1), the unwindowed cap. Accurate for a few blockers (RMS 3e-4 for one, 0.1 for
//    four overlapping), but its ringing lobes add up: dense clusters of 16–64 blockers blow up (RMS
//    0.5–3.8, still finite).
enum class LogKind { Windowed, Raw };

// Closed-form ZH projection g_θ of one spherical blocker's visibility (order coefficients).
std::vector<double> capVisibilityZonal(double theta, int order);

// Order-n projection of e^{f(ω)} for a ZH vector f (order coefficients), by 1D Gauss–Legendre
// quadrature in cos θ (256 nodes: converged to < 1e-12 for |f| ≤ 60). The reference for tables/tests.
std::vector<double> expZonalExact(std::span<const double> zonal);

// Order-n projection of e^{f(ω)} for a full SH vector f, by sphere quadrature exact to degree
// `degree` (the integrand is smooth; degree 48 reaches ~1e-10 for ‖f‖ ≤ 8). For tables and tests.
std::vector<double> expExact(std::span<const double> f, int degree = 48);

// Scene-independent tables for one order (3 or 4), built once per order (thread-safe) by tables().
class ExpTables {
 public:
  static constexpr int kThetaEntries = 256;     // θ in [0, π/2], uniform
  static constexpr int kMagEntries = 128;       // ‖f̂‖ in [0, kMaxMagnitude], uniform
  static constexpr double kMaxMagnitude = 4.0;  // OL range; beyond it the hybrid halves
  static constexpr double kHybridBlendStart = 3.0;  // expHybrid blends over [this, kMaxMagnitude]

  int order() const { return order_; }
  // log(g_θ) as ZH (order coefficients), linear interpolation in θ; θ clamped to [0, π/2]
  // (after the receiver rules no blocker subtends more than a hemisphere).
  std::vector<double> logZonal(double theta) const;
  // The same rotated to unit direction d (Eq. 22).
  std::vector<double> logBlocker(double theta, const glm::dvec3& d) const;
  // a(m), b(m) for m in [0, kMaxMagnitude] (clamped), linear interpolation.
  std::array<double, 2> olCoefficients(double magnitude) const;
  // The largest ‖exp(f_θ) − g_θ‖₂ over the log table (the fit's residual), for tests.
  double logResidual() const { return logResidual_; }

  // Raw table rows for upload: logTable()[i·order + l], olTable()[2i + {0,1}].
  std::span<const double> logTable() const { return logTable_; }
  std::span<const double> olTable() const { return olTable_; }

  ExpTables(int order, LogKind kind);
  LogKind kind() const { return kind_; }

 private:
  int order_ = 0;
  LogKind kind_ = LogKind::Windowed;
  std::vector<double> logTable_;
  std::vector<double> olTable_;
  double logResidual_ = 0.0;
};

// The tables for order 3 or 4 (built on first use, ~1 s each). Throws InternalError for other orders.
const ExpTables& expTables(int order, LogKind kind = LogKind::Windowed);

// DC isolation + optimal linear approximation, valid for ‖f̂‖ ≤ kMaxMagnitude (clamped beyond).
std::vector<double> expOl(std::span<const double> f, LogKind kind = LogKind::Windowed);
// The hybrid: halving-and-squaring above kMaxMagnitude. Finite for any finite f; returns how many
// squarings it used in `squarings` when not null.
// `kind` selects the OL table, trained on sums of that kind's logs.
std::vector<double> expHybrid(std::span<const double> f, int* squarings = nullptr, LogKind kind = LogKind::Windowed);

}  // namespace bounce::sh
