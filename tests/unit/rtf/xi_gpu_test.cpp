// The ξ pass (shaders/rtf/xi.comp, Eq. 11–12) on the GPU = xiCache() on the CPU (the reference),
// for a baked field and random proxy light. Both sum in float32 in different orders: the
// tolerance is 1e-5 of the sum of |terms| (≈ 2⁻¹⁷ · the ~100-term sums), plus 1e-7 absolute.
#include <gtest/gtest.h>

#include <cstring>

#include "engine/gi/rtf/evaluate.hpp"
#include "engine/gi/rtf/xi_pass.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/math/sampling.hpp"
#include "tests/unit/rtf/small_field.hpp"

namespace bounce::gi::rtf {
namespace {

TEST(RtfXiGpu, ComputePassEqualsTheCpuCaches) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const BakeResult b = bake(testing::unitSphere(glm::vec3(0.8f, 0.6f, 0.4f), 8), testing::smallSettings());
  const Field& f = b.field;
  const FieldSettings& s = f.settings;
  math::Pcg32 rng(5);
  std::vector<glm::vec3> L(std::size_t(s.proxies) * kShCount);
  for (auto& l : L) l = rng.nextFloat3() * 2.0f - 1.0f;
  const std::vector<glm::vec3> want = xiCache(f, L);
  // The scale of each ξ: the same sums with |terms|.
  Field absField = f;
  for (float& x : absField.itf.basis) x = std::abs(x);
  for (float& x : absField.itf.alpha) x = std::abs(x);
  std::vector<glm::vec3> absL(L.size());
  for (std::size_t i = 0; i < L.size(); ++i) absL[i] = glm::abs(L[i]);
  const std::vector<glm::vec3> scale = xiCache(absField, absL);

  XiPass pass(ctx, f);
  pass.setProxyLight(L);
  gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) { pass.record(cmd); });
  const auto bytes = gpu::readback(ctx, pass.xi());
  const std::size_t w = std::size_t(6 * s.faceSize), h = std::size_t(s.faceSize);
  ASSERT_EQ(bytes.size(), std::size_t(s.spheres) * kShCount * w * h * 16);
  std::vector<glm::vec4> texels(bytes.size() / 16);
  std::memcpy(texels.data(), bytes.data(), bytes.size());
  const int n2 = s.faceSize * s.faceSize, per = samplesPerSphere(s);
  for (std::size_t r = 0; r < sampleCount(s); ++r) {
    const int sphere = int(r) / per, rest = int(r) % per, face = rest / n2, y = rest % n2 / s.faceSize, x = rest % s.faceSize;
    for (int i = 0; i < kShCount; ++i) {
      const std::size_t layer = std::size_t(sphere * kShCount + i);
      const glm::vec4 got = texels[(layer * h + std::size_t(y)) * w + std::size_t(face * s.faceSize + x)];
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(got[c], want[r * kShCount + std::size_t(i)][c], 1e-5f * scale[r * kShCount + std::size_t(i)][c] + 1e-7f)
            << "sample " << r << " coefficient " << i;
    }
  }
}

}  // namespace
}  // namespace bounce::gi::rtf
