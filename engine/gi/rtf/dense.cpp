#include "engine/gi/rtf/dense.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

namespace bounce::gi::rtf::dense {

namespace {
typedef float V8 __attribute__((vector_size(32)));
constexpr std::size_t kChunk = 1024;  // floats of a row per pass: 2 + 4 rows × 4 KiB stay in L1
}  // namespace

#define BOUNCE_LOAD8(dst, ptr) std::memcpy(&(dst), (ptr), sizeof(V8))

[[gnu::target_clones("arch=x86-64-v3", "default")]]
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

[[gnu::target_clones("arch=x86-64-v3", "default")]]
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

[[gnu::target_clones("arch=x86-64-v3", "default")]]
void addOuter(const float* p, const float* const* y, std::size_t n, std::size_t k, std::size_t D, float* w, std::size_t ldw) {
  if (ldw == 0) ldw = D;
  // Register tiles of 4 rows of w × 16 columns (8 accumulators) summed over a block of kRows y
  // rows: per 8 FMAs 2 loads of y and 4 broadcasts of p, and w is read and written once per block
  // instead of once per y row (the rank-1 form was L2-bound: 0.3 of dots()'s rate, session 13).
  // Each w[j·D + d] adds its terms in i order whatever the blocking of d, so splitting the
  // columns among threads gives the same bytes.
  constexpr std::size_t kCols = 256, kRows = 128;  // a packed y block of 128 × 1 KiB stays in L2
  thread_local std::vector<float> block(kRows * kCols);  // once per thread (the ITF bake calls this per sample)
  const auto add = [](float* wj, const V8& a) {
    for (int l = 0; l < 8; ++l) wj[l] += a[l];
  };
  for (std::size_t d0 = 0; d0 < D; d0 += kCols) {
    const std::size_t len = std::min(kCols, D - d0), len16 = len & ~std::size_t(15);
    for (std::size_t i0 = 0; i0 < n; i0 += kRows) {
      const std::size_t rowsHere = std::min(n, i0 + kRows) - i0;
      // Packed in panels of 16 columns, rows consecutive (block[(d/16)·kRows·16 + i·16 + d%16]): the
      // inner loop below reads one 64-byte line after the other (a 1 KiB row stride thrashed L1's sets).
      for (std::size_t i = 0; i < rowsHere; ++i)
        for (std::size_t d = 0; d < len16; d += 16)
          std::memcpy(block.data() + d * kRows + i * 16, y[i0 + i] + d0 + d, 16 * sizeof(float));
      for (std::size_t j = 0; j < k; j += 4) {
        const std::size_t jn = std::min<std::size_t>(4, k - j);
        const std::size_t j1 = j + std::min<std::size_t>(1, jn - 1), j2 = j + std::min<std::size_t>(2, jn - 1),
                          j3 = j + std::min<std::size_t>(3, jn - 1);
        for (std::size_t d = 0; d < len16; d += 16) {
          V8 a00 = {}, a01 = {}, a10 = {}, a11 = {}, a20 = {}, a21 = {}, a30 = {}, a31 = {};
          const float* yb = block.data() + d * kRows;
          const float* pi = p + i0 * k;
          for (std::size_t i = 0; i < rowsHere; ++i, yb += 16, pi += k) {
            V8 y0, y1;
            BOUNCE_LOAD8(y0, yb);
            BOUNCE_LOAD8(y1, yb + 8);
            const float p0 = pi[j], p1 = pi[j1], p2 = pi[j2], p3 = pi[j3];
            a00 += p0 * y0, a01 += p0 * y1, a10 += p1 * y0, a11 += p1 * y1;
            a20 += p2 * y0, a21 += p2 * y1, a30 += p3 * y0, a31 += p3 * y1;
          }
          float* w0 = w + j * ldw + d0 + d;
          add(w0, a00), add(w0 + 8, a01);
          if (jn > 1) add(w0 + ldw, a10), add(w0 + ldw + 8, a11);
          if (jn > 2) add(w0 + 2 * ldw, a20), add(w0 + 2 * ldw + 8, a21);
          if (jn > 3) add(w0 + 3 * ldw, a30), add(w0 + 3 * ldw + 8, a31);
        }
        for (std::size_t t = 0; t < jn; ++t) {  // the last len % 16 columns
          float* wj = w + (j + t) * ldw + d0;
          for (std::size_t d = len16; d < len; ++d) {
            float a = 0.0f;
            for (std::size_t i = 0; i < rowsHere; ++i) a += p[(i0 + i) * k + j + t] * y[i0 + i][d0 + d];
            wj[d] += a;
          }
        }
      }
    }
  }
}

#undef BOUNCE_LOAD8

}  // namespace bounce::gi::rtf::dense
