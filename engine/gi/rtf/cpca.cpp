#include "engine/gi/rtf/cpca.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/progress.hpp"
#include "engine/math/sampling.hpp"

namespace bounce::gi::rtf {

namespace {

using Vec = std::vector<double>;

double dot(const double* a, const double* b, std::size_t n) {
  double s = 0.0;
  for (std::size_t i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

// Squared distance of x to its reconstruction in cluster h (basis rows b, D wide; ne+1 rows).
double residual2(const float* x, const Vec& basis, std::size_t D, int ne, std::vector<double>& scratch) {
  scratch.assign(D, 0.0);
  for (std::size_t d = 0; d < D; ++d) scratch[d] = double(x[d]) - basis[d];
  double r2 = dot(scratch.data(), scratch.data(), D);
  for (int j = 1; j <= ne; ++j) {
    const double a = dot(scratch.data(), basis.data() + std::size_t(j) * D, D);
    r2 -= a * a;  // orthonormal rows: ‖y − Σ a_j e_j‖² = ‖y‖² − Σ a_j²
  }
  return std::max(r2, 0.0);
}

// Mean and an orthonormal basis of the principal ne-subspace of the samples `members`.
// `start` (optional): the cluster's previous basis (mean row first): its rows start the iteration
// (a warm start: a few products then suffice); rows that are zero there start random.
Vec fitCluster(std::span<const float> data, std::size_t D, const std::vector<std::size_t>& members, int ne,
               int powerIterations, std::uint64_t seed, const Vec* start) {
  Vec basis(std::size_t(ne + 1) * D, 0.0);
  if (members.empty()) return basis;
  for (std::size_t r : members)
    for (std::size_t d = 0; d < D; ++d) basis[d] += data[r * D + d];
  for (std::size_t d = 0; d < D; ++d) basis[d] /= double(members.size());
  if (ne == 0) return basis;
  const std::size_t n = members.size();
  // Centred rows Y (n × D).
  std::vector<double> Y(n * D);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t d = 0; d < D; ++d) Y[i * D + d] = double(data[members[i] * D + d]) - basis[d];
  // Start vectors: random (generic, so they are not orthogonal to the data's span).
  math::Pcg32 rng(seed);
  std::vector<double> V(std::size_t(ne) * D);
  for (double& v : V) v = rng.nextDouble() * 2.0 - 1.0;
  if (start != nullptr && start->size() == basis.size())
    for (int j = 0; j < ne; ++j) {
      const double* row = start->data() + std::size_t(j + 1) * D;
      if (dot(row, row, D) > 0.5) std::copy(row, row + D, V.begin() + std::ptrdiff_t(std::size_t(j) * D));  // unit rows
    }
  double scale = 0.0;
  for (double y : Y) scale = std::max(scale, std::abs(y));
  const auto orthonormalize = [&](std::vector<double>& W) {
    for (int j = 0; j < ne; ++j) {
      double* w = W.data() + std::size_t(j) * D;
      for (int pass = 0; pass < 2; ++pass)  // twice is enough (Kahan/Parlett "twice is enough")
        for (int i = 0; i < j; ++i) {
          const double* u = W.data() + std::size_t(i) * D;
          const double a = dot(w, u, D);
          for (std::size_t d = 0; d < D; ++d) w[d] -= a * u[d];
        }
      const double len = std::sqrt(dot(w, w, D));
      // A direction with nothing of the data left (rank < ne): a zero row, α = 0 for every sample.
      if (len > 1e-9 * std::max(scale, 1e-30) * std::sqrt(double(n))) {
        for (std::size_t d = 0; d < D; ++d) w[d] /= len;
      } else {
        std::fill(w, w + D, 0.0);
      }
    }
  };
  std::vector<double> proj(n * std::size_t(ne));
  for (int it = 0; it < std::max(powerIterations, 1); ++it) {
    // P = Y V (n × ne), W = Yᵀ P (ne × D rows).
    for (std::size_t i = 0; i < n; ++i)
      for (int j = 0; j < ne; ++j) proj[i * ne + j] = dot(Y.data() + i * D, V.data() + std::size_t(j) * D, D);
    std::fill(V.begin(), V.end(), 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (int j = 0; j < ne; ++j) {
        const double p = proj[i * ne + j];
        double* w = V.data() + std::size_t(j) * D;
        const double* y = Y.data() + i * D;
        for (std::size_t d = 0; d < D; ++d) w[d] += p * y[d];
      }
    orthonormalize(V);
  }
  std::copy(V.begin(), V.end(), basis.begin() + std::ptrdiff_t(D));
  return basis;
}

}  // namespace

void Cpca::reconstruct(std::size_t r, std::span<float> out) const {
  const std::size_t D = std::size_t(dimension);
  if (out.size() < D || r >= cluster.size()) throw InternalError("rtf::Cpca::reconstruct: bad sample or output");
  const float* b = basis.data() + std::size_t(cluster[r]) * std::size_t(components + 1) * D;
  for (std::size_t d = 0; d < D; ++d) out[d] = b[d];
  for (int j = 1; j <= components; ++j) {
    const float a = alpha[r * std::size_t(components) + std::size_t(j - 1)];
    const float* e = b + std::size_t(j) * D;
    for (std::size_t d = 0; d < D; ++d) out[d] += a * e[d];
  }
}

Cpca compress(std::span<const float> data, std::size_t D, const CpcaSettings& s) {
  if (D == 0 || data.size() % D != 0) throw InternalError("rtf::compress: data is not N·D floats");
  if (s.clusters < 1 || s.components < 0 || s.iterations < 0) throw InternalError("rtf::compress: bad settings");
  for (float x : data)
    if (!std::isfinite(x)) throw InternalError("rtf::compress: non-finite data");
  const std::size_t N = data.size() / D;
  if (N == 0) throw InternalError("rtf::compress: no samples");
  const int nc = int(std::min<std::size_t>(std::size_t(s.clusters), N));
  const int ne = s.components;
  const auto x = [&](std::size_t r) { return data.data() + r * D; };
  const auto dist2 = [&](const float* a, const double* c) {
    double s2 = 0.0;
    for (std::size_t d = 0; d < D; ++d) {
      const double t = double(a[d]) - c[d];
      s2 += t * t;
    }
    return s2;
  };

  constexpr int kLloydRounds = 8;
  Progress progress("rtf cpca", std::size_t(nc + kLloydRounds + s.iterations + 1));
  // Farthest-point seeds: sample 0, then repeatedly the sample farthest from every seed so far.
  std::vector<Vec> centres;
  std::vector<double> nearest(N, std::numeric_limits<double>::infinity());
  std::size_t next = 0;
  for (int h = 0; h < nc; ++h) {
    centres.emplace_back(x(next), x(next) + D);
    parallelFor(0, N, [&](std::size_t r) { nearest[r] = std::min(nearest[r], dist2(x(r), centres.back().data())); }, 64);
    next = std::size_t(std::max_element(nearest.begin(), nearest.end()) - nearest.begin());
    progress.advance();
  }
  // Lloyd k-means.
  std::vector<std::uint32_t> assign(N, 0);
  for (int it = 0; it < kLloydRounds; ++it, progress.advance()) {
    parallelFor(0, N, [&](std::size_t r) {
      double best = std::numeric_limits<double>::infinity();
      for (int h = 0; h < nc; ++h)
        if (const double d2 = dist2(x(r), centres[std::size_t(h)].data()); d2 < best) best = d2, assign[r] = std::uint32_t(h);
    }, 64);
    std::vector<std::size_t> count(std::size_t(nc), 0);
    for (auto& c : centres) std::fill(c.begin(), c.end(), 0.0);
    for (std::size_t r = 0; r < N; ++r) {
      ++count[assign[r]];
      for (std::size_t d = 0; d < D; ++d) centres[assign[r]][d] += x(r)[d];
    }
    for (int h = 0; h < nc; ++h)
      if (count[std::size_t(h)] > 0)
        for (double& c : centres[std::size_t(h)]) c /= double(count[std::size_t(h)]);
  }

  // CPCA rounds: fit, then reassign by reconstruction error.
  std::vector<Vec> bases(static_cast<std::size_t>(nc));
  bool warm = false;  // after the first fit, each cluster starts from its previous basis
  const auto fitAll = [&]() {
    std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(nc));
    for (std::size_t r = 0; r < N; ++r) members[assign[r]].push_back(r);
    const int iterations = warm ? std::max(3, s.powerIterations / 4) : s.powerIterations;
    parallelFor(0, std::size_t(nc), [&](std::size_t h) {
      const Vec previous = bases[h];
      bases[h] = fitCluster(data, D, members[h], ne, iterations, 0x5eed0000u + h, warm ? &previous : nullptr);
    });
    warm = true;
    return members;
  };
  for (int it = 0; it < s.iterations; ++it) {
    const auto members = fitAll();
    parallelFor(0, N, [&](std::size_t r) {
      std::vector<double> scratch;
      double best = std::numeric_limits<double>::infinity();
      std::uint32_t arg = assign[r];
      for (int h = 0; h < nc; ++h) {
        if (members[std::size_t(h)].empty()) continue;
        if (const double e = residual2(x(r), bases[std::size_t(h)], D, ne, scratch); e < best) best = e, arg = std::uint32_t(h);
      }
      assign[r] = arg;
    }, 16);
    progress.advance();
  }
  fitAll();
  progress.advance();
  progress.finish();

  Cpca out;
  out.dimension = int(D), out.clusters = nc, out.components = ne;
  out.cluster = assign;
  out.basis.resize(std::size_t(nc) * std::size_t(ne + 1) * D);
  for (int h = 0; h < nc; ++h)
    for (std::size_t i = 0; i < bases[std::size_t(h)].size(); ++i)
      out.basis[std::size_t(h) * std::size_t(ne + 1) * D + i] = float(bases[std::size_t(h)][i]);
  out.alpha.assign(N * std::size_t(ne), 0.0f);
  parallelFor(0, N, [&](std::size_t r) {
    const Vec& b = bases[assign[r]];
    for (int j = 1; j <= ne; ++j) {
      double a = 0.0;
      for (std::size_t d = 0; d < D; ++d) a += (double(x(r)[d]) - b[d]) * b[std::size_t(j) * D + d];
      out.alpha[r * std::size_t(ne) + std::size_t(j - 1)] = float(a);
    }
  }, 64);
  return out;
}

CpcaError measure(const Cpca& c, std::span<const float> data) {
  const std::size_t D = std::size_t(c.dimension), N = c.samples();
  if (data.size() != N * D) throw InternalError("rtf::measure: data does not match the compression");
  double err = 0.0, norm = 0.0;
  std::vector<float> xr(D);
  for (std::size_t r = 0; r < N; ++r) {
    c.reconstruct(r, xr);
    for (std::size_t d = 0; d < D; ++d) {
      const double t = double(data[r * D + d]);
      err += (t - xr[d]) * (t - xr[d]);
      norm += t * t;
    }
  }
  CpcaError e;
  e.frobenius = norm > 0.0 ? std::sqrt(err / norm) : std::sqrt(err);
  e.ratio = compressionRatio(c);
  return e;
}

double compressionRatio(const Cpca& c) {
  const double N = double(c.samples());
  return N * double(c.dimension) / (double(c.basis.size()) + N * double(c.components + 1));
}

}  // namespace bounce::gi::rtf
