// CPCA (paper §4.1, Eq. 9): exact on data that is exactly what Eq. 9 can represent, and the
// reported ratio is the count of floats it claims.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/gtc/packing.hpp>
#include <tbb/global_control.h>

#include "engine/core/error.hpp"
#include "engine/gi/rtf/cpca.hpp"
#include "engine/math/sampling.hpp"
#include "tests/unit/rtf/half_bound.hpp"

namespace bounce::gi::rtf {
namespace {

// `clusters` groups of `perCluster` samples: mean_h + Σ_{j<rank} a_j b_hj, means far apart
// (scale 100) against unit-scale variations, so every group is one cluster of Eq. 9.
std::vector<float> lowRank(int clusters, int perCluster, int rank, std::size_t D, std::uint64_t seed) {
  math::Pcg32 rng(seed);
  std::vector<float> x;
  for (int h = 0; h < clusters; ++h) {
    std::vector<float> mean(D), basis(std::size_t(rank) * D);
    for (float& m : mean) m = 100.0f * (rng.nextFloat() * 2.0f - 1.0f);
    for (float& b : basis) b = rng.nextFloat() * 2.0f - 1.0f;
    for (int s = 0; s < perCluster; ++s) {
      std::vector<float> a(static_cast<std::size_t>(rank));
      for (float& v : a) v = rng.nextFloat() * 2.0f - 1.0f;
      for (std::size_t d = 0; d < D; ++d) {
        float v = mean[d];
        for (int j = 0; j < rank; ++j) v += a[std::size_t(j)] * basis[std::size_t(j) * D + d];
        x.push_back(v);
      }
    }
  }
  return x;
}

TEST(RtfCpca, LowRankSingleClusterIsExact) {
  const std::size_t D = 60;
  const auto x = lowRank(1, 200, 3, D, 1);
  CpcaSettings s;
  s.clusters = 1;
  s.components = 3;
  const Cpca c = compress(x, D, s);
  const CpcaError e = measure(c, x);
  // Float storage of basis and α: relative error of a few float epsilons (1.2e-7) per term.
  EXPECT_LT(e.frobenius, 1e-5);
}

TEST(RtfCpca, LowRankClustersAreRecoveredExactly) {
  const std::size_t D = 48;
  const int clusters = 4, per = 50, rank = 2;
  const auto x = lowRank(clusters, per, rank, D, 2);
  CpcaSettings s;
  s.clusters = clusters;
  s.components = rank;
  const Cpca c = compress(x, D, s);
  const CpcaError e = measure(c, x);
  EXPECT_LT(e.frobenius, 1e-5);
  // Samples generated together share a cluster.
  for (int h = 0; h < clusters; ++h)
    for (int r = 1; r < per; ++r) EXPECT_EQ(c.cluster[std::size_t(h * per + r)], c.cluster[std::size_t(h * per)]);
  // Ratio: N·D floats against nc·(ne+1)·D basis floats + N·(ne+1) (α and the cluster id).
  const double N = clusters * per;
  EXPECT_DOUBLE_EQ(e.ratio, N * D / (clusters * (rank + 1) * double(D) + N * (rank + 1)));
}

TEST(RtfCpca, TooFewComponentsLeavesAnErrorThatMoreComponentsRemove) {
  const std::size_t D = 40;
  const auto x = lowRank(1, 100, 6, D, 3);
  CpcaSettings s;
  s.clusters = 1;
  s.components = 2;
  const double e2 = measure(compress(x, D, s), x).frobenius;
  s.components = 6;
  const double e6 = measure(compress(x, D, s), x).frobenius;
  EXPECT_GT(e2, 1e-4);  // 4 of the 6 directions dropped
  EXPECT_LT(e6, 1e-5);
}

TEST(RtfCpca, MoreClustersThanSamplesAndZeroDataStayFinite) {
  const std::size_t D = 8;
  std::vector<float> x(3 * D, 0.0f);
  CpcaSettings s;
  s.clusters = 10;
  s.components = 4;
  const Cpca c = compress(x, D, s);
  EXPECT_EQ(c.clusters, 3);
  const CpcaError e = measure(c, x);
  EXPECT_EQ(e.frobenius, 0.0);
  for (float a : c.alpha) EXPECT_TRUE(std::isfinite(a));
  x[5] = std::nanf("");
  EXPECT_THROW(compress(x, D, s), InternalError);
}

TEST(RtfCpca, IsDeterministic) {
  const std::size_t D = 30;
  const auto x = lowRank(3, 40, 4, D, 4);
  CpcaSettings s;
  s.clusters = 3;
  s.components = 2;
  const Cpca a = compress(x, D, s), b = compress(x, D, s);
  EXPECT_EQ(a.basis, b.basis);
  EXPECT_EQ(a.alpha, b.alpha);
  EXPECT_EQ(a.cluster, b.cluster);
}

// The products are split among threads (by rows, by columns of 512, session 13): every entry is
// still summed in one fixed order, so 1, 2 and 3 threads give the same bytes. Sizes cross the
// splits: clusters of 150 > 64 rows, D = 1100 > 2 column blocks with a remainder.
TEST(RtfCpca, SameBytesOnOneTwoAndThreeThreads) {
  const std::size_t D = 1100;
  const auto x = lowRank(2, 150, 6, D, 7);
  CpcaSettings s;
  s.clusters = 2;
  s.components = 4;  // < rank: the subspace iteration has work to do, the reassignment a choice
  const auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    return compress(x, D, s);
  };
  const Cpca one = run(1);
  for (int threads : {2, 3}) {
    const Cpca c = run(threads);
    EXPECT_EQ(one.basis, c.basis) << threads;
    EXPECT_EQ(one.alpha, c.alpha) << threads;
    EXPECT_EQ(one.cluster, c.cluster) << threads;
  }
}

// fp16 storage (cpca.hpp quantize with n₈ = 0, what the field file holds): every reconstructed entry moves
// by no more than half_bound.hpp's bound, derived from the half's 11-bit significand; the rounding
// is idempotent; the stored ratio counts 2 bytes per basis entry and α and 4 per cluster id.
TEST(RtfCpca, Fp16RoundingMovesEveryEntryWithinItsBound) {
  const std::size_t D = 48;
  const int clusters = 4, per = 50, rank = 3;
  const auto x = lowRank(clusters, per, rank, D, 5);  // means up to 100, variations up to ~3
  CpcaSettings s;
  s.clusters = clusters;
  s.components = rank;
  const Cpca f = compress(x, D, s);
  Cpca h = f;
  quantize(h, 0);
  EXPECT_FALSE(isQuantized(f));
  EXPECT_TRUE(isQuantized(h));
  Cpca again = h;
  quantize(again, 0);
  EXPECT_EQ(again.basis, h.basis);
  EXPECT_EQ(again.alpha, h.alpha);
  EXPECT_EQ(h.cluster, f.cluster);
  std::vector<float> xf(D), xh(D);
  double worst = 0.0;  // max |x̂_h − x̂_f| / bound
  for (std::size_t r = 0; r < f.samples(); ++r) {
    f.reconstruct(r, xf);
    h.reconstruct(r, xh);
    for (std::size_t d = 0; d < D; ++d) {
      const double bf = testing::halfBound(f, r, d, false), bh = testing::halfBound(h, r, d, true);
      ASSERT_LE(bf, bh);  // the bound from the rounded values (what a loaded file has) is the looser
      worst = std::max(worst, std::abs(double(xh[d]) - double(xf[d])) / bf);
    }
  }
  EXPECT_LE(worst, 1.0);
  EXPECT_GT(worst, 0.25);  // measured 0.93: the bound is tight, not loose by orders
  // Stored bytes: 4·N·D / (2·(n_c·(n_e+1)·D + N·n_e) + 4·N).
  const double N = clusters * per;
  const double expected = 4.0 * N * D / (2.0 * (clusters * (rank + 1) * double(D) + N * rank) + 4.0 * N);
  EXPECT_DOUBLE_EQ(storedRatio(h), expected);
  EXPECT_DOUBLE_EQ(measure(h, x).stored, expected);
  EXPECT_DOUBLE_EQ(storedRatio(h), storedRatio(f));  // a count of bytes, not of the values
}

// The 8-bit tail (cpca.hpp quantize, n₈ = 2 of 3 components): each tail basis entry and α moves
// from the float compression's by at most half its scale's step (plus the step's own float
// rounding), the scale maps the largest |value| of each row / sample to code ±127, the head stays
// fp16, the rounding is idempotent, isQuantized sees one value off a code, and the stored bytes
// are 2 per half, 1 per code, 4 per scale and cluster id.
TEST(RtfCpca, ByteTailMovesEachValueWithinHalfAStep) {
  const std::size_t D = 48;
  const int clusters = 4, per = 50, rank = 3, n8 = 2;
  const auto x = lowRank(clusters, per, rank, D, 5);
  CpcaSettings s;
  s.clusters = clusters;
  s.components = rank;
  const Cpca f = compress(x, D, s);
  Cpca q = f;
  EXPECT_THROW(quantize(q, rank + 1), InternalError);
  quantize(q, n8);
  ASSERT_TRUE(isQuantized(q));
  ASSERT_EQ(q.basisScale.size(), std::size_t(clusters * n8));
  ASSERT_EQ(q.alphaScale.size(), f.samples());
  const std::size_t head = std::size_t(rank - n8);
  for (int h = 0; h < clusters; ++h)
    for (int t = 0; t < n8; ++t) {
      const float sc = q.basisScale[std::size_t(h * n8 + t)];
      const std::size_t row = (std::size_t(h) * (rank + 1) + head + 1 + std::size_t(t)) * D;
      float top = 0.0f;
      for (std::size_t d = 0; d < D; ++d) {
        ASSERT_LE(std::abs(q.basis[row + d] - f.basis[row + d]), 0.5f * sc * (1.0f + 1e-5f)) << h << " " << t << " " << d;
        top = std::max(top, std::abs(q.basis[row + d]));
      }
      EXPECT_FLOAT_EQ(top, 127.0f * sc);  // the largest entry is code ±127 (a unit row: sc > 0)
    }
  for (std::size_t r = 0; r < f.samples(); ++r) {
    const float sc = q.alphaScale[r];
    for (std::size_t j = head; j < std::size_t(rank); ++j)
      ASSERT_LE(std::abs(q.alpha[r * rank + j] - f.alpha[r * rank + j]), 0.5f * sc * (1.0f + 1e-5f) + 1e-30f) << r << " " << j;
    for (std::size_t j = 0; j < head; ++j) EXPECT_EQ(q.alpha[r * rank + j], glm::unpackHalf1x16(glm::packHalf1x16(f.alpha[r * rank + j])));
  }
  Cpca again = q;
  quantize(again, n8);
  EXPECT_EQ(again.basis, q.basis);
  EXPECT_EQ(again.alpha, q.alpha);
  Cpca off = q;
  off.alpha[std::size_t(rank) - 1] += 0.25f * off.alphaScale[0];  // between two codes
  EXPECT_FALSE(isQuantized(off));
  const double N = clusters * per;
  const double halves = clusters * (rank - n8 + 1) * double(D) + N * (rank - n8);
  const double codes = clusters * n8 * double(D) + N * n8;
  const double expected = 4.0 * N * D / (2.0 * halves + codes + 4.0 * (clusters * n8 + N) + 4.0 * N);
  EXPECT_DOUBLE_EQ(storedRatio(q), expected);
  EXPECT_DOUBLE_EQ(measure(q, x).stored, expected);
}

TEST(RtfCpca, Fp16RoundingRejectsValuesPastTheLargestHalf) {
  const std::size_t D = 8;
  const auto x = lowRank(1, 10, 1, D, 6);
  CpcaSettings s;
  s.clusters = 1;
  s.components = 1;
  Cpca c = compress(x, D, s);
  c.basis[0] = 65519.0f;  // rounds down to 65504, the largest half (the spacing there is 32)
  Cpca ok = c;
  quantize(ok, 0);
  EXPECT_EQ(ok.basis[0], 65504.0f);
  c.alpha[3] = -65520.0f;  // rounds to −inf
  EXPECT_THROW(quantize(c, 0), InternalError);
}

}  // namespace
}  // namespace bounce::gi::rtf
