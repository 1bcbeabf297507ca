#include "engine/anim/subdivision.hpp"

#include <algorithm>
#include <cmath>

#include "engine/core/parallel.hpp"

namespace bounce::anim {

bool LimitStencilJob::validate() const {
  if (!stencils || !stencils->present() || stencils->offsets.empty()) return false;
  const asset::LimitStencils& st = *stencils;
  const std::size_t rows = st.offsets.size() - 1;
  if (outPositions.size() != rows || outNormals.size() != rows || cageNormals.size() != cagePositions.size()) return false;
  for (std::uint32_t i : st.indices)
    if (i >= cagePositions.size()) return false;
  return true;
}

void evaluateLimitStencils(const asset::LimitStencils& st, std::span<const glm::vec3> P, std::span<const glm::vec3> N,
                           std::span<glm::vec3> outP, std::span<glm::vec3> outN, std::size_t begin, std::size_t end) {
  const std::uint32_t* idx = st.indices.data();
  const float* w = st.weights.data();
  const float* wu = st.duWeights.data();
  const float* wv = st.dvWeights.data();
  for (std::size_t v = begin; v < end; ++v) {
    glm::vec3 s(0.0f), du(0.0f), dv(0.0f), n(0.0f);
    for (std::uint32_t k = st.offsets[v]; k < st.offsets[v + 1]; ++k) {
      const glm::vec3 p = P[idx[k]];
      s += w[k] * p;
      du += wu[k] * p;
      dv += wv[k] * p;
      n += w[k] * N[idx[k]];
    }
    const glm::vec3 c = glm::cross(du, dv);
    const float len = glm::length(c);
    if (len > kParallelTangents * glm::length(du) * glm::length(dv) && std::isfinite(len)) {
      n = c / len;
    } else {
      const float nl = glm::length(n);
      n = nl > 0.0f ? n / nl : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    outP[v] = s;
    outN[v] = n;
  }
}

bool LimitStencilJob::run() const {
  if (!validate()) return false;
  const std::size_t rows = outPositions.size();
  // Rows in blocks of 256: small enough to balance two cores, large enough that the pool's
  // per-task cost stays below the ~10k multiply-adds of a block.
  constexpr std::size_t kBlock = 256;
  const std::size_t blocks = (rows + kBlock - 1) / kBlock;
  auto block = [&](std::size_t b) {
    evaluateLimitStencils(*stencils, cagePositions, cageNormals, outPositions, outNormals, b * kBlock,
                          std::min(rows, (b + 1) * kBlock));
  };
  if (parallel && blocks > 1) parallelFor(0, blocks, block);
  else
    for (std::size_t b = 0; b < blocks; ++b) block(b);
  return true;
}

}  // namespace bounce::anim
