#include "engine/gi/rtf/cpca.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/packing.hpp>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/core/progress.hpp"
#include "engine/gi/rtf/dense.hpp"
#include "engine/math/sampling.hpp"

namespace bounce::gi::rtf {

namespace {

constexpr std::size_t kBlock = 64;  // samples per task of the blocked products
constexpr std::size_t kColumns = 512;  // columns per task of the subspace iteration's Yᵀ P
// Reassignment tries the sample's own cluster and the clusters of its kNearestMeans nearest means
// (SHHS03 tries all n_c). Trying all is n_c·(n_e+1)·D multiply-adds per sample — 82·10⁹ a round
// at the paper's settings, more than the whole bake may take. Measured (textured box, 16 spheres ×
// 6·8² samples, 32 × 16): all 32 → 5.70 %, these ≤ 5 → 5.71 %, at 61 % of the CPU time.
constexpr int kNearestMeans = 4;

// Four independent chains (a fixed order: the same bytes on every thread count): one chain was
// bound by the add's latency, and Gram–Schmidt at n_e = 80 calls this 80² times per product.
double dotd(const double* a, const double* b, std::size_t n) {
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4)
    for (int l = 0; l < 4; ++l) s[l] += a[i + std::size_t(l)] * b[i + std::size_t(l)];
  for (; i < n; ++i) s[0] += a[i] * b[i];
  return (s[0] + s[1]) + (s[2] + s[3]);
}

// One cluster's Eq. 9 basis, (ne+1) float rows of D: the mean E_h0, then E_h1..E_hne.
struct Basis {
  std::vector<float> rows;
  std::vector<float> meanProj;  // E_hj · E_h0, j = 1..ne (the reassignment projects x, not x − E_h0)
  float meanNorm2 = 0.0f;
};

// Mean and an orthonormal basis of the principal ne-subspace of the samples `members`.
// `start` (optional): the cluster's previous basis: its rows start the iteration (a warm start:
// a few products then suffice); rows that are zero there start random.
Basis fitCluster(std::span<const float> data, std::size_t D, const std::vector<std::size_t>& members, int ne,
                 int powerIterations, std::uint64_t seed, const Basis* start, std::vector<float>& Y) {
  Basis out;
  out.rows.assign(std::size_t(ne + 1) * D, 0.0f);
  out.meanProj.assign(std::size_t(ne), 0.0f);
  if (members.empty()) return out;
  const std::size_t n = members.size();
  std::vector<double> mean(D, 0.0);
  parallelFor(0, (D + kColumns - 1) / kColumns, [&](std::size_t cb) {  // each column summed in member order
    const std::size_t d0 = cb * kColumns, d1 = std::min(D, d0 + kColumns);
    for (std::size_t r : members)
      for (std::size_t d = d0; d < d1; ++d) mean[d] += data[r * D + d];
  });
  for (std::size_t d = 0; d < D; ++d) out.rows[d] = float(mean[d] /= double(n));
  out.meanNorm2 = dense::dot(out.rows.data(), out.rows.data(), D);
  if (ne == 0) return out;
  // Centred rows Y (n × D), float: the products below are float, so the mean must not ride along.
  // Y is the caller's scratch (one buffer for all clusters: a fresh n·D allocation per fit spent
  // ~10 % of the CPCA in page faults and zeroing at 6·64², session 13).
  if (Y.size() < n * D) Y.resize(n * D);
  std::vector<const float*> yRows(n);
  std::vector<double> rowEnergy(n);
  parallelFor(0, n, [&](std::size_t i) {
    const float* x = data.data() + members[i] * D;
    float* y = Y.data() + i * D;
    double e = 0.0;
    for (std::size_t d = 0; d < D; ++d) y[d] = float(double(x[d]) - mean[d]), e += double(y[d]) * y[d];
    yRows[i] = y, rowEnergy[i] = e;
  }, 16);
  double energy = 0.0;  // ‖Y‖_F², summed in sample order (the same bytes on any thread count)
  for (double e : rowEnergy) energy += e;
  // Start vectors: random (generic, so they are not orthogonal to the data's span).
  math::Pcg32 rng(seed);
  std::vector<double> V(std::size_t(ne) * D);
  for (double& v : V) v = rng.nextDouble() * 2.0 - 1.0;
  if (start != nullptr && start->rows.size() == out.rows.size())
    for (int j = 0; j < ne; ++j) {
      const float* row = start->rows.data() + std::size_t(j + 1) * D;
      if (dense::dot(row, row, D) > 0.5f) std::copy(row, row + D, V.begin() + std::ptrdiff_t(std::size_t(j) * D));
    }
  // Modified Gram–Schmidt in double, twice ("twice is enough", Kahan/Parlett).
  const auto orthonormalize = [&](std::vector<double>& W, bool product) {
    for (int j = 0; j < ne; ++j) {
      double* w = W.data() + std::size_t(j) * D;
      for (int pass = 0; pass < 2; ++pass)
        for (int i = 0; i < j; ++i) {
          const double* u = W.data() + std::size_t(i) * D;
          const double a = dotd(w, u, D);
          for (std::size_t d = 0; d < D; ++d) w[d] -= a * u[d];
        }
      const double len = std::sqrt(dotd(w, w, D));
      // After a product, |w| ≈ the eigenvalue λ_j of YᵀY (Σλ = ‖Y‖_F²). A direction below 1e-7 of
      // the cluster's energy (the float products' noise, ≈ 6e-8·‖Y‖_F²) is rank the data does not
      // have: a zero row, α = 0 for every sample. Before the first product (|w| = 1) keep all.
      if (len > 0.0 && (!product || len > 1e-7 * energy)) {
        for (std::size_t d = 0; d < D; ++d) w[d] /= len;
      } else {
        std::fill(w, w + D, 0.0);
      }
    }
  };
  orthonormalize(V, false);
  std::vector<float> Vf(V.size()), P(n * std::size_t(ne)), W(V.size());
  for (int it = 0; it < std::max(powerIterations, 1); ++it) {
    // P = Y Vᵀ (n × ne), then Wᵀ = Yᵀ P (ne rows of D): one product with Y Yᵀ's row space.
    std::transform(V.begin(), V.end(), Vf.begin(), [](double v) { return float(v); });
    // Both products split among threads (a cluster can hold half the samples: the clusters alone
    // left one core idle): P by blocks of rows, Wᵀ by blocks of columns. Every entry is summed in
    // the same order whatever the split (dense.hpp), so the result does not depend on the threads.
    parallelFor(0, (n + kBlock - 1) / kBlock, [&](std::size_t b) {
      const std::size_t i0 = b * kBlock;
      dense::dots(yRows.data() + i0, std::min(n, i0 + kBlock) - i0, Vf.data(), std::size_t(ne), D, P.data() + i0 * std::size_t(ne));
    });
    std::fill(W.begin(), W.end(), 0.0f);
    parallelFor(0, (D + kColumns - 1) / kColumns, [&](std::size_t cb) {
      const std::size_t d0 = cb * kColumns;
      std::vector<const float*> cols(n);
      for (std::size_t i = 0; i < n; ++i) cols[i] = yRows[i] + d0;
      dense::addOuter(P.data(), cols.data(), n, std::size_t(ne), std::min(D, d0 + kColumns) - d0, W.data() + d0, D);
    });
    std::transform(W.begin(), W.end(), V.begin(), [](float w) { return double(w); });
    orthonormalize(V, true);
  }
  std::transform(V.begin(), V.end(), out.rows.begin() + std::ptrdiff_t(D), [](double v) { return float(v); });
  for (int j = 0; j < ne; ++j) out.meanProj[std::size_t(j)] = dense::dot(out.rows.data() + std::size_t(j + 1) * D, out.rows.data(), D);
  return out;
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
  const std::size_t N = data.size() / D;
  if (N == 0) throw InternalError("rtf::compress: no samples");
  const std::size_t blocks = (N + kBlock - 1) / kBlock;
  std::vector<char> finite(blocks, 1);
  std::vector<float> norm2(N);  // ‖x_r‖²
  parallelFor(0, blocks, [&](std::size_t b) {
    for (std::size_t r = b * kBlock; r < std::min(N, (b + 1) * kBlock); ++r) {
      const float* x = data.data() + r * D;
      for (std::size_t d = 0; d < D; ++d)
        if (!std::isfinite(x[d])) finite[b] = 0;
      norm2[r] = dense::dot(x, x, D);
    }
  });
  if (std::find(finite.begin(), finite.end(), 0) != finite.end()) throw InternalError("rtf::compress: non-finite data");
  const int nc = int(std::min<std::size_t>(std::size_t(s.clusters), N));
  const int ne = s.components;
  std::vector<const float*> rows(N);
  for (std::size_t r = 0; r < N; ++r) rows[r] = data.data() + r * D;

  constexpr int kLloydRounds = 8;
  Progress progress("rtf cpca", std::size_t(nc + kLloydRounds + s.iterations + 1));
  // k-means++ seeds (Arthur & Vassilvitskii 2007): the first at random, each next one drawn with
  // probability ∝ its squared distance to the nearest seed so far. Farthest-point seeds (the
  // deterministic extreme of this) spent 24 of 32 clusters on 3-sample groups of outliers — the
  // samples next to the surface, whose M are largest — and left one cluster 2677 of 6144 samples.
  // Distances as ‖x‖² − 2x·c + ‖c‖² (one pass over the data per seed, no subtraction per float).
  math::Pcg32 seedRng(0x5eedc0deu);
  std::vector<float> centres(std::size_t(nc) * D);
  std::vector<float> centreNorm2(static_cast<std::size_t>(nc));
  std::vector<double> nearest(N, std::numeric_limits<double>::infinity());
  std::size_t next = std::min<std::size_t>(N - 1, std::size_t(seedRng.nextDouble() * double(N)));
  // The first seed must not be a zero sample (a zero vector is no line: every distance to it would
  // be 0 and every later seed repeat it); the ITF has many (the samples inside the object).
  for (std::size_t k = 0; k < N && !(norm2[next] > 0.0f); ++k) next = (next + 1) % N;
  for (int h = 0; h < nc; ++h) {
    float* c = centres.data() + std::size_t(h) * D;
    std::copy(rows[next], rows[next] + D, c);
    centreNorm2[std::size_t(h)] = norm2[next];
    parallelFor(0, N, [&](std::size_t r) {
      const double xc = dense::dot(rows[r], c, D);
      // The distance between lines through 0 (sin² of the angle; 0 for a zero sample).
      const double d2 = norm2[r] > 0.0f && centreNorm2[std::size_t(h)] > 0.0f
                            ? 1.0 - xc * xc / (double(norm2[r]) * centreNorm2[std::size_t(h)]) : 0.0;
      nearest[r] = std::min(nearest[r], std::max(d2, 0.0));
    }, 64);
    nearest[next] = 0.0;
    double total = 0.0;
    for (double d2 : nearest) total += d2;
    if (!(total > 0.0)) {  // every sample is on a seed already: the rest repeat one (empty clusters)
      next = 0;
    } else {
      double u = seedRng.nextDouble() * total;
      next = N - 1;
      for (std::size_t r = 0; r < N; ++r)
        if ((u -= nearest[r]) < 0.0 && nearest[r] > 0.0) {
          next = r;
          break;
        }
    }
    progress.advance();
  }
  // Lloyd k-means, until no sample moves (at most kLloydRounds).
  std::vector<std::uint32_t> assign(N, 0);
  const auto nearestCentres = [&](bool* moved) {
    std::vector<char> changed(blocks, 0);
    parallelFor(0, blocks, [&](std::size_t b) {
      const std::size_t r0 = b * kBlock, n = std::min(N, r0 + kBlock) - r0;
      std::vector<float> dot(n * std::size_t(nc));
      dense::dots(rows.data() + r0, n, centres.data(), std::size_t(nc), D, dot.data());
      for (std::size_t i = 0; i < n; ++i) {
        float best = std::numeric_limits<float>::infinity();
        std::uint32_t arg = 0;
        for (int h = 0; h < nc; ++h) {
          const float xc = dot[i * std::size_t(nc) + std::size_t(h)];
          const float d2 = -xc * xc;  // −cos²·‖x‖² against unit centres: the nearest line
          if (d2 < best) best = d2, arg = std::uint32_t(h);
        }
        if (assign[r0 + i] != arg) changed[b] = 1;
        assign[r0 + i] = arg;
      }
    });
    *moved = std::find(changed.begin(), changed.end(), 1) != changed.end();
  };
  // The centre of a line cluster: the mean of its unit samples, each signed to face the current
  // centre (x and −x are the same line): weight[r] = ±1/‖x_r‖.
  std::vector<double> weight(N, 0.0);
  for (int it = 0; it < kLloydRounds; ++it, progress.advance()) {
    bool moved = false;
    nearestCentres(&moved);
    if (!moved && it > 0) break;
    parallelFor(0, N, [&](std::size_t r) {
      const double xc = dense::dot(rows[r], centres.data() + std::size_t(assign[r]) * D, D);
      weight[r] = norm2[r] > 0.0f ? (xc < 0.0 ? -1.0 : 1.0) / std::sqrt(double(norm2[r])) : 0.0;
    }, 64);
    std::vector<std::size_t> count(std::size_t(nc), 0);
    for (std::size_t r = 0; r < N; ++r) ++count[assign[r]];
    // Means in double, the columns split across threads.
    const std::size_t colBlocks = (D + 255) / 256;
    parallelFor(0, colBlocks, [&](std::size_t cb) {
      const std::size_t d0 = cb * 256, d1 = std::min(D, d0 + 256);
      std::vector<double> sum(std::size_t(nc) * (d1 - d0), 0.0);
      for (std::size_t r = 0; r < N; ++r) {
        double* sr = sum.data() + std::size_t(assign[r]) * (d1 - d0);
        const double w = weight[r];
        for (std::size_t d = d0; d < d1; ++d) sr[d - d0] += w * rows[r][d];
      }
      for (int h = 0; h < nc; ++h)
        if (count[std::size_t(h)] > 0)
          for (std::size_t d = d0; d < d1; ++d)
            centres[std::size_t(h) * D + d] = float(sum[std::size_t(h) * (d1 - d0) + d - d0] / double(count[std::size_t(h)]));
    });
    for (int h = 0; h < nc; ++h) {
      float* c = centres.data() + std::size_t(h) * D;
      centreNorm2[std::size_t(h)] = dense::dot(c, c, D);
      if (centreNorm2[std::size_t(h)] > 0.0f) {  // unit centres: the line's direction
        const float inv = 1.0f / std::sqrt(centreNorm2[std::size_t(h)]);
        for (std::size_t d = 0; d < D; ++d) c[d] *= inv;
        centreNorm2[std::size_t(h)] = 1.0f;
      }
    }
  }

  // CPCA rounds: fit, then reassign by reconstruction error.
  std::vector<Basis> bases(static_cast<std::size_t>(nc));
  bool warm = false;  // after the first fit, each cluster starts from its previous basis
  std::vector<float> scratch;  // the centred cluster, fitCluster's Y
  const auto fitAll = [&]() {
    std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(nc));
    for (std::size_t r = 0; r < N; ++r) members[assign[r]].push_back(r);
    const int iterations = warm ? std::max(3, s.powerIterations / 4) : s.powerIterations;
    // One cluster after the other, each fit's products split among the threads (fitCluster): with
    // n_c = 8 and uneven clusters a loop over clusters left a core idle.
    for (std::size_t h = 0; h < std::size_t(nc); ++h) {
      const Basis previous = bases[h];
      bases[h] = fitCluster(data, D, members[h], ne, iterations, 0x5eed0000u + h, warm ? &previous : nullptr, scratch);
    }
    warm = true;
    return members;
  };
  const int tries = std::min(nc, kNearestMeans);
  std::vector<float> means(std::size_t(nc) * D);
  for (int it = 0; it < s.iterations; ++it) {
    const auto members = fitAll();
    for (int h = 0; h < nc; ++h)
      std::copy_n(bases[std::size_t(h)].rows.begin(), D, means.begin() + std::ptrdiff_t(std::size_t(h) * D));
    // Candidates per sample: its cluster, then the clusters of its `tries` nearest means.
    const std::size_t K = std::size_t(tries) + 1;
    std::vector<std::int32_t> cand(N * K, -1);
    std::vector<float> meanDist(N * K), residual(N * K, std::numeric_limits<float>::infinity());
    parallelFor(0, blocks, [&](std::size_t b) {
      const std::size_t r0 = b * kBlock, n = std::min(N, r0 + kBlock) - r0;
      std::vector<float> dot(n * std::size_t(nc));
      dense::dots(rows.data() + r0, n, means.data(), std::size_t(nc), D, dot.data());
      std::vector<std::pair<float, int>> order;
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t r = r0 + i;
        order.clear();
        for (int h = 0; h < nc; ++h)
          if (!members[std::size_t(h)].empty())
            order.emplace_back(norm2[r] - 2.0f * dot[i * std::size_t(nc) + std::size_t(h)] + bases[std::size_t(h)].meanNorm2, h);
        const std::size_t keep = std::min<std::size_t>(std::size_t(tries), order.size());
        std::partial_sort(order.begin(), order.begin() + std::ptrdiff_t(keep), order.end());
        const int own = int(assign[r]);
        cand[r * K] = own;
        const auto distToMean = [&](int h) {  // ‖x − E_h0‖²
          return norm2[r] - 2.0f * dot[i * std::size_t(nc) + std::size_t(h)] + bases[std::size_t(h)].meanNorm2;
        };
        meanDist[r * K] = distToMean(own);
        for (std::size_t t = 0; t < keep; ++t)
          if (order[t].second != own) cand[r * K + t + 1] = order[t].second, meanDist[r * K + t + 1] = distToMean(order[t].second);
      }
    });
    // Residual ‖x − E_0‖² − Σ_j (E_j·x − E_j·E_0)², batched per cluster over the samples that try it.
    std::vector<std::vector<std::size_t>> tryers(static_cast<std::size_t>(nc));  // entries r·K + slot
    for (std::size_t e = 0; e < N * K; ++e)
      if (cand[e] >= 0) tryers[std::size_t(cand[e])].push_back(e);
    for (int h = 0; h < nc; ++h) {
      const Basis& B = bases[std::size_t(h)];
      const auto& list = tryers[std::size_t(h)];
      parallelFor(0, (list.size() + kBlock - 1) / kBlock, [&](std::size_t b) {
        const std::size_t e0 = b * kBlock, n = std::min(list.size(), e0 + kBlock) - e0;
        std::vector<const float*> x(n);
        for (std::size_t i = 0; i < n; ++i) x[i] = rows[list[e0 + i] / K];
        std::vector<float> proj(n * std::size_t(ne));
        if (ne > 0) dense::dots(x.data(), n, B.rows.data() + D, std::size_t(ne), D, proj.data());
        for (std::size_t i = 0; i < n; ++i) {
          const std::size_t e = list[e0 + i];
          double r2 = meanDist[e];
          for (int j = 0; j < ne; ++j) {
            const double a = double(proj[i * std::size_t(ne) + std::size_t(j)]) - B.meanProj[std::size_t(j)];
            r2 -= a * a;
          }
          residual[e] = float(std::max(r2, 0.0));
        }
      });
    }
    for (std::size_t r = 0; r < N; ++r) {
      std::size_t best = r * K;
      for (std::size_t t = 1; t < K; ++t)
        if (cand[r * K + t] >= 0 && residual[r * K + t] < residual[best]) best = r * K + t;
      assign[r] = std::uint32_t(cand[best]);
    }
    progress.advance();
  }
  const auto members = fitAll();
  progress.advance();
  progress.finish();

  Cpca out;
  out.dimension = int(D), out.clusters = nc, out.components = ne;
  out.cluster = assign;
  out.basis.resize(std::size_t(nc) * std::size_t(ne + 1) * D);
  for (int h = 0; h < nc; ++h)
    std::copy(bases[std::size_t(h)].rows.begin(), bases[std::size_t(h)].rows.end(),
              out.basis.begin() + std::ptrdiff_t(std::size_t(h) * std::size_t(ne + 1) * D));
  // α = E_jᵀ(x − E_0) from the centred sample (float products of x and E_0 separately would lose
  // the digits of α where the mean is large against the variation).
  out.alpha.assign(N * std::size_t(ne), 0.0f);
  if (ne > 0)
    for (int h = 0; h < nc; ++h) {
      const auto& list = members[std::size_t(h)];
      const float* B = bases[std::size_t(h)].rows.data();
      parallelFor(0, (list.size() + kBlock - 1) / kBlock, [&](std::size_t b) {
        const std::size_t i0 = b * kBlock, n = std::min(list.size(), i0 + kBlock) - i0;
        std::vector<float> y(n * D), proj(n * std::size_t(ne));
        std::vector<const float*> yRows(n);
        for (std::size_t i = 0; i < n; ++i) {
          for (std::size_t d = 0; d < D; ++d) y[i * D + d] = rows[list[i0 + i]][d] - B[d];
          yRows[i] = y.data() + i * D;
        }
        dense::dots(yRows.data(), n, B + D, std::size_t(ne), D, proj.data());
        for (std::size_t i = 0; i < n; ++i)
          std::copy(proj.begin() + std::ptrdiff_t(i * std::size_t(ne)), proj.begin() + std::ptrdiff_t((i + 1) * std::size_t(ne)),
                    out.alpha.begin() + std::ptrdiff_t(list[i0 + i] * std::size_t(ne)));
      });
    }
  return out;
}

CpcaError measure(const Cpca& c, std::span<const float> data) {
  const std::size_t D = std::size_t(c.dimension), N = c.samples();
  if (data.size() != N * D) throw InternalError("rtf::measure: data does not match the compression");
  const std::size_t blocks = (N + kBlock - 1) / kBlock;
  std::vector<double> errB(blocks, 0.0), normB(blocks, 0.0);
  parallelFor(0, blocks, [&](std::size_t b) {
    std::vector<float> xr(D);
    for (std::size_t r = b * kBlock; r < std::min(N, (b + 1) * kBlock); ++r) {
      c.reconstruct(r, xr);
      for (std::size_t d = 0; d < D; ++d) {
        const double t = double(data[r * D + d]);
        errB[b] += (t - xr[d]) * (t - xr[d]);
        normB[b] += t * t;
      }
    }
  });
  double err = 0.0, norm = 0.0;
  for (std::size_t b = 0; b < blocks; ++b) err += errB[b], norm += normB[b];
  CpcaError e;
  e.frobenius = norm > 0.0 ? std::sqrt(err / norm) : std::sqrt(err);
  e.ratio = compressionRatio(c);
  e.stored = storedRatio(c);
  return e;
}

namespace {
constexpr float kHalfMax = 65504.0f;  // the largest finite half
float toHalf(float x) { return glm::unpackHalf1x16(glm::packHalf1x16(x)); }

// The 8-bit code of v under scale (0 for a zero scale: the row or sample is all zeros).
float code(float v, float scale) { return scale > 0.0f ? std::nearbyint(v / scale) : 0.0f; }
// max |v| / 127 over [first, last): the scale that maps the largest value to code ±127.
float byteScale(const float* first, const float* last) {
  float m = 0.0f;
  for (const float* v = first; v != last; ++v) m = std::max(m, std::abs(*v));
  return m / 127.0f;
}
}  // namespace

void quantize(Cpca& c, int n8) {
  const int ne = c.components;
  if (n8 < 0 || n8 > ne) throw InternalError("rtf::quantize: byteComponents must be in 0..components");
  const std::size_t D = std::size_t(c.dimension), N = c.samples(), nc = std::size_t(c.clusters);
  const std::size_t head = std::size_t(ne - n8) + 1;  // rows 0 (mean) .. ne − n₈ of each cluster: halves
  c.byteComponents = n8;
  c.basisScale.assign(nc * std::size_t(n8), 0.0f);
  c.alphaScale.assign(n8 > 0 ? N : 0, 0.0f);
  const auto half = [](float& x) {
    const float h = toHalf(x);
    if (!(std::abs(h) <= kHalfMax)) throw InternalError("rtf::quantize: a CPCA value beyond fp16's range (65504)");
    x = h;
  };
  const auto bytes = [](float* first, float* last, float& scale) {
    scale = byteScale(first, last);
    for (float* v = first; v != last; ++v) *v = scale * code(*v, scale);
  };
  for (std::size_t h = 0; h < nc; ++h)
    for (std::size_t j = 0; j <= std::size_t(ne); ++j) {
      float* row = c.basis.data() + (h * std::size_t(ne + 1) + j) * D;
      if (j < head) std::for_each(row, row + D, half);
      else bytes(row, row + D, c.basisScale[h * std::size_t(n8) + j - head]);
    }
  for (std::size_t r = 0; r < N; ++r) {
    float* a = c.alpha.data() + r * std::size_t(ne);
    std::for_each(a, a + (head - 1), half);
    if (n8 > 0) bytes(a + (head - 1), a + ne, c.alphaScale[r]);
  }
}

bool isQuantized(const Cpca& c) {
  const int ne = c.components, n8 = c.byteComponents;
  const std::size_t D = std::size_t(c.dimension), N = c.samples(), nc = std::size_t(c.clusters);
  if (n8 < 0 || n8 > ne || c.basisScale.size() != nc * std::size_t(n8) || c.alphaScale.size() != (n8 > 0 ? N : 0))
    return false;
  const std::size_t head = std::size_t(ne - n8) + 1;
  const auto isHalf = [](float x) { return toHalf(x) == x; };  // NaN fails
  const auto isCoded = [](const float* first, const float* last, float scale) {
    if (!(scale >= 0.0f) || !std::isfinite(scale)) return false;
    for (const float* v = first; v != last; ++v) {
      const float q = code(*v, scale);
      if (!(std::abs(q) <= 127.0f) || !(scale * q == *v)) return false;
    }
    return true;
  };
  for (std::size_t h = 0; h < nc; ++h)
    for (std::size_t j = 0; j <= std::size_t(ne); ++j) {
      const float* row = c.basis.data() + (h * std::size_t(ne + 1) + j) * D;
      if (j < head ? !std::all_of(row, row + D, isHalf) : !isCoded(row, row + D, c.basisScale[h * std::size_t(n8) + j - head]))
        return false;
    }
  for (std::size_t r = 0; r < N; ++r) {
    const float* a = c.alpha.data() + r * std::size_t(ne);
    if (!std::all_of(a, a + (head - 1), isHalf)) return false;
    if (n8 > 0 && !isCoded(a + (head - 1), a + ne, c.alphaScale[r])) return false;
  }
  return true;
}

CpcaParts storedParts(const Cpca& c) {
  if (!isQuantized(c)) throw InternalError("rtf::storedParts: CPCA not quantized (rtf::quantize)");
  const std::size_t D = std::size_t(c.dimension), N = c.samples(), nc = std::size_t(c.clusters);
  const std::size_t ne = std::size_t(c.components), n8 = std::size_t(c.byteComponents), head = ne - n8;
  CpcaParts p;
  const auto codes = [](const float* first, const float* last, float scale, std::vector<std::int8_t>& out) {
    for (const float* v = first; v != last; ++v) out.push_back(std::int8_t(code(*v, scale)));
  };
  for (std::size_t h = 0; h < nc; ++h) {
    const float* b = c.basis.data() + h * (ne + 1) * D;
    p.basisHalves.insert(p.basisHalves.end(), b, b + (head + 1) * D);
    for (std::size_t t = 0; t < n8; ++t) codes(b + (head + 1 + t) * D, b + (head + 2 + t) * D, c.basisScale[h * n8 + t], p.basisCodes);
  }
  for (std::size_t r = 0; r < N; ++r) {
    const float* a = c.alpha.data() + r * ne;
    p.alphaHalves.insert(p.alphaHalves.end(), a, a + head);
    if (n8 > 0) codes(a + head, a + ne, c.alphaScale[r], p.alphaCodes);
  }
  return p;
}

double storedBytes(std::size_t N, std::size_t D, int nc, int ne, int n8) {
  const double halves = double(nc) * double(ne - n8 + 1) * double(D) + double(N) * double(ne - n8);
  const double codes = double(nc) * double(n8) * double(D) + double(N) * double(n8);
  const double scales = n8 > 0 ? double(nc) * double(n8) + double(N) : 0.0;
  return 2.0 * halves + codes + 4.0 * scales + 4.0 * double(N);
}

double storedRatio(const Cpca& c) {
  const double N = double(c.samples());
  return 4.0 * N * double(c.dimension) / storedBytes(c.samples(), std::size_t(c.dimension), c.clusters, c.components, c.byteComponents);
}

double compressionRatio(const Cpca& c) {
  const double N = double(c.samples());
  return N * double(c.dimension) / (double(c.basis.size()) + N * double(c.components + 1));
}

}  // namespace bounce::gi::rtf
