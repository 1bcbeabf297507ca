// CPCA (paper §4.1, Eq. 9): exact on data that is exactly what Eq. 9 can represent, and the
// reported ratio is the count of floats it claims.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.hpp"
#include "engine/gi/rtf/cpca.hpp"
#include "engine/math/sampling.hpp"

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

}  // namespace
}  // namespace bounce::gi::rtf
