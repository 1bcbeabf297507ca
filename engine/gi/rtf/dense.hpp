#pragma once
// The two dense float kernels the RTF bake spends its time in (CPCA, Eq. 9, and the ITF
// projection, Eq. 6–7): blocks of dot products and rank-k row updates. One thread each (callers
// split the work with parallelFor); compiled twice (AVX2+FMA and baseline x86-64) and picked at
// load time, because the project builds for baseline x86-64 and these loops are 8 floats wide.
// Accumulation is in float, 8 lanes × independent chains (the error of a D-long dot grows like
// √(D/8)·ε·|a||b|, ≈ 2e-6 relative at D = 6144): callers that need more centre their data first.
#include <cstddef>

namespace bounce::gi::rtf::dense {

// c[i·nb + j] = Σ_d a[i][d] · b[j·D + d]   (i < na, j < nb; a: row pointers, b: nb contiguous rows)
void dots(const float* const* a, std::size_t na, const float* b, std::size_t nb, std::size_t D, float* c);
// Σ_d a[d] · b[d]
float dot(const float* a, const float* b, std::size_t D);
// w[j·ldw + d] += Σ_i p[i·k + j] · y[i][d]   (i < n, j < k, d < D; ldw = 0 means D): Wᵀ += Yᵀ P,
// the second product of the subspace iteration and the rank-k update of the ITF accumulation.
// Each w entry sums its terms in blocks of 128 i in order, whatever D: a caller may split the
// columns among threads (in multiples of 256) and get the same bytes.
void addOuter(const float* p, const float* const* y, std::size_t n, std::size_t k, std::size_t D, float* w,
              std::size_t ldw = 0);

}  // namespace bounce::gi::rtf::dense
