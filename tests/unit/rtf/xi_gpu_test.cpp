// The ξ pass (shaders/rtf/xi.comp, Eq. 11–12) on the GPU = xiCache() on the CPU (the reference),
// for a baked field and random proxy light. Both sum in float32 in different orders: the
// tolerance is 1e-5 of the sum of |terms| (≈ 2⁻¹⁷ · the ~100-term sums), plus 1e-7 absolute.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/gi/rtf/evaluate.hpp"
#include "engine/gi/rtf/xi_pass.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/math/sampling.hpp"
#include "tests/unit/rtf/net_bound.hpp"
#include "tests/unit/rtf/small_field.hpp"

namespace bounce::gi::rtf {
namespace {

// The pass reads the half basis and α as packHalf2x16 words (xi_pass.cpp halfWords): n_e = 3 makes
// every other sample's α row start in a word's high half (n_e = 4: rows start word-aligned). The
// 8-bit tail (cpca.hpp quantize, n₈ components) as four codes a word (xi_pass.cpp byteWords): n₈ = 3
// and 2 start the sample's code rows at every byte of a word; n₈ = n_e leaves no half α at all.
TEST(RtfXiGpu, ComputePassEqualsTheCpuCaches) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  for (const auto& [components, byteComponents] : {std::pair{4, 0}, std::pair{3, 0}, std::pair{3, 3}, std::pair{5, 2}}) {
    SCOPED_TRACE("components " + std::to_string(components) + " byteComponents " + std::to_string(byteComponents));
    FieldSettings fs = testing::smallSettings();
    fs.components = components;
    fs.byteComponents = byteComponents;
    const BakeResult b = bake(testing::unitSphere(glm::vec3(0.8f, 0.6f, 0.4f), 8), fs);
    const Field& f = b.field;
    const FieldSettings& s = f.settings;
    ASSERT_EQ(f.itf.byteComponents, byteComponents);
    ASSERT_EQ(f.itf.alphaScale.size(), byteComponents > 0 ? sampleCount(s) : 0u);
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

    XiPass pass(ctx, f, {.keepXi = true});
    // ξ and X leave UNDEFINED when the pass is built (a one-time submit), not inside a frame, whose
    // layout changes by passes the render graph's journal does not roll back (review 15, item 2);
    // record() then changes no layout, which validation checks against the GPU's layout.
    EXPECT_EQ(pass.xi().layout(), VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(pass.net().layout(), VK_IMAGE_LAYOUT_GENERAL);
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
}

// The ξ pass's inputs, random: the proxies' light in [−1, 1], a blocked matrix in [−0.1, 0.1] (so every slot of
// X is signed and non-zero) and, withScale, a per-sample scale (rgb, w_off) and on-object factor in [0, 1).
struct XiInputs {
  std::vector<glm::vec3> L;
  std::vector<glm::vec4> blocked, scale;
  std::vector<float> onObjects;
};
XiInputs randomInputs(math::Pcg32& rng, const FieldSettings& s, bool withScale) {
  XiInputs in;
  in.L.resize(std::size_t(s.proxies) * kShCount);
  for (auto& l : in.L) l = rng.nextFloat3() * 2.0f - 1.0f;
  in.blocked.resize(kShCount * 9);
  for (auto& t : in.blocked) t = glm::vec4(rng.nextFloat3() * 0.2f - 0.1f, 0.0f);
  if (!withScale) return in;
  for (std::size_t r = 0; r < sampleCount(s); ++r) in.scale.push_back(glm::vec4(rng.nextFloat3(), rng.nextFloat()));
  for (std::size_t r = 0; r < sampleCount(s); ++r) in.onObjects.push_back(rng.nextFloat());
  return in;
}

// The shading step's X in 8 bits (xi.comp stages 1–2), held as Y = r_s² X (XiPass::netScale): each
// slot's range = max |Y| over the samples of the CPU's X (netValues: ξ folded with the blocked light)
// times its sphere's r_s², and each texel decodes, Y = m(2t − 1), to the CPU's r_s² X within half a
// step (m/255) plus X's float error (1e-4 m: X's sums of ≤ 25 terms in float, against a step of
// 2m/255 ≈ 8e-3 m). Random light and blocked matrix, so every slot is signed and non-zero; the unused
// 28th slot decodes to 0. Twice: without a per-sample scale, and with a random one (setBlockedScale: rgb
// the blocked term's factor, w the interreflected term's off the objects, and a random on-object factor,
// overlap.hpp), which X must carry. Both variants of X (texels 0–6 off the objects, 7–13 on them), one
// range per slot over both; without a scale the two are the same.
TEST(RtfXiGpu, NetImageHoldsXToHalfAStepOfItsSlotsRange) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const BakeResult b = bake(testing::unitSphere(glm::vec3(0.8f, 0.6f, 0.4f), 8), testing::smallSettings());
  const Field& f = b.field;
  const FieldSettings& s = f.settings;
  for (const bool withScale : {false, true}) {
    SCOPED_TRACE(withScale ? "with a per-sample scale" : "without a scale");
    math::Pcg32 rng(9);
    const auto [L, blocked, scale, onObjects] = randomInputs(rng, s, withScale);
    const std::vector<glm::vec3> xi = xiCache(f, L);
    const std::vector<glm::vec3> X = testing::netValues(f, xi, blocked, scale);
    const std::vector<glm::vec3> Xon = testing::netValues(f, xi, blocked, scale, onObjects);
    const std::array<float, 28> want = testing::netRanges(X, s, Xon);

    XiPass pass(ctx, f);
    pass.setProxyLight(L);
    pass.setBlockedLight(blocked);
    pass.setBlockedScale(scale, onObjects);
    gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) { pass.record(cmd); });
    const auto rangeBytes = gpu::readback(ctx, pass.netRange());
    ASSERT_EQ(rangeBytes.size(), 28 * sizeof(float));
    std::array<float, 28> m{};
    std::memcpy(m.data(), rangeBytes.data(), sizeof(m));
    for (int slot = 0; slot < 27; ++slot) {
      ASSERT_GT(want[std::size_t(slot)], 0.0f);
      EXPECT_NEAR(m[std::size_t(slot)], want[std::size_t(slot)], 1e-4f * want[std::size_t(slot)]) << "slot " << slot;
    }
    EXPECT_EQ(m[27], 0.0f);

    const auto bytes = gpu::readback(ctx, pass.net());
    const std::size_t w = std::size_t(6 * s.faceSize), h = std::size_t(s.faceSize);
    ASSERT_EQ(bytes.size(), std::size_t(s.spheres) * XiPass::kNetTexels * XiPass::kNetVariants * w * h * 4);
    const int n2 = s.faceSize * s.faceSize, per = samplesPerSphere(s);
    float worst = 0.0f;
    double differ = 0.0;  // how far the two variants lie apart (they must, with a scale)
    for (int variant = 0; variant < 2; ++variant)
    for (std::size_t r = 0; r < sampleCount(s); ++r) {
      const std::vector<glm::vec3>& XV = variant == 0 ? X : Xon;
      const int sphere = int(r) / per, rest = int(r) % per, face = rest / n2, y = rest % n2 / s.faceSize, x = rest % s.faceSize;
      for (int i = 0; i < 9; ++i)
        for (int c = 0; c < 3; ++c) {
          const int slot = XiPass::netSlot(c, i), k = variant * int(XiPass::kNetTexels) + slot / 4;
          const std::size_t slice = std::size_t(k * s.spheres + sphere);
          const std::uint8_t t = bytes[((slice * h + std::size_t(y)) * w + std::size_t(face * s.faceSize + x)) * 4 + std::size_t(slot % 4)];
          const float mm = m[std::size_t(slot)];
          const float got = mm * (2.0f * float(t) / 255.0f - 1.0f);
          const float err = std::abs(got - XiPass::netScale(s, sphere) * XV[r * 9 + std::size_t(i)][c]);
          differ += std::abs(Xon[r * 9 + std::size_t(i)][c] - X[r * 9 + std::size_t(i)][c]);
          worst = std::max(worst, err / (mm / 255.0f));
          ASSERT_LE(err, mm / 255.0f + 1e-4f * mm) << "sample " << r << " coefficient " << i << " channel " << c;
        }
      const std::size_t slice = std::size_t((variant * int(XiPass::kNetTexels) + 6) * s.spheres + sphere);
      EXPECT_EQ(bytes[((slice * h + std::size_t(y)) * w + std::size_t(face * s.faceSize + x)) * 4 + 3], 128) << "sample " << r;
    }
    if (withScale) {
      EXPECT_GT(differ, 0.0);
    } else {
      EXPECT_EQ(differ, 0.0);
    }
    std::printf("rtf 8-bit X%s: worst %.3f of half a step\n", withScale ? " (scaled)" : "", worst);
  }
}

// The frames' variant (ξ not stored; xi_subgroup.comp where the device has subgroup arithmetic) writes the
// same ranges and the same 8-bit X, byte for byte, as xi.comp with ξ stored, and as xi.comp without it: a
// maximum does not depend on the order it is taken in, and ξ is not read by stage 2. Without keepXi, xi()
// refuses. Without subgroup arithmetic only the two xi.comp passes are compared.
TEST(RtfXiGpu, SubgroupRangesAndNoXiStoresLeaveTheSameX) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const BakeResult b = bake(testing::unitSphere(glm::vec3(0.8f, 0.6f, 0.4f), 8), testing::smallSettings());
  const Field& f = b.field;
  const FieldSettings& s = f.settings;
  math::Pcg32 rng(17);
  const auto [L, blocked, scale, onObjects] = randomInputs(rng, s, true);
  std::vector<std::vector<std::uint8_t>> ranges, nets;
  std::vector<XiPassOptions> options = {{.keepXi = true, .subgroupMax = false}, {.keepXi = false, .subgroupMax = false}};
  if (computeSubgroupArithmetic(ctx)) options.push_back({.keepXi = false, .subgroupMax = true});
  for (const XiPassOptions o : options) {
    XiPass pass(ctx, f, o);
    pass.setProxyLight(L);
    pass.setBlockedLight(blocked);
    pass.setBlockedScale(scale, onObjects);
    gpu::submitAndWait(ctx, [&](VkCommandBuffer cmd) { pass.record(cmd); });
    ranges.push_back(gpu::readback(ctx, pass.netRange()));
    nets.push_back(gpu::readback(ctx, pass.net()));
    if (!o.keepXi) {
      EXPECT_THROW(pass.xi(), InternalError);
    }
  }
  ASSERT_EQ(ranges[0].size(), 28 * sizeof(float));
  std::array<float, 28> m{};
  std::memcpy(m.data(), ranges[1].data(), sizeof(m));
  for (int slot = 0; slot < 27; ++slot) EXPECT_GT(m[std::size_t(slot)], 0.0f) << "slot " << slot;  // not a trivially equal zero
  for (std::size_t k = 1; k < options.size(); ++k) {
    EXPECT_EQ(ranges[0], ranges[k]) << k;
    ASSERT_EQ(nets[0].size(), nets[k].size());
    EXPECT_EQ(nets[0], nets[k]) << k;
  }
}

}  // namespace
}  // namespace bounce::gi::rtf
