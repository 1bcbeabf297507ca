#pragma once
// Clustered principal component analysis (paper §4.1, Eq. 9; Sloan, Hall, Hart, Snyder 2003,
// "Clustered principal components for precomputed radiance transfer", §3).
//
// N sample vectors x_r of dimension D are split into clusters C_1..C_nc; a sample r in C_h is
// reconstructed as
//   x̂_r = E_h0 + Σ_{j=1..ne} α_j(r) E_hj                                          (Eq. 9)
// with E_h0 the cluster mean and E_h1..E_hne an orthonormal basis of the cluster's ne-dimensional
// principal subspace. The paper's Eq. 9 writes no mean term; SHHS03 (which the paper cites for
// CPCA) keeps it, and it costs one component: we keep it (α_0 ≡ 1).
//
// Algorithm (SHHS03 §3, "iterative CPCA"): k-means++ seeds and Lloyd k-means on LINES through 0
// (the distance of two samples is the sine of their angle, so x and 10x fall together), then
// `iterations` rounds of {per cluster: mean + principal subspace; every sample moves to the
// cluster, among its own and those of its 4 nearest means, that reconstructs it best}. Why lines:
// an ITF's samples along a ray from the object differ mostly by the (η/d)² of the solid angle the
// object covers, a factor 100 over the paper's spheres; k-means on the raw vectors cut them by
// magnitude, and its farthest-point seeds spent most clusters on a few samples next to the surface
// (a Cornell box prop, 16 spheres × 6·8² samples: 24 of 32 clusters held 3 samples each).
// The principal subspace comes from block power (subspace) iteration on the centred cluster,
// X_cᵀ(X_c V), in float products (dense.hpp) re-orthonormalised by modified Gram–Schmidt in
// double: only the span matters for Eq. 9 (α = Eᵀ(x − E_0) is the orthogonal projection), so no
// eigen-decomposition is needed. Rounds after the first start each cluster from its previous
// basis (powerIterations/4, at least 3, products). A cluster whose centred data has rank ≤ ne is
// reproduced exactly (to float rounding): its span is found by the first product.
// Deterministic: seeds and start vectors come from Pcg32 with a fixed seed.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace bounce::gi::rtf {

struct CpcaSettings {
  int clusters = 32;    // n_c (paper: 32)
  int components = 16;  // n_e (paper: 16)
  int iterations = 4;   // reassignment rounds after k-means
  int powerIterations = 12;  // products of the first fit
};

struct Cpca {
  int dimension = 0, clusters = 0, components = 0;
  // basis[(h·(ne+1) + j)·D + d]: j = 0 the mean E_h0, j ≥ 1 the orthonormal E_hj (zero vectors
  // where the cluster's data has lower rank).
  std::vector<float> basis;
  std::vector<std::uint32_t> cluster;  // per sample
  std::vector<float> alpha;            // per sample: ne coefficients α_1..α_ne
  std::size_t samples() const { return cluster.size(); }
  // x̂_r into out (size D).
  void reconstruct(std::size_t sample, std::span<float> out) const;
};

// data: N·D floats, sample-major. Throws InternalError on inconsistent sizes or non-finite data.
Cpca compress(std::span<const float> data, std::size_t dimension, const CpcaSettings& settings);

struct CpcaError {
  double frobenius = 0.0;  // ‖X − X̂‖_F / ‖X‖_F (the paper's error, relative), 0 for X = 0
  double ratio = 0.0;      // N·D floats before / floats after (basis + per-sample α and cluster id)
  double stored = 0.0;     // storedRatio: fp32 bytes before / bytes of the field file's CPCA
};
CpcaError measure(const Cpca& cpca, std::span<const float> data);
// The ratio of CpcaError alone (it needs no data).
double compressionRatio(const Cpca& cpca);

// fp16 storage (issue 14, README "CPCA error–ratio curve"): the field file and the ξ pass hold the
// basis E_hj and the coefficients α as IEEE halves, the cluster ids as 32-bit words.
// roundToHalf rounds every basis entry and α to the nearest half in place (glm::packHalf1x16:
// round to nearest), so the Cpca in memory is exactly what the file holds and measure() after it
// gives the error of the stored field. Per value the rounding moves v by at most 2⁻¹¹·|v| (11-bit
// significand, |v| ≥ 2⁻¹⁴) or 2⁻²⁵ (subnormal halves). The basis vectors are unit (|E_hj,d| ≤ 1)
// and the ITF is a transfer of light to light (O(1)), far inside the range.
// Throws InternalError when some |value| would round past the largest half (65504).
void roundToHalf(Cpca& cpca);
// True when every basis entry and α is a half exactly (what serialize() requires).
bool isHalf(const Cpca& cpca);
// 4·N·D bytes (fp32 X) / (2·(basis + α) + 4·N) bytes: the field file's CPCA (halves, 32-bit ids).
double storedRatio(const Cpca& cpca);

}  // namespace bounce::gi::rtf
