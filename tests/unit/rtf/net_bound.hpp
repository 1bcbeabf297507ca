#pragma once
// What the ξ pass's 8-bit X image (xi.comp, XiPass::net) holds, on the CPU, and the error bound its
// 8 bits put on the shading pass (rtf.frag) — shared by the GPU tests of both passes.
#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gi/rtf/evaluate.hpp"
#include "engine/gi/rtf/xi_pass.hpp"
#include "engine/math/sh.hpp"
#include "engine/math/sh_convolve.hpp"
#include "engine/math/sampling.hpp"
#include "engine/math/sh_eval.hpp"

namespace bounce::gi::rtf::testing {

// X_i = Â_l(i)/π ξ_i − Σ_j T'_ij (u − V)_j per sample and i < 9, [sample·9 + i] (xi.comp's fold;
// T'_ij = blocked[j·9 + i].rgb as RtfObjectGpu::blocked, u_0 = 2√π).
// `scale` (XiPass::setBlockedScale; empty: 1): per sample, rgb the blocked term's factor, w the
// interreflected term's (overlap.hpp; off the rtf objects). `onObjects` non-empty: the on-object variant,
// with that per-sample factor of the interreflected term in place of scale's w.
inline std::vector<glm::vec3> netValues(const Field& f, std::span<const glm::vec3> xi, std::span<const glm::vec4> blocked,
                                        std::span<const glm::vec4> scale = {}, std::span<const float> onObjects = {}) {
  const std::size_t N = sampleCount(f.settings);
  std::vector<glm::vec3> X(N * 9);
  for (std::size_t r = 0; r < N; ++r)
    for (int i = 0; i < 9; ++i) {
      const float a = float(sh::cosineLobeBand(i == 0 ? 0 : i < 4 ? 1 : 2) / math::kPi);
      const glm::vec4 sc = scale.empty() ? glm::vec4(1.0f) : scale[r];
      glm::vec3 x = a * xi[r * kShCount + std::size_t(i)] * (onObjects.empty() ? sc.w : onObjects[r]);
      glm::vec3 b(0.0f);
      for (int j = 0; j < kShCount; ++j) {
        const float notV = (j == 0 ? 3.5449077018110318f : 0.0f) - f.oof[r * kShCount + std::size_t(j)];
        b += notV * glm::vec3(blocked[std::size_t(j * 9 + i)]);
      }
      X[r * 9 + std::size_t(i)] = x - glm::vec3(sc) * b;
    }
  return X;
}

// Each slot's scale m = max |Y| over the samples of Y = r_s² X (XiPass::netRange, netScale), [slot]; with
// the on-object variant's X too (`on`, netValues with onObjects), over both: they share each slot's m.
inline std::array<float, 28> netRanges(std::span<const glm::vec3> X, const FieldSettings& s, std::span<const glm::vec3> on = {}) {
  std::array<float, 28> m{};
  const std::size_t per = std::size_t(samplesPerSphere(s));
  for (const std::span<const glm::vec3> values : {X, on})
    for (std::size_t k = 0; k < values.size(); ++k)
      for (int c = 0; c < 3; ++c) {
        float& slot = m[std::size_t(XiPass::netSlot(c, int(k % 9)))];
        slot = std::max(slot, std::abs(values[k][c]) * XiPass::netScale(s, int(k / 9 / per)));
      }
  return m;
}

// What rtf.frag multiplies the decoded Y by at |q| = r (η) to get X: the end's fade (tailFade) over
// r² clamped to [r_0, r_N] (xi_pass.hpp netScale's lookup).
inline float netDecode(const FieldSettings& s, float r, float reach = 0.0f) {
  const float rc = std::clamp(r, sphereRadius(s, 0), sphereRadius(s, s.spheres - 1));
  return tailFade(s, r, reach) / (rc * rc);
}

// The 8-bit image's share of a shaded pixel's error, channel c, receiver normal n (world), albedo
// ρ_c: ρ_c · decode · Σ_i |y_i(n_local)| · m_slot(c,i) · kNetSteps/255, decode = netDecode() at the
// pixel's |q|. Per slot the stored t = Y/(2m) + ½ is Y to ½ step of 1/255 (Y: m/255); the sampler then
// filters 8-bit texels on llvmpipe's fixed-point path: 8-bit weights and an 8-bit result for each of
// the 3 lerps of a trilinear fetch, ≤ 1 step of t from the weight and ≤ 1 from the result each, so
// |t̃ − t| ≤ (½ + 3·2)/255 and Y to 13 m/255. The bound Vulkan itself gives (≥ 4 bits of sub-texel
// weight precision) is looser; this is the implementation the tests run on.
inline constexpr float kNetSteps = 13.0f;
// shCount: the coefficients the shading reads (the record's ids.y: 9 or 4).
inline float netBound(const std::array<float, 28>& m, const glm::vec4 toLocal[3], glm::vec3 n, float decode, float rho, int c,
                      int shCount = 9) {
  const glm::vec3 nl(glm::dot(glm::vec3(toLocal[0]), n), glm::dot(glm::vec3(toLocal[1]), n), glm::dot(glm::vec3(toLocal[2]), n));
  const auto y = sh::evalBasis<float>(3, nl);
  float s = 0.0f;
  for (int i = 0; i < shCount; ++i) s += std::abs(y[std::size_t(i)]) * m[std::size_t(XiPass::netSlot(c, i))];
  return rho * decode * s * kNetSteps / 255.0f;
}

}  // namespace bounce::gi::rtf::testing
