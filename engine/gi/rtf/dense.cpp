#include "engine/gi/rtf/dense.hpp"

#include <algorithm>
#include <cstring>

namespace bounce::gi::rtf::dense {

namespace {
typedef float V8 __attribute__((vector_size(32)));
constexpr std::size_t kChunk = 1024;  // floats of a row per pass: 2 + 4 rows × 4 KiB stay in L1
}  // namespace

#define BOUNCE_LOAD8(dst, ptr) std::memcpy(&(dst), (ptr), sizeof(V8))

[[gnu::target_clones("arch=haswell", "default")]]
void dots(const float* const* a, std::size_t na, const float* b, std::size_t nb, std::size_t D, float* c) {
  std::fill(c, c + na * nb, 0.0f);
  for (std::size_t d0 = 0; d0 < D; d0 += kChunk) {
    const std::size_t len = std::min(kChunk, D - d0), len8 = len & ~std::size_t(7);
    for (std::size_t i = 0; i < na; i += 2) {
      const float* a0 = a[i] + d0;
      const float* a1 = a[std::min(i + 1, na - 1)] + d0;
      for (std::size_t j = 0; j < nb; j += 4) {
        const float* bj[4];
        for (std::size_t t = 0; t < 4; ++t) bj[t] = b + std::min(j + t, nb - 1) * D + d0;
        V8 s00 = {}, s01 = {}, s02 = {}, s03 = {}, s10 = {}, s11 = {}, s12 = {}, s13 = {};
        for (std::size_t d = 0; d < len8; d += 8) {
          V8 x0, x1, y0, y1, y2, y3;
          BOUNCE_LOAD8(x0, a0 + d);
          BOUNCE_LOAD8(x1, a1 + d);
          BOUNCE_LOAD8(y0, bj[0] + d);
          BOUNCE_LOAD8(y1, bj[1] + d);
          BOUNCE_LOAD8(y2, bj[2] + d);
          BOUNCE_LOAD8(y3, bj[3] + d);
          s00 += x0 * y0, s01 += x0 * y1, s02 += x0 * y2, s03 += x0 * y3;
          s10 += x1 * y0, s11 += x1 * y1, s12 += x1 * y2, s13 += x1 * y3;
        }
        float r[2][4] = {};
        for (int l = 0; l < 8; ++l) {
          r[0][0] += s00[l], r[0][1] += s01[l], r[0][2] += s02[l], r[0][3] += s03[l];
          r[1][0] += s10[l], r[1][1] += s11[l], r[1][2] += s12[l], r[1][3] += s13[l];
        }
        for (std::size_t d = len8; d < len; ++d)
          for (std::size_t t = 0; t < 4; ++t) r[0][t] += a0[d] * bj[t][d], r[1][t] += a1[d] * bj[t][d];
        for (std::size_t u = 0; u < 2 && i + u < na; ++u)
          for (std::size_t t = 0; t < 4 && j + t < nb; ++t) c[(i + u) * nb + j + t] += r[u][t];
      }
    }
  }
}

[[gnu::target_clones("arch=haswell", "default")]]
float dot(const float* a, const float* b, std::size_t D) {
  V8 s0 = {}, s1 = {};
  std::size_t d = 0;
  for (; d + 16 <= D; d += 16) {
    V8 x0, x1, y0, y1;
    BOUNCE_LOAD8(x0, a + d);
    BOUNCE_LOAD8(x1, a + d + 8);
    BOUNCE_LOAD8(y0, b + d);
    BOUNCE_LOAD8(y1, b + d + 8);
    s0 += x0 * y0, s1 += x1 * y1;
  }
  float r = 0.0f;
  for (int l = 0; l < 8; ++l) r += s0[l] + s1[l];
  for (; d < D; ++d) r += a[d] * b[d];
  return r;
}

[[gnu::target_clones("arch=haswell", "default")]]
void addOuter(const float* p, const float* const* y, std::size_t n, std::size_t k, std::size_t D, float* w) {
  constexpr std::size_t kCols = 512;  // w's k rows × 2 KiB stay in L1/L2 while every y row passes
  for (std::size_t d0 = 0; d0 < D; d0 += kCols) {
    const std::size_t len = std::min(kCols, D - d0);
    for (std::size_t i = 0; i < n; ++i) {
      const float* __restrict yi = y[i] + d0;
      for (std::size_t j = 0; j < k; ++j) {
        const float pij = p[i * k + j];
        if (pij == 0.0f) continue;
        float* __restrict wj = w + j * D + d0;
        for (std::size_t d = 0; d < len; ++d) wj[d] += pij * yi[d];
      }
    }
  }
}

#undef BOUNCE_LOAD8

}  // namespace bounce::gi::rtf::dense
