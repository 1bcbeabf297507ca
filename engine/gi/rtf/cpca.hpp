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
  // Storage (quantize below): components 1..ne − byteComponents (and the mean) as fp16, the last
  // byteComponents (the low-energy tail) as 8-bit codes with a scale. 0 for a Cpca from compress().
  int byteComponents = 0;
  // basis[(h·(ne+1) + j)·D + d]: j = 0 the mean E_h0, j ≥ 1 the orthonormal E_hj (zero vectors
  // where the cluster's data has lower rank).
  std::vector<float> basis;
  std::vector<std::uint32_t> cluster;  // per sample
  std::vector<float> alpha;            // per sample: ne coefficients α_1..α_ne
  // After quantize with byteComponents = n₈ > 0 (empty otherwise): the 8-bit rows' and α's scales.
  // basisScale[h·n₈ + t] is row E_h(ne−n₈+1+t)'s (entry = scale·code), alphaScale[r] sample r's
  // tail α (α_j(r) = scale·code for j > ne − n₈); codes in −127..127. basis and alpha hold the
  // decoded values (float(scale·code)), so reconstruct() and measure() see what the file holds.
  std::vector<float> basisScale, alphaScale;
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

// Storage (issue 14; README "CPCA error–ratio curve", "CPCA: the tail in 8 bits, session 15"): the
// field file and the ξ pass hold the means, the first ne − n₈ basis vectors E_hj and their α as
// IEEE halves (glm::packHalf1x16, round to nearest: v moves by at most 2⁻¹¹·|v|, or 2⁻²⁵ for
// subnormal halves), the cluster ids as 32-bit words, and the last n₈ = byteComponents components
// as signed 8-bit codes: a basis row with one fp32 scale per row (scale = max|E_hj,d| / 127), a
// sample's tail α with one fp32 scale per sample (scale = max_{j>ne−n₈} |α_j(r)| / 127), so each
// value moves by at most scale/2. Why per sample and not per component: the samples along a ray
// differ by (η/d)² (a factor ≈ 100, cpca.cpp "lines"), so a per-component scale is set by the
// samples next to the surface and drowns the far ones (animated box, 8 × 128 at 6·64² rays, every α
// in 8 bits, basis fp16: 2.2 % per component against 1.6 % per sample; fp16 0.57 %). Why only the
// tail: the head components carry most of the energy, and 8 bits there cost more error than the
// components they buy (same prop, 8 × 112 predicted: all in 8 bits 3.2 % at 70.6:1, the first 16 in
// fp16 0.92 % at 62.0:1, the first 24 0.81 % at 58.5:1; tools/rtf_parts/rtf_cpca_tail.py, README
// "CPCA: the tail in 8 bits, session 15").
// quantize(c, n₈) rounds in place, so the Cpca in memory is exactly what the file holds and
// measure() after it gives the stored field's error. Throws InternalError when n₈ is not in
// 0..components or some |value| would round past the largest half (65504).
void quantize(Cpca& cpca, int byteComponents);
// True when every value is what quantize() leaves: halves, and codes × scales (what serialize() requires).
bool isQuantized(const Cpca& cpca);
// 4·N·D bytes (fp32 X) / bytes of the field file's CPCA: 2 per half, 1 per code, 4 per scale and id.
double storedRatio(const Cpca& cpca);
// A quantized Cpca split as the field file and the ξ pass store it: per cluster the half rows (the
// mean, E_1..E_{ne−n₈}) then per cluster the code rows; per sample the half α then the coded α.
struct CpcaParts {
  std::vector<float> basisHalves, alphaHalves;
  std::vector<std::int8_t> basisCodes, alphaCodes;
};
// Throws InternalError when the Cpca is not quantized (isQuantized).
CpcaParts storedParts(const Cpca& cpca);
// Bytes of the field file's CPCA for a shape (what storedRatio divides by).
double storedBytes(std::size_t samples, std::size_t dimension, int clusters, int components, int byteComponents);

}  // namespace bounce::gi::rtf
