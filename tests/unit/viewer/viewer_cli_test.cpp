// `bounce` on a glTF file as a user runs it (child processes, Vulkan validation on): a capture of
// the Duck shows the duck in the middle, sky above, lit ground below and the sun's shadow; `bounce
// level` writes a level that loads and names the same asset; bad input is exit 2 with one line.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/gpu/image_io.hpp"
#include "engine/scene/level.hpp"
#include "game/display_tonemap.hpp"
#include "tests/support/cli_run.hpp"

namespace fs = std::filesystem;
using bounce::gpu::CpuImage;

namespace {

using bounce::testcli::Outcome;
using bounce::testcli::quote;
using bounce::testcli::readText;

const fs::path kDuck = fs::path(BOUNCE_SHARED_DIR) / "assets/Duck/glTF-Binary/Duck.glb";

// Measured at 160x120 (frame 0, default effects direct,shadows,probes); each bound is far from
// both the measured value and what a wrong picture (black, sky only, model off-centre) gives.
// The Duck's texture is yellow: in the middle tenth of the image R and G exceed B by ~100 levels.
constexpr double kMinYellowExcess = 40.0;
// The sky (background 0.4, grey) in the top corners: channels within a few levels, not black.
constexpr double kMaxSkyChannelSpread = 6.0;
constexpr double kMinSkyLevel = 60.0;
// The ground in the bottom rows is lit (sun + sky): not black.
constexpr double kMinGroundLevel = 40.0;
// Shadows only darken: no pixel brighter with shadows than without (8-bit rounding aside) ...
constexpr int kMaxShadowBrightening = 1;
// ... and the duck's shadow darkens a visible part of the ground by more than 20 levels.
constexpr int kShadowDarkening = 20;
constexpr double kMinShadowFraction = 0.01;
// CPU tonemap of the PFM vs the GPU's PNG: both round to nearest, from the same RGBA16F values.
constexpr int kMaxTonemapLevels = 1;

class ViewerCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(BOUNCE_TEST_OUT) / "viewer-cli" / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  Outcome bounce(const std::vector<std::string>& args) { return bounce::testcli::runBounce(args, dir_); }
  CpuImage capture(const std::string& name, const std::string& effects) {
    std::vector<std::string> args{"capture", kDuck.string(), "--out", (dir_ / name).string(), "--resolution", "160x120"};
    if (!effects.empty()) args.insert(args.end(), {"--effects", effects});
    const Outcome r = bounce(args);
    EXPECT_EQ(r.code, 0) << r.err;
    return bounce::gpu::readPng(dir_ / name / "frame-0000.png");
  }
  fs::path dir_;
};

struct Mean {
  double c[3] = {0, 0, 0};
};

Mean mean(const CpuImage& img, std::uint32_t x0, std::uint32_t y0, std::uint32_t x1, std::uint32_t y1) {
  Mean m;
  for (std::uint32_t y = y0; y < y1; ++y)
    for (std::uint32_t x = x0; x < x1; ++x)
      for (int k = 0; k < 3; ++k) m.c[k] += img.bytes[(std::size_t(y) * img.width + x) * 4 + k];
  for (double& v : m.c) v /= double((x1 - x0) * (y1 - y0));
  return m;
}

}  // namespace

TEST_F(ViewerCli, CaptureOfADuckShowsDuckSkyGroundAndShadow) {
  const CpuImage lit = capture("default", "");
  ASSERT_EQ(lit.width, 160u);
  ASSERT_EQ(lit.height, 120u);
  const Mean centre = mean(lit, 64, 48, 96, 72);
  EXPECT_GT(centre.c[0] - centre.c[2], kMinYellowExcess);
  EXPECT_GT(centre.c[1] - centre.c[2], kMinYellowExcess);
  for (std::uint32_t x0 : {0u, 150u}) {
    const Mean sky = mean(lit, x0, 0, x0 + 10, 6);
    EXPECT_GT(sky.c[1], kMinSkyLevel);
    EXPECT_LT(std::max({sky.c[0], sky.c[1], sky.c[2]}) - std::min({sky.c[0], sky.c[1], sky.c[2]}), kMaxSkyChannelSpread);
  }
  const Mean ground = mean(lit, 0, 112, 160, 120);
  EXPECT_GT(ground.c[1], kMinGroundLevel);
  // The CPU display transform (reference previews) is the GPU's: the capture's PFM through it
  // gives its PNG, up to one 8-bit level of rounding (the HDR target is RGBA16F).
  const auto cpu = bounce::game::tonemapToSrgb8(bounce::gpu::readPfm(dir_ / "default" / "frame-0000.pfm"));
  ASSERT_EQ(cpu.size(), lit.bytes.size());
  int worst = 0;
  for (std::size_t i = 0; i < cpu.size(); ++i) worst = std::max(worst, std::abs(int(cpu[i]) - int(lit.bytes[i])));
  EXPECT_LE(worst, kMaxTonemapLevels);

  const CpuImage shadowed = capture("shadows", "direct,shadows");
  const CpuImage unshadowed = capture("direct", "direct");
  std::size_t darker = 0;
  int brightest = -255;
  for (std::size_t i = 0; i < shadowed.bytes.size(); i += 4) {
    const int delta = int(shadowed.bytes[i + 1]) - int(unshadowed.bytes[i + 1]);
    brightest = std::max(brightest, delta);
    darker += delta < -kShadowDarkening;
  }
  EXPECT_LE(brightest, kMaxShadowBrightening);
  EXPECT_GT(double(darker) / double(160 * 120), kMinShadowFraction);
}

TEST_F(ViewerCli, LevelCommandWritesALevelThatLoads) {
  const fs::path out = dir_ / "my" / "duck.json";
  const Outcome r = bounce({"level", kDuck.string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const bounce::scene::Level level = bounce::scene::loadLevel(out);
  ASSERT_EQ(level.entities.size(), 4u);
  ASSERT_TRUE(level.entities[0].mesh);
  EXPECT_EQ(level.entities[0].mesh->asset, fs::absolute(kDuck).lexically_normal());
  EXPECT_EQ(readText(out).find("\"/"), std::string::npos) << "paths relative to the level";
  // ... and plays like any level (one frame, headless).
  const Outcome p = bounce({"profile", out.string(), "--frames", "1", "--resolution", "64x48"});
  EXPECT_EQ(p.code, 0) << p.err;
}

TEST_F(ViewerCli, BadInputIsExitTwoWithOneLine) {
  const Outcome missing = bounce({"profile", (dir_ / "missing.glb").string(), "--frames", "1"});
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("missing.glb: file: not found"), std::string::npos) << missing.err;
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
  const Outcome notGltf = bounce({"level", (fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json").string(), "--out",
                                  (dir_ / "x.json").string()});
  EXPECT_EQ(notGltf.code, 2);
  EXPECT_NE(notGltf.err.find("not a glTF file"), std::string::npos) << notGltf.err;
  const Outcome noOut = bounce({"level", kDuck.string()});
  EXPECT_EQ(noOut.code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "x.json"));
}

TEST_F(ViewerCli, ReferenceOfAGltfFileWritesAPngPreview) {
  const fs::path out = dir_ / "duck-ref.pfm";
  const Outcome r = bounce({"reference", kDuck.string(), "--out", out.string(), "--spp", "1", "--resolution", "32x24"});
  ASSERT_EQ(r.code, 0) << r.err;
  const CpuImage preview = bounce::gpu::readPng(dir_ / "duck-ref.png");
  EXPECT_EQ(preview.width, 32u);
  EXPECT_EQ(preview.height, 24u);
  const auto expected = bounce::game::tonemapToSrgb8(bounce::gpu::readPfm(out));
  EXPECT_EQ(std::vector<std::uint8_t>(preview.bytes.begin(), preview.bytes.end()), expected);
}

// Issue 16: a misspelt command is answered with the nearest one; a level given to `capture` (and
// a capture script to `play`/`profile`) says what the file is.
TEST_F(ViewerCli, MisspeltCommandAndSwappedFileKindsAreNamed) {
  const Outcome typo = bounce({"captur", "x"});
  EXPECT_EQ(typo.code, 2);
  EXPECT_EQ(typo.err, "bounce: captur: unknown command, did you mean \"capture\"? (expected one of the commands in 'bounce --help')\n");
  const fs::path level = fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json";
  const Outcome asScript = bounce({"capture", level.string(), "--out", (dir_ / "o").string()});
  EXPECT_EQ(asScript.code, 2);
  EXPECT_NE(asScript.err.find("cornell-1.json: /bounce_level: this is a level, not a capture script"), std::string::npos)
      << asScript.err;
  const fs::path script = fs::path(BOUNCE_SOURCE_DIR) / "content/captures/cornell-1.json";
  const Outcome asLevel = bounce({"profile", script.string(), "--frames", "1"});
  EXPECT_EQ(asLevel.code, 2);
  EXPECT_NE(asLevel.err.find("cornell-1.json: /bounce_capture: this is a capture script, not a level"), std::string::npos)
      << asLevel.err;
}

// Issue 16: a render size the device cannot hold is refused before any work, exit 2, one line.
TEST_F(ViewerCli, OversizedResolutionIsRefusedUpFront) {
  // 16384² needs ~16 GiB of frame images: refused on lavapipe (system memory) and on GPUs with
  // less than 32 GiB; a larger device renders it, and then there is nothing to refuse.
  const Outcome r = bounce({"profile", kDuck.string(), "--frames", "1", "--resolution", "16384x16384"});
  if (r.code == 0) GTEST_SKIP() << "this device holds 16384x16384 frames";
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("bounce profile: --resolution: 16384x16384"), std::string::npos) << r.err;
}

// Issue 16: a scripted key after the last frame was silently ignored.
TEST_F(ViewerCli, ScriptedKeyAfterTheLastFrameIsBadInput) {
  const Outcome r = bounce({"play", kDuck.string(), "--frames", "3", "--keys", "F3@100"});
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "bounce play: --keys: a key at frame 100 after the last frame (2) (expected frames below --frames 3)\n");
}
