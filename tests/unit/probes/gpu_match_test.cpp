// The probes pass against the CPU API: render cornell-1 with effects ["probes"] only (no direct
// light, no emission in the box: the HDR image is exactly the probes term) and compare pixels
// with ρ/π·max(E(x, n, v), 0) from ProbeVolume::irradiance at the surface the camera ray hits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/core/file.hpp"
#include "engine/core/paths.hpp"
#include "engine/gi/probes/bake.hpp"
#include "engine/gi/probes/node.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/image_io.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/ref/reference_scene.hpp"
#include "engine/scene/systems.hpp"
#include "game/capture_run.hpp"
#include "game/session.hpp"

using namespace bounce;
namespace fs = std::filesystem;

namespace tiles_glsl {  // PROBE_TILE, the tile image's texels a probe per axis
using namespace glm;
#include "shaders/probes/probe_tiles.glsl"
}  // namespace tiles_glsl

namespace {
constexpr std::uint32_t kSize = 64;
// HDR is RGBA16F (11-bit mantissa, ~0.05%) and the GPU reconstructs x from a D32 depth while the
// CPU intersects exactly; near probe-weight edges that moves the result a little: 3% + 1e-4.
constexpr double kRelTol = 0.03, kAbsTol = 1e-4;
// Pixels on silhouettes and on the dynamic prop are not compared exactly: at most 5% may differ.
constexpr double kMaxDisagreeing = 0.05;
}  // namespace

TEST(ProbeGpu, PassEqualsCpuApiAtEveryPixel) {
  const fs::path out = fs::path(BOUNCE_TEST_OUT) / "probes-gpu";
  const fs::path levelPath = fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json";
  const fs::path script = out / "frame0.json";
  writeFileAtomic(script, "{\"bounce_capture\": 1, \"level\": \"" + levelPath.string() +
                              "\", \"resolution\": [64, 64], \"dt\": 0.0166667, \"frames\": 1, \"capture\": [0], "
                              "\"effects\": [\"probes\"]}");
  const game::CaptureResult raster = game::runCaptureScript(script, out / "capture");
  ASSERT_EQ(raster.frames.size(), 1u);
  const gpu::FloatImage img = gpu::readPfm(raster.frames[0].pfm);

  // The Session baked with the default settings into the build's caches: the same entry loads here.
  scene::Level level = scene::loadLevel(levelPath);
  const auto baked = gi::probes::loadOrBake(level, game::cookCacheDir(), bounce::cacheDir("probes"), {});
  EXPECT_TRUE(baked.fromCache);
  ecs::Registry registry;
  scene::instantiate(level, registry);
  scene::motionSystem(registry, 0.0);
  scene::transformSystem(registry);
  ref::ReferenceAssets assets;
  assets.load(registry, game::cookCacheDir());
  const ref::SceneBvh bvh(ref::extractScene(registry, level, assets));

  std::size_t compared = 0, disagree = 0;
  double sum = 0.0;
  for (std::uint32_t y = 0; y < kSize; ++y)
    for (std::uint32_t x = 0; x < kSize; ++x) {
      const ref::CameraRay r = ref::cameraRay(bvh.scene().camera, kSize, kSize, x, y);
      ref::Hit hit;
      if (!bvh.intersect(r.origin, r.direction, r.tMin, r.tMax, hit)) continue;
      glm::vec3 n = hit.shadingNormal;
      if (glm::dot(n, r.direction) > 0.0f) n = -n;
      const ref::RefMaterial& m = bvh.scene().materials[hit.material];
      glm::vec3 albedo = m.albedo;
      if (m.albedoTexture >= 0) albedo *= bvh.scene().textures[m.albedoTexture].sample(hit.uv);
      albedo = glm::clamp(albedo, 0.0f, 1.0f);
      const glm::vec3 e = glm::max(baked.volume.irradiance(hit.position, n, -r.direction), glm::vec3(0.0f));
      const glm::vec3 want = albedo / 3.14159265f * e;
      ++compared;
      bool ok = true;
      for (int c = 0; c < 3; ++c) {
        const double got = img.rgb[3 * (std::size_t(y) * kSize + x) + c];
        ok &= std::abs(got - want[c]) <= kRelTol * std::max<double>(got, want[c]) + kAbsTol;
        sum += got;
      }
      disagree += !ok;
    }
  ASSERT_GT(compared, kSize * kSize / 2);
  EXPECT_GT(sum, 0.0);
  const double fraction = double(disagree) / double(compared);
  std::printf("probes pass vs CPU API: %.2f %% of %zu pixels differ\n", 100 * fraction, compared);
  EXPECT_LE(fraction, kMaxDisagreeing);
}

// Issue 15: probes.frag reads the probes' SH from a uniform block when the volume fits 64 KiB
// (cheaper on llvmpipe than a texelFetch per texel), packed (node.cpp shPackedWords: L_0 as halves,
// L_1, L_2 as 8-bit fractions of s·L_0; 8 words a probe at order 3, not the image's 28 floats), and
// from the image's floats otherwise. L_0 rounds by at most 2⁻¹¹ relative, and the RGBA16F target
// rounds both images by 2⁻¹¹ again, so a channel may move by that (which can partly cancel, hence
// the absolute floor: 2⁻¹¹ of the image's largest value) plus two target roundings, plus the 8-bit
// fractions' bound on E (gi::probes::packedShIrradianceError, derived in node.cpp) times ρ/π ≤ 1/π:
// |a − b| ≤ 3·2⁻¹¹·max(a, b) + 2⁻¹¹·max + E_q/π. The visibility moments come from a second block as
// (mean, σ) halves when they fit (256 probes; cornell-1's 216 do): they move the Chebyshev weights
// by about 2⁻¹¹ relative, inside the same bound (alone they move cornell-1's captures by rel RMSE
// 2.4e-5). A volume past the block (more than 2016 probes) takes the image path.
TEST(ProbeGpu, ShFromTheUniformBlockIsTheImagePathWithinItsRounding) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path levelPath = fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json";
  game::Session session(ctx, game::loadLevelWithEffects(levelPath, std::vector<std::string>{"probes"}));
  session.update(0.0);
  const auto baked =
      gi::probes::loadOrBake(scene::loadLevel(levelPath), game::cookCacheDir(), bounce::cacheDir("probes"), {});
  ASSERT_EQ(baked.volume.order, 3);
  ASSERT_EQ(baked.volume.grid.probeCount(), 216u);
  const auto render = [&](gi::probes::ProbeNode& node) {
    session.renderer().setNode("probes", node.node());
    gpu::OffscreenPresenter presenter(ctx, {160, 120});
    render::FrameSettings settings;
    settings.keepHdr = true;
    session.render(presenter, settings);
    return session.renderer().readHdr();
  };
  // Order 3 as baked, and order 2 (the first 4 coefficients of each probe: 5 of the 8 words).
  gi::probes::ProbeVolume order2 = baked.volume;
  order2.order = 2;
  order2.sh.clear();
  for (std::size_t p = 0; p < baked.volume.grid.probeCount(); ++p)
    for (std::size_t i = 0; i < 4; ++i) order2.sh.push_back(baked.volume.sh[p * 9 + i]);
  // And order 3 with every third probe invalid (cornell-1 has none): the block's valid bits
  // (node.cpp shPackedWords, one bit a probe after the SH texels, 7 words for 216 probes) must
  // drop the same probes as the image's valid floats.
  gi::probes::ProbeVolume holes = baked.volume;
  for (std::size_t p = 1; p < holes.valid.size(); p += 3) holes.valid[p] = 0u;
  const gi::probes::ProbeVolume* volumes[] = {&baked.volume, &order2, &holes};
  std::vector<float> allValid;
  for (const gi::probes::ProbeVolume* volume : volumes) {
    // The packed SH themselves, not the irradiance tiles made from them (next test).
    gi::probes::ProbeNode ubo(ctx, session.renderer().pipelines(), *volume, true, false);
    gi::probes::ProbeNode image(ctx, session.renderer().pipelines(), *volume, false);
    EXPECT_FALSE(ubo.tiles());
    EXPECT_FALSE(image.tiles());
    EXPECT_TRUE(ubo.shInUbo());
    EXPECT_TRUE(ubo.momentsInUbo());
    EXPECT_FALSE(image.shInUbo());
    EXPECT_FALSE(image.momentsInUbo());
    const std::vector<float> a = render(ubo), b = render(image);
    ASSERT_EQ(a.size(), b.size());
    constexpr double kHalfUlp = 1.0 / 2048.0;  // 2⁻¹¹: fp16's unit roundoff
    const double quantised = gi::probes::packedShIrradianceError(*volume) / 3.14159265358979;  // ρ/π·E_q, ρ ≤ 1
    double top = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) top = std::max(top, double(std::abs(b[i])));
    std::size_t lit = 0, equal = 0, outside = 0, pastHalves = 0;
    double worst = 0.0;    // the largest |a − b| / max(a, b) over channels above 1 % of the top
    double largest = 0.0;  // the largest |a − b| beyond the fp16 part of the bound, as a fraction of E_q/π
    for (std::size_t i = 0; i < a.size(); ++i) {
      lit += a[i] > 0.0f, equal += a[i] == b[i];
      const double big = std::max(std::abs(double(a[i])), std::abs(double(b[i]))), diff = std::abs(double(a[i]) - b[i]);
      const double halves = 3.0 * kHalfUlp * big + kHalfUlp * top;
      outside += diff > halves + quantised;
      pastHalves += diff > halves;
      largest = std::max(largest, (diff - halves) / quantised);
      if (big > 0.01 * top) worst = std::max(worst, diff / big);
    }
    std::printf("probes order %d, the uniform blocks' packed SH vs the images' floats: %zu of %zu channel values "
                "equal, %zu lit, largest relative difference %.2e (above 1 %% of the top value %.3g); 8-bit bound "
                "E_q/pi = %.3g (%.2e of the top), %zu values past the fp16 part, the largest at %.3f of E_q/pi\n",
                volume->order, equal, a.size(), lit, worst, top, quantised, quantised / top, pastHalves, largest);
    EXPECT_GT(lit, a.size() / 2);
    EXPECT_GT(top, 0.0);
    EXPECT_EQ(outside, 0u) << "order " << volume->order;
    EXPECT_LT(equal, a.size());  // the blocks really hold the packed values: some channel moved
    EXPECT_GT(quantised, 0.0);
    EXPECT_LT(quantised, 0.03 * top);  // the derivation's bound is not vacuous on this image
    if (volume == &baked.volume) allValid = a;
    if (volume == &holes) {  // the flags matter here: a third of the probes left out moves most pixels
      std::size_t moved = 0;
      for (std::size_t i = 0; i < a.size(); ++i) moved += std::abs(a[i] - allValid[i]) > 0.01f * std::abs(allValid[i]);
      std::printf("probes with every third one invalid: %zu of %zu channel values move by > 1 %%\n", moved, a.size());
      EXPECT_GT(moved, a.size() / 4);
    }
  }

  // 2 texels a probe at either order: 12³ = 1728 probes fit (3456 + 54 texels), 13³ = 2197 do not.
  gi::probes::ProbeVolume big = baked.volume;
  for (int perAxis : {12, 13}) {
    big.grid.count = glm::ivec3(perAxis);
    const std::size_t n = big.grid.probeCount();
    big.sh.assign(n * std::size_t(big.coeffs()), glm::vec3(0.1f));
    big.moments.assign(n * std::size_t(gi::probes::kVisBins), glm::vec2(1.0f, 1.0f));
    big.valid.assign(n, 1u);
    const gi::probes::ProbeNode node(ctx, session.renderer().pipelines(), big);
    EXPECT_EQ(node.shInUbo(), perAxis == 12) << perAxis;
    EXPECT_FALSE(node.momentsInUbo()) << perAxis << ": 64 bins × 4 B a probe, 256 probes at most";
  }
  // With the valid bits (a texel per 32 probes after the SH texels): 2016 probes fit at either order
  // (4032 + 63 texels), 2017 do not (4034 + 64 > 4096).
  for (const int order : {2, 3})
    for (const glm::ivec3 count : {glm::ivec3(16, 126, 1), glm::ivec3(1, 2017, 1)}) {
      big.order = order;
      big.grid.count = count;
      const std::size_t n = big.grid.probeCount();
      big.sh.assign(n * std::size_t(big.coeffs()), glm::vec3(0.1f));
      big.moments.assign(n * std::size_t(gi::probes::kVisBins), glm::vec2(1.0f, 1.0f));
      big.valid.assign(n, 1u);
      EXPECT_EQ(gi::probes::ProbeNode(ctx, session.renderer().pipelines(), big).shInUbo(), n == 2016u) << n;
    }
  big.order = 3;
  // A value past the largest half (65504) keeps the image path.
  big.grid.count = glm::ivec3(9);
  big.sh.assign(big.grid.probeCount() * std::size_t(big.coeffs()), glm::vec3(0.1f));
  big.moments.assign(big.grid.probeCount() * std::size_t(gi::probes::kVisBins), glm::vec2(1.0f, 1.0f));
  big.valid.assign(big.grid.probeCount(), 1u);
  big.sh[9] = glm::vec3(1e5f, 0.1f, 0.1f);  // probe 1's L_0
  EXPECT_FALSE(gi::probes::ProbeNode(ctx, session.renderer().pipelines(), big).shInUbo());
  // So does an L_0 channel of 0 under a non-zero L_i (no finite fraction; a baked volume, its
  // radiance ≥ 0, has none), and a fraction past the largest half (s = |L_i| / |L_0|).
  big.sh[9] = glm::vec3(0.0f, 0.1f, 0.1f);
  EXPECT_FALSE(gi::probes::ProbeNode(ctx, session.renderer().pipelines(), big).shInUbo());
  big.sh[9] = glm::vec3(1e-3f, 0.1f, 0.1f), big.sh[10] = glm::vec3(1e3f, 0.0f, 0.0f);
  EXPECT_FALSE(gi::probes::ProbeNode(ctx, session.renderer().pipelines(), big).shInUbo());
  big.sh[10] = glm::vec3(10.0f, 0.0f, 0.0f);  // s = 10⁴: finite, the block path
  EXPECT_TRUE(gi::probes::ProbeNode(ctx, session.renderer().pipelines(), big).shInUbo());
}

// Session 11: probes.frag taps each corner probe's irradiance tile (pass probes.tiles, one bilinear
// RGBA16F tap a probe, shaders/probes/probe_tiles.glsl) instead of reading its packed SH words. The
// tiles are E of the same packed SH at the texels' normals, so against the block's SH path a channel
// moves by the tiles' interpolation error (gi::probes::tileIrradianceError, measured over dense
// normals on the CPU) times ρ/π ≤ 1/π, plus the tile texels' fp16 rounding and the two targets'
// (2⁻¹¹ each, relative; the E_k mixed can exceed their mix, hence the floor 2⁻¹¹ of the top value):
// |a − b| ≤ 4·2⁻¹¹·max(a, b) + 2⁻¹¹·top + E_t/π.
TEST(ProbeGpu, TilesAreTheShPathWithinTheirInterpolationError) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path levelPath = fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json";
  game::Session session(ctx, game::loadLevelWithEffects(levelPath, std::vector<std::string>{"probes"}));
  session.update(0.0);
  const auto baked =
      gi::probes::loadOrBake(scene::loadLevel(levelPath), game::cookCacheDir(), bounce::cacheDir("probes"), {});
  const auto render = [&](gi::probes::ProbeNode& node) {
    session.renderer().setNode("probes", node.node());
    gpu::OffscreenPresenter presenter(ctx, {160, 120});
    render::FrameSettings settings;
    settings.keepHdr = true;
    session.render(presenter, settings);
    return session.renderer().readHdr();
  };
  gi::probes::ProbeVolume order2 = baked.volume;
  order2.order = 2;
  order2.sh.clear();
  for (std::size_t p = 0; p < baked.volume.grid.probeCount(); ++p)
    for (std::size_t i = 0; i < 4; ++i) order2.sh.push_back(baked.volume.sh[p * 9 + i]);
  const gi::probes::ProbeVolume* orders[] = {&baked.volume, &order2};
  for (const gi::probes::ProbeVolume* volume : orders) {
    gi::probes::ProbeNode tiles(ctx, session.renderer().pipelines(), *volume);
    gi::probes::ProbeNode sh(ctx, session.renderer().pipelines(), *volume, true, false);
    ASSERT_TRUE(tiles.tiles());
    ASSERT_FALSE(sh.tiles());
    const std::vector<float> a = render(tiles), b = render(sh);
    ASSERT_EQ(a.size(), b.size());
    constexpr double kHalfUlp = 1.0 / 2048.0;
    const double interpolation = gi::probes::tileIrradianceError(*volume) / 3.14159265358979;  // ρ/π·E_t, ρ ≤ 1
    double top = 0.0, sumSq = 0.0, diffSq = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) top = std::max(top, double(std::abs(b[i])));
    std::size_t lit = 0, outside = 0, equal = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      lit += b[i] > 0.0f, equal += a[i] == b[i];
      const double big = std::max(std::abs(double(a[i])), std::abs(double(b[i]))), diff = std::abs(double(a[i]) - b[i]);
      const double halves = 4.0 * kHalfUlp * big + kHalfUlp * top;
      outside += diff > halves + interpolation;
      largest = std::max(largest, diff / interpolation);
      sumSq += double(b[i]) * b[i], diffSq += diff * diff;
    }
    std::printf("probes order %d, irradiance tiles vs the SH: relative RMSE %.2e, largest difference %.3f of the "
                "interpolation bound E_t/pi = %.3g (%.2e of the top value %.3g), %zu of %zu values equal\n",
                volume->order, std::sqrt(diffSq / sumSq), largest, interpolation, interpolation / top, top, equal,
                a.size());
    EXPECT_GT(lit, a.size() / 2);
    EXPECT_EQ(outside, 0u) << "order " << volume->order;
    EXPECT_LT(equal, a.size());                    // the tiles really are read
    // E_t is absolute, set by the brightest probes (beside the lamp): 12 % (order 3) / 8 % (order 2) of
    // the image's top value, while the pixels move by at most 0.05 of it. On average the image moves
    // far less, measured 3.6e-3 / 2.8e-3 relative RMSE: a tenth of the goldens' 2 % tolerance.
    EXPECT_LT(interpolation, 0.15 * top);
    // The bound is measured with the same probe_tiles.glsl functions the pass runs, so it cannot see
    // a wrong border rule or tap (tiles_test.cpp checks those against geometry); the pixels' own
    // largest move, measured 0.034 (order 3) / 0.05 (order 2) of it, would grow past 0.1 of it.
    EXPECT_LT(largest, 0.1) << "order " << volume->order;
    EXPECT_LT(std::sqrt(diffSq / sumSq), 5e-3);
  }
  // Tiles need the block (they read the SH from it) and an image within the device's 2D limit:
  // 1100 probes in one column fit the block but make a 16 × 17 600 image.
  gi::probes::ProbeVolume big = baked.volume;
  for (const glm::ivec3 count : {glm::ivec3(9), glm::ivec3(1, 1100, 1), glm::ivec3(13)}) {
    big.grid.count = count;
    const std::size_t n = big.grid.probeCount();
    big.sh.assign(n * std::size_t(big.coeffs()), glm::vec3(0.1f));
    big.moments.assign(n * std::size_t(gi::probes::kVisBins), glm::vec2(1.0f, 1.0f));
    big.valid.assign(n, 1u);
    const gi::probes::ProbeNode node(ctx, session.renderer().pipelines(), big);
    const bool fits = std::uint32_t(tiles_glsl::PROBE_TILE * count.y * count.z) <= ctx.limits().maxImageDimension2D;
    EXPECT_EQ(node.shInUbo(), n <= 2016u) << n;
    EXPECT_EQ(node.tiles(), node.shInUbo() && fits) << n;
  }
}
