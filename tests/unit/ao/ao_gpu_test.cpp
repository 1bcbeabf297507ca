// The AO baselines: an open floor is unoccluded everywhere (no false occlusion from the surface
// itself), the Cornell box's creases are occluded, and values stay in [0, 1].
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "engine/gi/ao/node.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/format.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "game/session.hpp"

namespace bounce::gi::ao {
namespace {

namespace fs = std::filesystem;

// fp16 rounding of values ≤ 1 (2^-11) and the IGN jitter: an open plane reads ≥ 1 − this.
constexpr float kOpenTol = 0.01f;

struct AoFrame {
  std::vector<float> values;
  std::vector<std::string> passes;
};

AoFrame render(const fs::path& level, Kind kind) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session(ctx, game::loadLevelWithEffects(level, std::vector<std::string>{"direct", kindName(kind)}));
  session.update(0.0);
  Node node(ctx, session.renderer().pipelines(), kind);
  session.renderer().setNode(kindName(kind), node.node());
  gpu::OffscreenPresenter presenter(ctx, {128, 96});
  session.render(presenter, render::FrameSettings{});
  session.renderer().frames().waitIdle();
  const auto bytes = gpu::readback(ctx, *node.image());
  AoFrame f;
  f.values.resize(bytes.size() / 2);
  for (std::size_t i = 0; i < f.values.size(); ++i) {
    std::uint16_t h;
    std::memcpy(&h, &bytes[i * 2], 2);
    f.values[i] = gpu::halfToFloat(h);
  }
  f.passes = session.renderer().executedPasses();
  return f;
}

class Ao : public ::testing::TestWithParam<Kind> {};

TEST_P(Ao, OpenFloorIsUnoccluded) {
  const AoFrame f = render(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/render/plane-point.json", GetParam());
  ASSERT_EQ(f.values.size(), 128u * 96u);
  EXPECT_NE(std::find(f.passes.begin(), f.passes.end(), kindName(GetParam())), f.passes.end());
  const float lo = *std::min_element(f.values.begin(), f.values.end());
  std::printf("%s open floor: min visibility %.4f\n", kindName(GetParam()), lo);
  EXPECT_GE(lo, 1.0f - kOpenTol);
}

TEST_P(Ao, CornellCreasesAreOccluded) {
  const AoFrame f = render(fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json", GetParam());
  const float lo = *std::min_element(f.values.begin(), f.values.end());
  const float hi = *std::max_element(f.values.begin(), f.values.end());
  const auto dark = std::count_if(f.values.begin(), f.values.end(), [](float v) { return v < 0.8f; });
  double mean = 0.0;
  for (float v : f.values) mean += v;
  mean /= double(f.values.size());
  std::printf("%s cornell-1: visibility in [%.3f, %.3f], mean %.3f, %ld pixels below 0.8\n", kindName(GetParam()), lo, hi,
              mean, long(dark));
  EXPECT_GE(lo, 0.0f);
  EXPECT_LE(hi, 1.0f);
  EXPECT_GT(dark, 50);            // the box's edges and the prop's contact region
  EXPECT_LT(double(dark), 0.5 * double(f.values.size()));  // but not the open walls
}

INSTANTIATE_TEST_SUITE_P(Baselines, Ao, ::testing::Values(Kind::Ssao, Kind::Hbao),
                         [](const auto& info) { return std::string(kindName(info.param)); });

}  // namespace
}  // namespace bounce::gi::ao

namespace bounce::gi::ao {
namespace {

namespace fs = std::filesystem;

struct LitFrame {
  std::vector<float> hdr;  // RGB
  std::vector<float> ao;   // empty without an AO effect
};

LitFrame renderLit(const std::vector<std::string>& effects) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path level = fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json";
  game::Session session(ctx, game::loadLevelWithEffects(level, effects));
  session.update(0.0);
  gpu::OffscreenPresenter presenter(ctx, {128, 96});
  render::FrameSettings settings;
  settings.keepHdr = true;
  session.render(presenter, settings);
  LitFrame f;
  f.hdr = session.renderer().readHdr();
  if (Node* node = session.ao(Kind::Ssao)) {
    const auto bytes = gpu::readback(ctx, *node->image());
    for (std::size_t i = 0; i < bytes.size() / 2; ++i) {
      std::uint16_t h;
      std::memcpy(&h, &bytes[i * 2], 2);
      f.ao.push_back(gpu::halfToFloat(h));
    }
  }
  return f;
}

}  // namespace

// With an AO effect the probes node multiplies its indirect term by "ao.term" (the DNRT paper's
// baseline, §6.4): (probes+ssao − direct) = (probes − direct) · ao at every pixel. The HDR target is
// fp16, and each frame rounds its sum once: 2 half-precision steps (2·2⁻¹¹) of the brightest value.
TEST(AoProbes, ProbesTermIsMultipliedByTheAoTerm) {
  const LitFrame direct = renderLit({"direct"});
  const LitFrame probes = renderLit({"direct", "probes"});
  const LitFrame both = renderLit({"direct", "probes", "ssao"});
  ASSERT_EQ(both.ao.size() * 3, both.hdr.size());
  const float brightest = *std::max_element(probes.hdr.begin(), probes.hdr.end());
  const float tol = 2.0f * std::ldexp(1.0f, -11) * brightest;
  double darkened = 0.0;
  for (std::size_t i = 0; i < both.hdr.size(); ++i) {
    const float indirect = probes.hdr[i] - direct.hdr[i];
    const float expected = direct.hdr[i] + indirect * both.ao[i / 3];
    ASSERT_NEAR(both.hdr[i], expected, tol) << "pixel " << i / 3 << " channel " << i % 3;
    darkened += indirect - (both.hdr[i] - direct.hdr[i]);
  }
  EXPECT_GT(darkened, 0.0) << "SSAO takes some indirect light away";
}

}  // namespace bounce::gi::ao
