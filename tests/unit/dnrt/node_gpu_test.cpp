// The DNRT node on the GPU (lavapipe on CPU-only machines): cornell-1 with its prop's field, lit by
// a constant environment, rendered with and without the node. Under uniform light the object only
// removes light (L_DNRT = ρ_r L (R/d)² (ρ_s − 1) ≤ 0 for ρ_s ≤ 1), so the lack-of-light effect
// must darken the surfaces near the prop and brighten nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "engine/core/log.hpp"
#include "engine/gi/dnrt/bake.hpp"
#include "engine/gi/dnrt/irradiance_source.hpp"
#include "engine/gi/dnrt/node.hpp"
#include "engine/gi/dnrt/object_scene.hpp"
#include "engine/gi/dnrt/runtime.hpp"
#include "engine/gi/dnrt/technique.hpp"
#include "engine/gi/upsample.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/format.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "engine/render/passes/gbuffer_pass.hpp"
#include "engine/render/vk_backend.hpp"
#include "game/session.hpp"
#include "tests/unit/render/analytic.hpp"

namespace bounce::gi::dnrt {
namespace {

namespace fs = std::filesystem;

// fp16 rounding of the HDR target (11-bit mantissa: 5e-4 relative) on values ≲ 1.
constexpr float kHalfTol = 2e-3f;
// The ambient radiance of the constant environment (W/(m²·sr)).
constexpr float kAmbient = 2.0f;

struct Frame {
  std::vector<float> rgb;
  std::vector<std::string> passes;
};

Frame renderOnce(game::Session& session, gpu::Context& ctx) {
  gpu::OffscreenPresenter presenter(ctx, {160, 120});
  render::FrameSettings settings;
  settings.keepHdr = true;
  session.render(presenter, settings);
  return {session.renderer().readHdr(), session.renderer().executedPasses()};
}

// two-boxes.json in a session with its DNRT runtime (baked through a cache folder of the test's own:
// RuntimeBakesThroughTheCache… empties its folder and tests may run in parallel), rendered once so
// the world the objects are packed from is extracted; `objects` are its two drawn objects and `node`
// a bare node the test drives with objects and settings of its choosing.
struct TwoBoxes {
  explicit TwoBoxes(const char* cacheName)
      : session(ctx, game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/two-boxes.json",
                                                std::nullopt)),
        node(ctx, session.renderer().pipelines(), gpu::FrameRing::kDefaultFramesInFlight) {
    session.update(0.0);
    assets.load(session.registry(), fs::path(BOUNCE_TEST_OUT) / "dnrt" / "cooked");
    runtime = std::make_unique<Runtime>(ctx, session.renderer().pipelines(), session.registry(), assets,
                                        fs::path(BOUNCE_TEST_OUT) / "dnrt" / cacheName,
                                        gpu::FrameRing::kDefaultFramesInFlight, session.level().background);
    session.renderer().setNode("dnrt", runtime->node());
    renderOnce(session, ctx);
    objects = runtime->objectsFor(session.world());
  }
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session;
  Node node;
  ref::ReferenceAssets assets;
  std::unique_ptr<Runtime> runtime;
  std::vector<NodeObject> objects;
};

// floor-box.json (a box above a floor, camera straight down) in a session, its meshes loaded for the
// bake, and the DNRT entity: the setup of the tests that compare the floor with a CPU figure.
struct FloorBox {
  FloorBox()
      : session(ctx, game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/floor-box.json",
                                                std::nullopt)),
        reg(session.registry()) {
    session.update(0.0);
    assets.load(reg, fs::path(BOUNCE_TEST_OUT) / "dnrt" / "cooked");
    reg.view<scene::Dnrt>().each([&](ecs::Entity e, scene::Dnrt&) { box = e; });
  }
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session;
  ecs::Registry& reg;
  ref::ReferenceAssets assets;
  ecs::Entity box;
};

TEST(DnrtGpu, PropDarkensItsSurroundingsAndBrightensNothing) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session(ctx, game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json",
                                                        std::vector<std::string>{"direct", "dnrt"}));
  session.update(0.0);
  ecs::Registry& reg = session.registry();
  ref::ReferenceAssets assets;
  assets.load(reg, fs::path(BOUNCE_TEST_OUT) / "dnrt" / "cooked");
  ecs::Entity prop;
  reg.view<scene::Dnrt>().each([&](ecs::Entity e, scene::Dnrt&) { prop = e; });
  ASSERT_FALSE(prop.isNull());
  FieldSettings fs = settingsFrom(reg.get<scene::Dnrt>(prop));
  fs.grid = 16;  // CI-sized bake
  fs.samplesPerAxis = 8;
  const BakeResult baked = bake(objectScene(reg, prop, assets), fs);
  const FieldTextures textures(ctx, baked.field, "prop");
  Node node(ctx, session.renderer().pipelines(), gpu::FrameRing::kDefaultFramesInFlight);
  const ConstantEnvironment env{glm::vec3(kAmbient)};
  bool fullScreen = false, objectFullScreen = false, mirrored = false;
  session.renderer().setNode("dnrt", [&](rg::RenderGraph& graph, render::PassContext& pc) {
    // mirrored: the prop's field reflected through its local x = 0 plane (det(world) < 0).
    const glm::mat4 world = reg.get<scene::WorldTransform>(prop).matrix *
                            glm::mat4(glm::vec4(mirrored ? -1.0f : 1.0f, 0, 0, 0), glm::vec4(0, 1, 0, 0),
                                      glm::vec4(0, 0, 1, 0), glm::vec4(0, 0, 0, 1));
    const glm::vec3 o = glm::vec3(world * glm::vec4(baked.field.centre, 1.0f));
    NodeObject obj{&textures, packObject(baked.field, world, env.radianceSH(o), prop.index()), "prop"};
    obj.mode = objectFullScreen ? Mode::FullScreen : Mode::Box;  // the level's "mode": "fullscreen"
    node.addTo(graph, pc, {obj}, NodeSettings{fullScreen ? std::optional(Mode::FullScreen) : std::nullopt});
  });
  const Frame with = renderOnce(session, ctx);
  fullScreen = true;
  const Frame withFull = renderOnce(session, ctx);
  fullScreen = false, objectFullScreen = true;
  const Frame withObjectFull = renderOnce(session, ctx);
  EXPECT_EQ(withObjectFull.rgb, withFull.rgb) << "per-object and node-wide full-screen mode draw the same";
  objectFullScreen = false, mirrored = true;
  const Frame mirroredBox = renderOnce(session, ctx);
  fullScreen = true;
  const Frame mirroredFull = renderOnce(session, ctx);
  fullScreen = false;
  session.renderer().setNode("dnrt", {});
  const Frame without = renderOnce(session, ctx);

  EXPECT_NE(std::find(with.passes.begin(), with.passes.end(), "dnrt"), with.passes.end());
  EXPECT_EQ(std::find(without.passes.begin(), without.passes.end(), "dnrt"), without.passes.end());
  ASSERT_EQ(with.rgb.size(), without.rgb.size());
  std::size_t darkened = 0, brightened = 0;
  double removed = 0.0, modeDiff = 0.0;
  for (std::size_t i = 0; i < with.rgb.size(); ++i) {
    const float d = with.rgb[i] - without.rgb[i];
    const float tol = kHalfTol * std::max(1.0f, std::abs(without.rgb[i]));
    if (d < -tol) ++darkened, removed -= d;
    if (d > tol) ++brightened;
    modeDiff = std::max(modeDiff, double(std::abs(withFull.rgb[i] - with.rgb[i])));
  }
  std::printf("dnrt: %zu of %zu channel values darkened (total %.3f), %zu brightened; box vs full screen max diff %.2g\n",
              darkened, with.rgb.size(), removed, brightened, modeDiff);
  EXPECT_GT(darkened, 300u);  // the prop's neighbourhood covers hundreds of pixels at 160×120
  EXPECT_EQ(brightened, 0u);
  // The box covers every pixel with a non-zero term: both modes give the same image.
  EXPECT_LT(modeDiff, kHalfTol);

  // A mirrored object (negative-determinant world matrix) keeps its box: its back faces stay back
  // faces, so the box draws what full screen draws, and the mirrored field still darkens hundreds of
  // values (a flipped winding would cull the exit faces and depth-reject every receiver: 0 darkened).
  std::size_t mirroredDarkened = 0;
  double mirroredDiff = 0.0;
  for (std::size_t i = 0; i < with.rgb.size(); ++i) {
    if (mirroredBox.rgb[i] - without.rgb[i] < -kHalfTol * std::max(1.0f, std::abs(without.rgb[i]))) ++mirroredDarkened;
    mirroredDiff = std::max(mirroredDiff, double(std::abs(mirroredFull.rgb[i] - mirroredBox.rgb[i])));
  }
  std::printf("dnrt mirrored: %zu darkened; box vs full screen max diff %.2g\n", mirroredDarkened, mirroredDiff);
  EXPECT_GT(mirroredDarkened, 300u);
  EXPECT_LT(mirroredDiff, kHalfTol);
}

// The shader against its CPU mirror (evaluate.hpp), pixel by pixel: a rotated 9-SH box above a
// floor, lit by radiance with l = 1 and l = 2 content (so the SH rotation into the object frame
// matters), no other light: the HDR image IS L_DNRT. Camera straight down; floor points from the
// level file (tests/unit/render/analytic.hpp).
TEST(DnrtGpu, ShaderMatchesCpuEvaluationOnTheFloor) {
  FloorBox f;
  ASSERT_FALSE(f.box.isNull());
  gpu::Context& ctx = f.ctx;
  game::Session& session = f.session;
  ecs::Registry& reg = f.reg;
  ref::ReferenceAssets& assets = f.assets;
  const ecs::Entity box = f.box;
  // The level's 9-SH field (7 slots) and the same box at 4 SH (3 slots): combine.comp's two variants.
  for (const int shCount : {9, 4}) {
    FieldSettings fieldSettings = settingsFrom(reg.get<scene::Dnrt>(box));
    fieldSettings.shCount = shCount;
    const BakeResult baked = bake(objectScene(reg, box, assets), fieldSettings);
    const FieldTextures textures(ctx, baked.field, "box");
    Node node(ctx, session.renderer().pipelines(), gpu::FrameRing::kDefaultFramesInFlight);
    std::array<glm::vec3, 9> sky{};
    const float v[9] = {3.0f, 0.8f, 1.4f, -0.6f, 0.5f, -0.9f, 0.7f, 0.4f, -1.1f};
    for (int i = 0; i < 9; ++i) sky[std::size_t(i)] = v[i] * glm::vec3(1.0f, 0.8f, 0.6f);
    const glm::mat4 world = reg.get<scene::WorldTransform>(box).matrix;
    session.renderer().setNode("dnrt", [&](rg::RenderGraph& graph, render::PassContext& pc) {
      node.addTo(graph, pc, {NodeObject{&textures, packObject(baked.field, world, sky), "box"}});
    });
    constexpr std::uint32_t kW = 96, kH = 96;
    gpu::OffscreenPresenter presenter(ctx, {kW, kH});
    render::FrameSettings settings;
    settings.keepHdr = true;
    session.render(presenter, settings);
    const std::vector<float> rgb = session.renderer().readHdr();

    const rtest::FloorScene floor = rtest::readFloorScene(session.level());
    const Placement pl = place(baked.field, world);
    const auto c = toLocal(irradianceSH(sky), pl.localToWorldRotation);
    // Bound of the GPU/CPU difference per channel. The draw filters this frame's combined volume
    // (combine.comp: Σ_j c_j M_j per grid vertex, exact texels, stored as fp16) with float weights, not
    // the UNORM8 slots (which llvmpipe filters with 8-bit weights and rounds to 8 bits again, up to
    // (hi − lo)/510 per coefficient: the bound before, about 4× this one). So: the fp16 rounding of a
    // vertex's sum, 2⁻¹¹ of at most Σ_j |c_j| max(|lo|, |hi|), times ρ_r ((n_o·n_r)₊ s ≤ 1).
    glm::vec3 filterBound(0.0f);
    for (int j = 0; j < baked.field.settings.shCount; ++j)
      for (int ch = 0; ch < 3; ++ch) {
        const Slot sl = slotOf(j, ch);
        const Range& r = baked.field.ranges[std::size_t(sl.texture) * 4 + sl.component];
        filterBound[ch] += floor.albedo[ch] * std::abs(c[std::size_t(j)][ch]) *
                           std::max(std::abs(r.lo), std::abs(r.hi)) / 2048.0f;
      }
    // fp16 output: 11-bit mantissa, relative rounding 2^-11 ≈ 5e-4 (1e-3 for the blend's two roundings).
    constexpr float kHalfRel = 1e-3f;
    float largest = 0.0f, worst = 0.0f, worstRatio = 0.0f;
    int compared = 0;
    for (std::uint32_t y = 0; y < kH; ++y)
      for (std::uint32_t x = 0; x < kW; ++x) {
        const auto p = rtest::floorPoint(floor, kW, kH, x, y);
        if (!p) continue;
        // Skip the floor hidden by the box (box half-diagonal 0.087 at height ≤ 0.21, seen from 1 m).
        if (glm::length(glm::vec2(p->x - 0.05f, p->z + 0.03f)) < 0.15f) continue;
        const glm::vec3 want = evaluate(baked.field, pl, c, *p, glm::vec3(0, 1, 0), floor.albedo);
        const std::size_t i = (std::size_t(y) * kW + x) * 3;
        const glm::vec3 got(rgb[i], rgb[i + 1], rgb[i + 2]);
        largest = std::max(largest, glm::length(want));
        for (int ch = 0; ch < 3; ++ch) {
          const float err = std::abs(got[ch] - want[ch]);
          worst = std::max(worst, err);
          worstRatio = std::max(worstRatio, err / (filterBound[ch] + kHalfRel * std::abs(want[ch])));
        }
        ++compared;
      }
    std::printf("dnrt shader vs CPU, %d SH: %d floor pixels, largest |L_DNRT| %.4f, worst |difference| %.2g = %.2f of "
                "its bound (fp16 bound %.2g %.2g %.2g)\n",
                shCount, compared, largest, worst, worstRatio, filterBound.x, filterBound.y, filterBound.z);
    EXPECT_GT(compared, 5000);
    EXPECT_GT(largest, 0.01f);
    EXPECT_LE(worstRatio, 1.0f) << shCount << " SH";
  }
}

// The level path (Runtime: bake through the cache, upload, pack the drawn objects each frame) and
// the hard case of overlapping volumes: two objects' terms add (blending is additive), so the
// frame with both equals the sum of the frames with each alone.
TEST(DnrtGpu, RuntimeBakesThroughTheCacheAndOverlappingObjectsAdd) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path levelPath = fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/two-boxes.json";
  game::Session session(ctx, game::loadLevelWithEffects(levelPath, std::nullopt));
  session.update(0.0);
  ref::ReferenceAssets assets;
  assets.load(session.registry(), fs::path(BOUNCE_TEST_OUT) / "dnrt" / "cooked");
  const fs::path cache = fs::path(BOUNCE_TEST_OUT) / "dnrt" / "runtime-cache";
  fs::remove_all(cache);
  const auto frames = gpu::FrameRing::kDefaultFramesInFlight;
  {
    Runtime first(ctx, session.renderer().pipelines(), session.registry(), assets, cache, frames);
    EXPECT_EQ(first.objectCount(), 2u);
    EXPECT_EQ(first.bakedCount(), 2u);
  }
  Runtime dnrt(ctx, session.renderer().pipelines(), session.registry(), assets, cache, frames,
               session.level().background);
  EXPECT_EQ(dnrt.bakedCount(), 0u);  // both from the cache
  ASSERT_EQ(dnrt.objectCount(), 2u);
  EXPECT_EQ(dnrt.field(1).settings.shCount, 9);

  session.renderer().setNode("dnrt", dnrt.node());
  const Frame both = renderOnce(session, ctx);
  EXPECT_NE(std::find(both.passes.begin(), both.passes.end(), "dnrt"), both.passes.end());
  const std::vector<NodeObject> all = dnrt.objectsFor(session.world());
  ASSERT_EQ(all.size(), 2u);
  Node node(ctx, session.renderer().pipelines(), frames);
  std::vector<float> alone[2];
  for (int k = 0; k < 2; ++k) {
    session.renderer().setNode("dnrt", [&](rg::RenderGraph& graph, render::PassContext& pc) {
      node.addTo(graph, pc, {all[std::size_t(k)]});
    });
    alone[k] = renderOnce(session, ctx).rgb;
  }
  // Each object's own pixels are skipped (gbuffer.entity). For these convex boxes that changes
  // nothing: their own surfaces face away from o, so (n_o·n_r)₊ = 0 there already (the skip is for
  // concave objects, whose inner faces see o through the filled interior values).
  std::vector<NodeObject> anonymous = all;
  for (NodeObject& o : anonymous) o.data.ids = glm::uvec4(0u);
  session.renderer().setNode("dnrt", [&](rg::RenderGraph& graph, render::PassContext& pc) {
    node.addTo(graph, pc, anonymous);
  });
  const std::vector<float> selfLit = renderOnce(session, ctx).rgb;
  int ownPixels = 0;
  for (std::size_t i = 0; i < both.rgb.size(); ++i) ownPixels += selfLit[i] != both.rgb[i] ? 1 : 0;
  EXPECT_EQ(ownPixels, 0);

  float largest = 0.0f, worst = 0.0f;
  int overlap = 0;
  for (std::size_t i = 0; i < both.rgb.size(); ++i) {
    largest = std::max(largest, std::abs(both.rgb[i]));
    worst = std::max(worst, std::abs(both.rgb[i] - alone[0][i] - alone[1][i]));
    overlap += alone[0][i] != 0.0f && alone[1][i] != 0.0f ? 1 : 0;
  }
  std::printf("two objects: %d overlapping channel values, largest |L| %.4f, worst |both - a - b| %.2g\n", overlap,
              largest, worst);
  EXPECT_GT(overlap, 1000);
  EXPECT_GT(largest, 0.005f);
  EXPECT_LE(worst, 2.0f * kHalfTol * largest);  // fp16 rounding of each of the frames

  // Intrusion (§5.2.3): box B stands between box A's centre and part of the floor. With A's
  // intrusion map, that part loses A's term entirely; nothing else changes.
  std::vector<NodeObject> a = {all[0]}, aIntrusion = {all[0]};
  aIntrusion[0].intrusion = true;
  std::vector<float> frames2[2];
  for (int k = 0; k < 2; ++k) {
    session.renderer().setNode("dnrt", [&](rg::RenderGraph& graph, render::PassContext& pc) {
      node.addTo(graph, pc, k == 0 ? a : aIntrusion);
    });
    const Frame f = renderOnce(session, ctx);
    frames2[k] = f.rgb;
    if (k == 1) {
      EXPECT_NE(std::find(f.passes.begin(), f.passes.end(), "dnrt.cube/box-a"), f.passes.end());
    }
  }
  int hidden = 0, kept = 0, other = 0;
  for (std::size_t i = 0; i < frames2[0].size(); ++i) {
    if (frames2[0][i] == 0.0f) continue;
    if (frames2[1][i] == 0.0f) ++hidden;
    else if (frames2[1][i] == frames2[0][i]) ++kept;
    else ++other;
  }
  std::printf("intrusion: %d channel values hidden by box B, %d kept, %d changed otherwise\n", hidden, kept, other);
  EXPECT_GT(hidden, 30);
  EXPECT_GT(kept, 10 * hidden);
  EXPECT_EQ(other, 0);
}

// Hard case: many objects over one pixel. Ten copies of box A at the same place (ten draws, ten
// additive blends into the same fp16 pixels) must add up to ten times one copy: finite, bounded,
// and equal within the rounding of the blends.
TEST(DnrtGpu, TenObjectsOverOnePixelAddUpToTenTimesOne) {
  constexpr int kCopies = 10;
  TwoBoxes boxes("many-cache");
  gpu::Context& ctx = boxes.ctx;
  game::Session& session = boxes.session;
  const std::vector<NodeObject>& all = boxes.objects;
  ASSERT_EQ(all.size(), 2u);
  Node& node = boxes.node;
  const auto renderWith = [&](std::vector<NodeObject> objects) {
    session.renderer().setNode("dnrt", [&, objects](rg::RenderGraph& graph, render::PassContext& pc) {
      node.addTo(graph, pc, objects);
    });
    return renderOnce(session, ctx).rgb;
  };
  std::vector<NodeObject> copies;
  for (int k = 0; k < kCopies; ++k) {
    copies.push_back(all[0]);
    copies.back().name = "box-a-" + std::to_string(k);  // one timestamp scope each
  }
  const std::vector<float> one = renderWith({all[0]}), many = renderWith(copies);
  session.renderer().setNode("dnrt", {});
  const std::vector<float> base = renderOnce(session, ctx).rgb;
  ASSERT_EQ(one.size(), many.size());
  // Each blend rounds the running sum to fp16 (relative 2^-11 of |base + k·v| after the k-th), and
  // `one` carries one such rounding: |many − base − N(one − base)| ≤ 2^-11 (N (|base| + N |v|) +
  // N (|base| + |v|)), with a factor 2 for the rounding of the blend's inputs.
  constexpr float kHalfUlp = 1.0f / 2048.0f;
  float largest = 0.0f, worstRatio = 0.0f;
  int covered = 0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    ASSERT_TRUE(std::isfinite(many[i])) << i;
    const float v = one[i] - base[i], got = many[i] - base[i], want = float(kCopies) * v;
    const float bound = 2.0f * kHalfUlp * kCopies * (2.0f * std::abs(base[i]) + (kCopies + 1) * std::abs(v)) + 1e-7f;
    worstRatio = std::max(worstRatio, std::abs(got - want) / bound);
    largest = std::max(largest, std::abs(got));
    covered += v != 0.0f ? 1 : 0;
  }
  std::printf("%d copies: %d channel values covered, largest |sum| %.4f, worst error %.2f of its fp16 bound\n", kCopies,
              covered, largest, worstRatio);
  EXPECT_GT(covered, 1000);
  EXPECT_GT(largest, 0.01f);
  EXPECT_LE(worstRatio, 1.0f);
}

// Records a copy of all of `from` (mip 0, layer 0, colour) over `to`, which has the same size and a
// format of the same texel size; the graph has put `from` in TRANSFER_SRC and `to` in TRANSFER_DST.
// The only image-to-image copies in the tests and engine are the two below.
void copyWholeImage(VkCommandBuffer cmd, const gpu::Image& from, const gpu::Image& to) {
  VkImageCopy region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.extent = {from.desc().width, from.desc().height, 1};
  vkCmdCopyImage(cmd, from.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to.handle(),
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
}

// Copies of this frame's "gbuffer.normal" (RGBA16F) and "gbuffer.entity" (R32_UINT), taken by a
// transfer pass the test adds to the graph ahead of the node (the targets are transients), for
// checking the normal's w encoding (shaders/common/gbuffer.glsl) texel by texel.
struct GBufferCopy {
  std::unique_ptr<gpu::Image> normal, entity;

  // extent: the frame's (renderOnce's presenter).
  void addTo(rg::RenderGraph& graph, const render::PassContext& pc, VkExtent2D extent) {
    rg::Blackboard& bb = graph.blackboard();
    const auto src = bb.get<rg::Texture>("gbuffer.normal");
    const rg::TextureDesc nd{extent.width, extent.height, 1, 1, 1, rg::Format::RGBA16F, false};
    const auto make = [&](std::unique_ptr<gpu::Image>& img, VkFormat format, const char* name) {
      if (img) return;
      gpu::ImageDesc d;
      d.width = nd.width;
      d.height = nd.height;
      d.format = format;
      d.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
      d.name = name;
      img = std::make_unique<gpu::Image>(*pc.gpu, d);
    };
    make(normal, VK_FORMAT_R16G16B16A16_SFLOAT, "test.normal-copy");
    make(entity, VK_FORMAT_R32_UINT, "test.entity-copy");
    // Imported fresh each frame with their tracked layout: Undefined, or TransferSrc after a frame.
    const auto state = [](const gpu::Image& img) {
      rg::ResourceState s;
      if (img.layout() != VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL) return s;
      s.layout = rg::Layout::TransferSrc;
      s.stages = rg::Stage::Transfer;
      s.access = rg::Access::TransferWrite;
      return s;
    };
    auto nDst = graph.importTexture("test.normal-copy", nd, state(*normal), pc.backend->importImage(*normal));
    rg::TextureDesc ed = nd;
    ed.format = rg::Format::R32_UINT;
    auto eDst = graph.importTexture("test.entity-copy", ed, state(*entity), pc.backend->importImage(*entity));
    struct Data {
      rg::Handle<rg::Texture> normal, entity, normalOut, entityOut;
    };
    const render::PassContext* p = &pc;
    const auto& data = graph.addPass<Data>(
        "test.gbuffer-copy",
        [&](rg::Builder& b, Data& d) {
          d.normal = b.read(src, rg::Usage::TransferSrc);
          d.entity = b.read(bb.get<rg::Texture>("gbuffer.entity"), rg::Usage::TransferSrc);
          d.normalOut = b.write(nDst, rg::Usage::TransferDst);
          d.entityOut = b.write(eDst, rg::Usage::TransferDst);
        },
        [p](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
          VkCommandBuffer cmd = p->cmd(c);
          const auto copy = [&](rg::Handle<rg::Texture> from, rg::Handle<rg::Texture> to) {
            copyWholeImage(cmd, p->backend->image(res.texture(from)), p->backend->image(res.texture(to)));
          };
          copy(d.normal, d.normalOut);
          copy(d.entity, d.entityOut);
        });
    graph.markOutput(data.normalOut, rg::Usage::TransferSrc);
    graph.markOutput(data.entityOut, rg::Usage::TransferSrc);
  }
};

// Replaces "gbuffer.normal" after the lighting pass, ahead of the node, by `image` (RGBA16F, the
// frame's size, uploaded in TRANSFER_SRC layout): a transfer pass copies it over the target and puts
// the new version on the blackboard, so the node reads it. Lighting has already read the original.
struct NormalOverride {
  std::unique_ptr<gpu::Image> image;

  void addTo(rg::RenderGraph& graph, const render::PassContext& pc, VkExtent2D extent) {
    rg::Blackboard& bb = graph.blackboard();
    const rg::TextureDesc nd{extent.width, extent.height, 1, 1, 1, rg::Format::RGBA16F, false};
    rg::ResourceState state;  // after upload(…, TRANSFER_SRC_OPTIMAL), or after the last frame's copy
    state.layout = rg::Layout::TransferSrc;
    state.stages = rg::Stage::Transfer;
    state.access = rg::Access::TransferWrite;
    auto src = graph.importTexture("test.normal-override", nd, state, pc.backend->importImage(*image));
    struct Data {
      rg::Handle<rg::Texture> src, normal;
    };
    const render::PassContext* p = &pc;
    const auto& data = graph.addPass<Data>(
        "test.normal-override",
        [&](rg::Builder& b, Data& d) {
          d.src = b.read(src, rg::Usage::TransferSrc);
          d.normal = b.write(bb.get<rg::Texture>("gbuffer.normal"), rg::Usage::TransferDst);
        },
        [p](const Data& d, const rg::PassResources& res, rg::CommandContext& c) {
          copyWholeImage(p->cmd(c), p->backend->image(res.texture(d.src)),
                         p->backend->image(res.texture(d.normal)));
        });
    bb.put("gbuffer.normal", data.normal);
  }
};

// The self test (dnrt.frag): a draw gives no light to pixels whose entity is the object's own. Box A
// of two-boxes.json is given the floor's entity id + 1 as its own, so the floor pixels A lights must
// lose A's term exactly (equal to the image without DNRT, bit for bit) while box B's faces towards A
// keep it and no other pixel changes; the id read from the normal's w (gbuffer.glsl, ids ≤ kEntityInNormalMax)
// and the gbuffer.entity fetch (NodeSettings::selfInNormal off, the path of larger ids) must give
// the same image, in each draw mode (box, full screen, clustered). Equal images alone would also hold
// if both settings took the fetch, so the test also checks the encoding texel by texel (w against a
// copy of gbuffer.entity) and which path ran (the normal's w zeroed after lighting: only the w path
// stops rejecting), and does the same for a clustered batch of two (the loop path, not kSingle).
TEST(DnrtGpu, SelfTestFromTheNormalsWRejectsExactlyTheObjectsOwnPixels) {
  TwoBoxes boxes("self-cache");
  gpu::Context& ctx = boxes.ctx;
  game::Session& session = boxes.session;
  const std::vector<NodeObject>& all = boxes.objects;
  ASSERT_EQ(all.size(), 2u);
  std::uint32_t floorId = 0;  // entity index + 1 (gbuffer.entity's encoding)
  session.registry().view<scene::Name>().each([&](ecs::Entity e, scene::Name& n) {
    if (n.id == "floor") floorId = e.index() + 1u;
  });
  ASSERT_NE(floorId, 0u);
  ASSERT_LE(floorId, render::kEntityInNormalMax);
  Node& node = boxes.node;
  const auto renderWith = [&](NodeObject object, NodeSettings settings) {
    session.renderer().setNode("dnrt", [&, object, settings](rg::RenderGraph& graph, render::PassContext& pc) {
      node.addTo(graph, pc, {object}, settings);
    });
    return renderOnce(session, ctx).rgb;
  };
  // The encoding the w path relies on, texel by texel: w = float(min(gbuffer.entity, kEntityInNormalMax + 1))
  // (gbuffer.frag; gbuffer.entity = entity index + 1, 0 = background, whose cleared w is 0 too).
  NormalOverride zeroW;  // this frame's normals with w = 0 everywhere ("no entity" for the w path)
  {
    GBufferCopy copy;
    NodeObject a = all[0];
    a.data.ids.x = floorId;
    session.renderer().setNode("dnrt", [&, a](rg::RenderGraph& graph, render::PassContext& pc) {
      copy.addTo(graph, pc, {160, 120});
      node.addTo(graph, pc, {a});
    });
    renderOnce(session, ctx);
    const std::vector<std::uint8_t> normalBytes = gpu::readback(ctx, *copy.normal);
    const std::vector<std::uint8_t> entityBytes = gpu::readback(ctx, *copy.entity);
    constexpr std::size_t kPixels = 160 * 120;
    ASSERT_EQ(normalBytes.size(), kPixels * 8);
    ASSERT_EQ(entityBytes.size(), kPixels * 4);
    int mismatched = 0, drawn = 0, floorPixels = 0;
    std::set<std::uint32_t> ids;
    for (std::size_t i = 0; i < kPixels; ++i) {
      std::uint16_t h;
      std::memcpy(&h, &normalBytes[i * 8 + 6], 2);
      std::uint32_t entity;
      std::memcpy(&entity, &entityBytes[i * 4], 4);
      const float w = gpu::halfToFloat(h);
      const float want = float(std::min(entity, render::kEntityInNormalMax + 1u));
      if (w != want && mismatched++ < 5)
        ADD_FAILURE() << "pixel " << i << ": normal's w " << w << ", gbuffer.entity " << entity << " (expected w " << want
                      << ")";
      drawn += entity != 0u ? 1 : 0;
      floorPixels += entity == floorId ? 1 : 0;
      ids.insert(entity);
    }
    std::printf("normal's w: %d of %zu pixels differ from min(gbuffer.entity, %u); %d drawn, %d on the floor, %zu ids\n",
                mismatched, kPixels, render::kEntityInNormalMax + 1u, drawn, floorPixels, ids.size());
    EXPECT_EQ(mismatched, 0);
    EXPECT_GT(floorPixels, 1000);   // the check covers the id the self test below compares
    EXPECT_GT(drawn, floorPixels);  // and other entities' ids (the boxes)
    EXPECT_GE(ids.size(), 3u);      // the floor and both boxes at least
    std::vector<std::uint8_t> zeroed = normalBytes;
    for (std::size_t i = 0; i < kPixels; ++i) zeroed[i * 8 + 6] = zeroed[i * 8 + 7] = 0;  // fp16 +0
    gpu::ImageDesc d;
    d.width = 160;
    d.height = 120;
    d.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    d.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    d.name = "test.normal-override";
    zeroW.image = std::make_unique<gpu::Image>(ctx, d);
    gpu::upload(ctx, *zeroW.image, zeroed, 0, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  }
  // Which path a draw took, seen in the image: with the normal's w zeroed after lighting (xyz kept),
  // the w path finds no own pixel (A's image without an own id), the gbuffer.entity fetch still
  // rejects the floor. So the w variant is the one used with selfInNormal on, and the fetch with it off.
  const auto renderZeroW = [&](NodeObject object, NodeSettings settings) {
    session.renderer().setNode("dnrt", [&, object, settings](rg::RenderGraph& graph, render::PassContext& pc) {
      zeroW.addTo(graph, pc, {160, 120});
      node.addTo(graph, pc, {object}, settings);
    });
    return renderOnce(session, ctx).rgb;
  };
  session.renderer().setNode("dnrt", {});
  const std::vector<float> without = renderOnce(session, ctx).rgb;
  for (const Mode mode : {Mode::Box, Mode::FullScreen, Mode::Clustered}) {
    NodeSettings normalW, entityImage;
    normalW.mode = entityImage.mode = mode;
    entityImage.selfInNormal = false;
    NodeObject a = all[0];
    a.data.ids.x = 0u;  // no own pixels
    const std::vector<float> anonymous = renderWith(a, normalW);
    a.data.ids.x = floorId;  // the floor's pixels count as A's own
    const std::vector<float> fromNormal = renderWith(a, normalW), fromEntity = renderWith(a, entityImage);
    ASSERT_EQ(fromNormal.size(), without.size());
    EXPECT_EQ(fromNormal, fromEntity) << "normal's w and gbuffer.entity reject the same pixels";
    EXPECT_EQ(renderZeroW(a, normalW), anonymous) << "selfInNormal on: the self test reads the normal's w";
    EXPECT_EQ(renderZeroW(a, entityImage), fromEntity) << "selfInNormal off: the self test fetches gbuffer.entity";
    int lit = 0, rejected = 0, otherwise = 0;
    for (std::size_t i = 0; i < without.size(); ++i) {
      if (anonymous[i] == without[i]) {
        otherwise += fromNormal[i] != without[i] ? 1 : 0;  // unlit by A: stays unlit
        continue;
      }
      ++lit;
      if (fromNormal[i] == anonymous[i]) continue;  // not the floor's: keeps A's term
      if (fromNormal[i] == without[i]) ++rejected;  // the floor's: A's term gone, exactly
      else ++otherwise;
    }
    std::printf("self test (mode %d): %d channel values lit by A, %d of them on the floor rejected, %d changed "
                "otherwise\n", int(mode), lit, rejected, otherwise);
    EXPECT_GT(rejected, 1000);  // the floor around A at 160×120
    EXPECT_GT(lit, rejected);   // box B's faces towards A keep A's term (21 channel values, measured)
    EXPECT_EQ(otherwise, 0);
  }
  // The clustered loop path (two objects in one batch: clustered.frag's loop over the batch, not kSingle):
  // A (the floor's id) and B (its own id) with the w path on and off give the same image bit for bit,
  // and with w zeroed the w path rejects nothing (the image of both without an own id) while the fetch
  // still does.
  const auto renderSet = [&](std::vector<NodeObject> objects, NodeSettings settings, bool zeroed) {
    session.renderer().setNode("dnrt", [&, objects, settings, zeroed](rg::RenderGraph& graph, render::PassContext& pc) {
      if (zeroed) zeroW.addTo(graph, pc, {160, 120});
      node.addTo(graph, pc, objects, settings);
    });
    return renderOnce(session, ctx).rgb;
  };
  NodeSettings on, off;
  on.mode = off.mode = Mode::Clustered;
  off.selfInNormal = false;
  NodeObject a = all[0], b = all[1];
  ASSERT_NE(b.data.ids.x, 0u);
  ASSERT_LE(b.data.ids.x, render::kEntityInNormalMax);
  a.data.ids.x = floorId;
  NodeObject a0 = a, b0 = b;
  a0.data.ids.x = b0.data.ids.x = 0u;
  const std::vector<float> anonymous = renderSet({a0, b0}, on, false);
  const std::vector<float> fromNormal = renderSet({a, b}, on, false), fromEntity = renderSet({a, b}, off, false);
  EXPECT_EQ(fromNormal, fromEntity) << "clustered batch of two: normal's w and gbuffer.entity reject the same pixels";
  int differ = 0;
  for (std::size_t i = 0; i < anonymous.size(); ++i) differ += fromNormal[i] != anonymous[i] ? 1 : 0;
  std::printf("clustered pair: %d channel values rejected as own\n", differ);
  EXPECT_GT(differ, 1000);  // A's term on the floor at least
  EXPECT_EQ(renderSet({a, b}, on, true), anonymous) << "clustered pair, selfInNormal on: reads the normal's w";
  EXPECT_EQ(renderSet({a, b}, off, true), fromEntity) << "clustered pair, selfInNormal off: fetches gbuffer.entity";
}

// Issue 15's clustered mode against the per-object box draws: box A (4 SH) and box B (9 SH) of
// two-boxes.json, so the atlas mixes 3- and 7-slot fields; each alone (the one-object pipeline); then 34 objects, two batches of the
// clustered draw (32 + 2). The images agree within kClusteredTolerance per channel value:
// - fp16: the box draws blend once per object (each rounding the running sum, relative 2^-11),
//   the clustered draw once per batch;
// - filtering: an atlas brick is sampled at other coordinates than its own texture (other float
//   rounding), and llvmpipe rounds a filtered UNORM8 value to 8 bits, so a slot's fetch may move by
//   one step: |k_slot| / 255 per component (ρ_r (n_o·n_r)₊ s ≤ 1), per object.
// The executed passes are exactly the box mode's (no pass is added; culling is unchanged).
TEST(DnrtGpu, ClusteredModeDrawsThePerObjectImage) {
  TwoBoxes boxes("clustered-cache");
  gpu::Context& ctx = boxes.ctx;
  game::Session& session = boxes.session;
  const std::vector<NodeObject>& all = boxes.objects;
  ASSERT_EQ(all.size(), 2u);
  ASSERT_NE(all[0].data.extents.z, all[1].data.extents.z) << "one 4-SH and one 9-SH field";
  Node& node = boxes.node;
  const auto renderWith = [&](std::vector<NodeObject> objects, std::optional<Mode> mode) {
    session.renderer().setNode("dnrt", [&, objects, mode](rg::RenderGraph& graph, render::PassContext& pc) {
      node.addTo(graph, pc, objects, NodeSettings{mode});
    });
    return renderOnce(session, ctx);
  };
  session.renderer().setNode("dnrt", {});
  const std::vector<float> base = renderOnce(session, ctx).rgb;

  // Box A alone and box B alone (a one-object batch: clustered.frag's kSingle pipeline, record 0 as
  // uniforms, no loops), then both, then 17 copies of both.
  std::vector<std::vector<NodeObject>> sets = {{all[0]}, {all[1]}};
  for (const int copies : {1, 17}) {
    sets.emplace_back();
    for (int k = 0; k < copies; ++k)
      for (const NodeObject& o : all) {
        sets.back().push_back(o);
        sets.back().back().name = o.name + "-" + std::to_string(k);
      }
  }
  for (const std::vector<NodeObject>& objects : sets) {
    float filterStep = 0.0f;  // Σ_objects Σ_slots |k| / 255
    for (const NodeObject& o : objects) {
      const DnrtShaderObject f = fold(o.data);
      for (const glm::vec4& kt : f.k) filterStep += (std::abs(kt.x) + std::abs(kt.y) + std::abs(kt.z) + std::abs(kt.w)) / 255.0f;
    }
    const Frame box = renderWith(objects, std::nullopt), clustered = renderWith(objects, Mode::Clustered);
    EXPECT_EQ(clustered.passes, box.passes) << "the same passes, culled the same";
    ASSERT_EQ(box.rgb.size(), clustered.rgb.size());
    const float n = float(objects.size());
    constexpr float kHalfUlp = 1.0f / 2048.0f;
    float largest = 0.0f, worstRatio = 0.0f;
    int covered = 0, equal = 0;
    for (std::size_t i = 0; i < box.rgb.size(); ++i) {
      ASSERT_TRUE(std::isfinite(clustered.rgb[i])) << i;
      const float v = box.rgb[i] - base[i];
      // kClusteredTolerance: n + 2 fp16 roundings of at most |base| + |v| plus the filtering steps.
      const float tolerance = (n + 2.0f) * kHalfUlp * (std::abs(base[i]) + 2.0f * std::abs(v)) + filterStep + 1e-7f;
      worstRatio = std::max(worstRatio, std::abs(clustered.rgb[i] - box.rgb[i]) / tolerance);
      largest = std::max(largest, std::abs(v));
      covered += v != 0.0f ? 1 : 0;
      equal += clustered.rgb[i] == box.rgb[i] ? 1 : 0;
    }
    std::printf("clustered vs box, %zu objects: %d channel values covered, %d of %zu equal, largest |L| %.4f, worst "
                "difference %.3f of its tolerance (filter step %.2g)\n",
                objects.size(), covered, equal, box.rgb.size(), largest, worstRatio, filterStep);
    EXPECT_GT(covered, 1000);
    EXPECT_GT(largest, 0.005f);
    EXPECT_LE(worstRatio, 1.0f);
    // And as a whole: within 1 % of the largest term (measured: 0.06 % for 2 objects, 0.6 % for 34,
    // the fp16 roundings of 34 blends), so a misplaced brick or a missed tile would show.
    float worstAbs = 0.0f;
    for (std::size_t i = 0; i < box.rgb.size(); ++i) worstAbs = std::max(worstAbs, std::abs(clustered.rgb[i] - box.rgb[i]));
    EXPECT_LE(worstAbs, 0.01f * largest) << objects.size() << " objects";
  }
}


// The fused mode ("dnrt": {"mode": "fused"}): the probes pass adds the object's term (probes.frag
// kDnrt) instead of a "dnrt" pass. floor-box.json with the probes, 160×120:
// - structure: the passes are the box mode's without "dnrt", its "dnrt.combine.fused" before "probes";
//   without the probes effect the object is drawn as a box (the box mode's passes); without the dnrt
//   effect neither DNRT pass runs;
// - image: the box mode's within fp16 rounding. The box mode rounds lighting.hdr after the probes'
//   blend and after DNRT's, the fused mode once after their fp32 sum, so a channel value moves by at
//   most those roundings: half-ulps (2⁻¹¹ relative each) of |probesOnly| + 2|box|;
// - two objects asking for fused (two-boxes.json): both in the probes pass through the tile masks
//   (kDnrt 2), no "dnrt" pass; the image the clustered mode's within the same fp16 bound, and the box
//   mode's within 1 % of the largest term.
TEST(DnrtGpu, FusedModeIsTheBoxImageInsideTheProbesPass) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const auto render = [&](std::vector<std::string> effects, Mode mode, const char* file = "floor-box.json") {
    scene::Level level = game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt" / file, effects);
    for (auto& e : level.entities)
      if (e.dnrt) e.dnrt->mode = mode;
    game::Session session(ctx, std::move(level));
    session.update(0.0);
    return renderOnce(session, ctx);
  };
  const std::vector<std::string> all = {"direct", "probes", "dnrt"};
  const Frame box = render(all, Mode::Box), fused = render(all, Mode::Fused);
  const Frame probesOnly = render({"direct", "probes"}, Mode::Fused);
  const auto at = [](const Frame& f, const char* pass) {
    return std::find(f.passes.begin(), f.passes.end(), pass) - f.passes.begin();
  };
  ASSERT_LT(at(box, "dnrt"), std::ptrdiff_t(box.passes.size())) << "the box mode draws";
  std::vector<std::string> expected;
  for (const std::string& p : box.passes) {
    if (p == "dnrt" || p == "dnrt.combine") continue;
    if (p == "probes") expected.push_back("dnrt.combine.fused");
    expected.push_back(p);
  }
  EXPECT_EQ(fused.passes, expected);
  EXPECT_EQ(render({"direct", "dnrt"}, Mode::Fused).passes, render({"direct", "dnrt"}, Mode::Box).passes)
      << "without the probes pass the fused object is drawn as a box";
  EXPECT_EQ(std::count(probesOnly.passes.begin(), probesOnly.passes.end(), "dnrt.combine"), 0);
  EXPECT_EQ(std::count(probesOnly.passes.begin(), probesOnly.passes.end(), "dnrt.combine.fused"), 0);
  EXPECT_EQ(std::count(probesOnly.passes.begin(), probesOnly.passes.end(), "dnrt"), 0);

  ASSERT_EQ(fused.rgb.size(), box.rgb.size());
  ASSERT_EQ(probesOnly.rgb.size(), box.rgb.size());
  constexpr float kHalfUlp = 1.0f / 2048.0f;
  float largest = 0.0f, worstRatio = 0.0f, worstAbs = 0.0f;
  int covered = 0, equal = 0;
  for (std::size_t i = 0; i < box.rgb.size(); ++i) {
    ASSERT_TRUE(std::isfinite(fused.rgb[i])) << i;
    const float term = box.rgb[i] - probesOnly.rgb[i];  // DNRT's term (box mode)
    // Box: lighting.hdr rounded after the probes' blend (≈ probesOnly) and after DNRT's (≈ box); fused:
    // once, after their sum (≈ box). So |fused − box| ≤ half-ulp · (|probesOnly| + 2|box|), whatever
    // the term's sign (the clustered test's bound above).
    const float tolerance = kHalfUlp * (std::abs(probesOnly.rgb[i]) + 2.0f * std::abs(box.rgb[i])) + 1e-7f;
    worstRatio = std::max(worstRatio, std::abs(fused.rgb[i] - box.rgb[i]) / tolerance);
    worstAbs = std::max(worstAbs, std::abs(fused.rgb[i] - box.rgb[i]));
    largest = std::max(largest, std::abs(term));
    covered += term != 0.0f ? 1 : 0;
    equal += fused.rgb[i] == box.rgb[i] ? 1 : 0;
  }
  std::printf("fused vs box: %d channel values carry DNRT's term, %d of %zu equal, largest |term| %.4f, worst "
              "difference %.3g (%.3f of its tolerance)\n",
              covered, equal, box.rgb.size(), largest, worstAbs, worstRatio);
  EXPECT_GT(covered, 1000);
  EXPECT_GT(largest, 0.005f);
  EXPECT_LE(worstRatio, 1.0f);

  // Two objects asking for fused (two-boxes.json, a 4-SH and a 9-SH field): both go into the probes pass
  // (probes.frag kDnrt 2, the clustered mode's visit of the pixel's tile mask) — one "dnrt.combine.fused"
  // before "probes" and no "dnrt" or "dnrt.combine" pass: the box mode's passes without those two.
  const Frame twoBox = render(all, Mode::Box, "two-boxes.json");
  const Frame twoFused = render(all, Mode::Fused, "two-boxes.json");
  const Frame twoClustered = render(all, Mode::Clustered, "two-boxes.json");
  const Frame twoProbes = render({"direct", "probes"}, Mode::Fused, "two-boxes.json");
  std::vector<std::string> twoExpected;
  for (const std::string& p : twoBox.passes) {
    if (p == "dnrt" || p == "dnrt.combine") continue;
    if (p == "probes") twoExpected.push_back("dnrt.combine.fused");
    twoExpected.push_back(p);
  }
  EXPECT_EQ(twoFused.passes, twoExpected);
  ASSERT_EQ(twoFused.rgb.size(), twoBox.rgb.size());
  ASSERT_EQ(twoClustered.rgb.size(), twoBox.rgb.size());
  ASSERT_EQ(twoProbes.rgb.size(), twoBox.rgb.size());
  // Against the clustered mode: the same atlas bricks, records, taps and per-pixel sum (dnrt/cluster.glsl)
  // in fp32; the clustered draw blends that sum onto the probes' rounded output, the fused pass blends
  // probes + sum once. So, as above, |fused − clustered| ≤ half-ulp · (|probesOnly| + 2|clustered|).
  // Against the box mode: within 1 % of the largest term, as the clustered test (one blend per object
  // there), so a term dropped, doubled or put on the wrong object would show.
  float twoLargest = 0.0f, twoWorst = 0.0f, twoRatio = 0.0f;
  int twoCovered = 0;
  for (std::size_t i = 0; i < twoBox.rgb.size(); ++i) {
    ASSERT_TRUE(std::isfinite(twoFused.rgb[i])) << i;
    const float term = twoClustered.rgb[i] - twoProbes.rgb[i];
    twoLargest = std::max(twoLargest, std::abs(twoBox.rgb[i] - twoProbes.rgb[i]));
    twoWorst = std::max(twoWorst, std::abs(twoFused.rgb[i] - twoBox.rgb[i]));
    const float tolerance = kHalfUlp * (std::abs(twoProbes.rgb[i]) + 2.0f * std::abs(twoClustered.rgb[i])) + 1e-7f;
    twoRatio = std::max(twoRatio, std::abs(twoFused.rgb[i] - twoClustered.rgb[i]) / tolerance);
    twoCovered += term != 0.0f ? 1 : 0;
  }
  std::printf("two boxes, both fused: %d channel values carry a term, largest |term| %.4f, worst difference to box "
              "%.3g, to clustered %.3f of its tolerance\n",
              twoCovered, twoLargest, twoWorst, twoRatio);
  EXPECT_GT(twoCovered, 1000);
  EXPECT_GT(twoLargest, 0.005f);
  EXPECT_LE(twoRatio, 1.0f);
  EXPECT_LE(twoWorst, 0.01f * twoLargest);

  const auto count = [](const Frame& f, const char* pass) { return std::count(f.passes.begin(), f.passes.end(), pass); };
  // The probes turned on after DNRT's runtime exists (`bounce play`'s keys): the hook still reaches the
  // probes node (Services::attachFusedDnrt), so the next frame is the fused one, not a box.
  {
    scene::Level level = game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/floor-box.json",
                                                    std::vector<std::string>{"direct", "dnrt"});
    for (auto& e : level.entities)
      if (e.dnrt) e.dnrt->mode = Mode::Fused;
    game::Session session(ctx, std::move(level));
    session.update(0.0);
    EXPECT_EQ(count(renderOnce(session, ctx), "dnrt"), 1) << "no probes yet: a box";
    session.level().effects.add(scene::Effect::Probes);
    const Frame later = renderOnce(session, ctx);
    EXPECT_EQ(later.passes, fused.passes);
  }
}

// The fused mode below full resolution ("dnrt": {"mode": "fused", "resolution": "half"|"quarter"}; README
// "DNRT's fused term at reduced resolution, session 17"): pass "dnrt.fused.reduced" writes the term's
// position-only factor f = s Σ_j c_j M_j at G-buffer pixel step·j and the probes pass takes one bilinear
// tap of it (normalised by the valid samples' weight) times the exact per-pixel (n_o·n_r)₊.
// - structure: the full-resolution fused passes with "dnrt.fused.reduced" between "dnrt.combine.fused"
//   and "probes"; no "dnrt", no "dnrt.upsample";
// - image, on a smooth scene (floor-box.json: a plane under a floating box, whose own samples are the
//   only invalid ones, so no depth edge of two receivers): the term equals the full-resolution fused
//   term within kRmsBound relative RMS and kMaxBound of the largest term at any channel value. What is
//   left is bilinear interpolation of a smooth f over 2 or 4 pixels, the nearest valid samples' f next
//   to the box's silhouette, and f's fp16 rounding. Measured at 160×120 (the printf): the bounds are
//   about 1.7× the measured figures, and leaving the term out would score 1 (rel RMS) and 1 (worst).
TEST(DnrtGpu, FusedModeAtReducedResolutionIsTheFullTermWithinABoundOnASmoothScene) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const auto render = [&](std::vector<std::string> effects, std::uint32_t step) {
    scene::Level level = game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/floor-box.json", effects);
    level.dnrt.step = step;
    for (auto& e : level.entities)
      if (e.dnrt) e.dnrt->mode = Mode::Fused;
    game::Session session(ctx, std::move(level));
    session.update(0.0);
    return renderOnce(session, ctx);
  };
  const std::vector<std::string> all = {"direct", "probes", "dnrt"};
  const Frame full = render(all, 1), probesOnly = render({"direct", "probes"}, 1);
  std::vector<std::string> expected;
  for (const std::string& p : full.passes) {
    if (p == "probes") expected.push_back("dnrt.fused.reduced");
    expected.push_back(p);
  }
  ASSERT_EQ(std::count(full.passes.begin(), full.passes.end(), "dnrt.combine.fused"), 1);
  ASSERT_EQ(full.rgb.size(), probesOnly.rgb.size());
  // half, quarter: measured 0.034 / 0.083 (rel RMS) and 0.125 / 0.289 (worst / largest) at 160×120,
  // where a quarter-resolution sample covers 4×4 of 160×120 pixels (the box is ~25 pixels wide)
  constexpr float kRmsBound[2] = {0.06f, 0.15f};
  constexpr float kMaxBound[2] = {0.25f, 0.5f};
  for (const std::uint32_t step : {2u, 4u}) {
    const Frame reduced = render(all, step);
    EXPECT_EQ(reduced.passes, expected) << "step " << step;
    ASSERT_EQ(reduced.rgb.size(), full.rgb.size());
    double sumSq = 0.0, errSq = 0.0;
    float largest = 0.0f, worst = 0.0f;
    int covered = 0;
    for (std::size_t i = 0; i < full.rgb.size(); ++i) {
      ASSERT_TRUE(std::isfinite(reduced.rgb[i])) << i;
      const float term = full.rgb[i] - probesOnly.rgb[i];
      const float err = reduced.rgb[i] - full.rgb[i];
      sumSq += double(term) * term;
      errSq += double(err) * err;
      largest = std::max(largest, std::abs(term));
      worst = std::max(worst, std::abs(err));
      covered += term != 0.0f ? 1 : 0;
    }
    const double rel = std::sqrt(errSq / sumSq);
    std::printf("fused step %u vs full: %d channel values carry the term, rel RMS %.4f of it, worst %.4g = %.3f of the "
                "largest term %.4f\n",
                step, covered, rel, worst, worst / largest, largest);
    EXPECT_GT(covered, 1000);
    EXPECT_GT(largest, 0.005f);
    EXPECT_LE(rel, kRmsBound[step == 2u ? 0 : 1]) << "step " << step;
    EXPECT_LE(worst, kMaxBound[step == 2u ? 0 : 1] * largest) << "step " << step;
  }
}

// `bounce bench dnrt`'s pass without the term (ProbeNode::setTermBaseline): on a frame with a fused object it
// adds exactly one "probes.baseline" pass, right before "probes" on the first frame and right after it on the
// next (which of the two finds the G-buffer in the caches evens out), and the image is the one without it bit
// for bit (it writes a scratch target nothing reads). Without a fused object (box mode) there is no term to
// time and no extra pass.
TEST(DnrtGpu, TermBaselineIsOnePassBesideTheFusedProbesPassAndLeavesTheImage) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const auto render = [&](Mode mode, bool baseline, int frames) {
    scene::Level level = game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/floor-box.json",
                                                    std::vector<std::string>{"direct", "probes", "dnrt"});
    for (auto& e : level.entities)
      if (e.dnrt) e.dnrt->mode = mode;
    if (mode == Mode::Fused) level.dnrt.step = 4;  // the bench's "fused quarter"
    game::Session session(ctx, std::move(level));
    if (baseline) session.probes()->setTermBaseline(true);
    std::vector<Frame> out;
    for (int f = 0; f < frames; ++f) {
      session.update(f / 60.0);
      out.push_back(renderOnce(session, ctx));
    }
    return out;
  };
  const std::vector<Frame> plain = render(Mode::Fused, false, 2), timed = render(Mode::Fused, true, 2);
  for (int f = 0; f < 2; ++f) {
    std::vector<std::string> expected = plain[f].passes;
    const auto probes = std::find(expected.begin(), expected.end(), "probes");
    ASSERT_NE(probes, expected.end());
    expected.insert(f == 0 ? probes : probes + 1, "probes.baseline");
    EXPECT_EQ(timed[f].passes, expected) << "frame " << f;
    ASSERT_EQ(timed[f].rgb.size(), plain[f].rgb.size());
    int differ = 0;
    for (std::size_t i = 0; i < plain[f].rgb.size(); ++i) differ += timed[f].rgb[i] != plain[f].rgb[i] ? 1 : 0;
    EXPECT_EQ(differ, 0) << "frame " << f << ": the image moved";
  }
  const std::vector<Frame> box = render(Mode::Box, true, 1);
  EXPECT_EQ(std::count(box[0].passes.begin(), box[0].passes.end(), "probes.baseline"), 0) << "no fused term, no baseline";
  EXPECT_EQ(box[0].passes, render(Mode::Box, false, 1)[0].passes);
}

// The probes pass split at the fused object's outer cube (probes::FusedDnrt::split, NodeSettings::splitProbes;
// README "DNRT's fused term only inside its outer cube, session 19"): floor-box.json's camera moved next to
// the box, inside its outer cube, looking down the floor past the cube's far faces, so the pass draws the
// cube's faces twice — the fused pipeline where the surface is not behind the face, the plain one where it
// is. The passes are the unsplit frame's. At full resolution the term is exactly 0 outside the cube
// (s(r) = 0), so the image is the unsplit one bit for bit: no pixel shaded twice or missed, no term lost.
// Below full resolution the node does not split (measured dearer there).
TEST(DnrtGpu, FusedProbesPassSplitAtTheOuterCubeIsTheUnsplitImage) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const auto render = [&](std::vector<std::string> effects, std::uint32_t step, bool split, bool* wasSplit) {
    scene::Level level = game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/floor-box.json", effects);
    level.dnrt.step = step;
    for (auto& e : level.entities) {
      if (e.dnrt) e.dnrt->mode = Mode::Fused;
      if (e.camera) {  // 0.37 m from the box's centre (its outer cube's half-size: 6 R ≈ 0.52 m), 40° down
        e.transform.translation = glm::vec3(0.0f, 0.35f, 0.25f);
        e.transform.rotation = glm::angleAxis(glm::radians(-40.0f), glm::vec3(1.0f, 0.0f, 0.0f));
      }
    }
    game::Session session(ctx, std::move(level));
    if (auto* dnrt = session.technique<SessionRuntime>("dnrt")) dnrt->runtime().settings().splitProbes = split;
    session.update(0.0);
    Frame frame = renderOnce(session, ctx);
    *wasSplit = session.probes()->lastPassSplit();
    return frame;
  };
  const std::vector<std::string> all = {"direct", "probes", "dnrt"};
  bool splitFull = false, unsplitFull = true, splitQuarter = true, probesSplit = true;
  const Frame full = render(all, 1, false, &unsplitFull), fullSplit = render(all, 1, true, &splitFull);
  const Frame probesOnly = render({"direct", "probes"}, 1, true, &probesSplit);
  EXPECT_TRUE(splitFull);
  EXPECT_FALSE(unsplitFull);
  EXPECT_FALSE(probesSplit) << "no fused object, no split";
  EXPECT_EQ(fullSplit.passes, full.passes);
  ASSERT_EQ(fullSplit.rgb.size(), full.rgb.size());
  ASSERT_EQ(probesOnly.rgb.size(), full.rgb.size());
  std::size_t differ = 0, carry = 0;
  for (std::size_t i = 0; i < full.rgb.size(); ++i) {
    differ += fullSplit.rgb[i] != full.rgb[i] ? 1 : 0;
    carry += full.rgb[i] != probesOnly.rgb[i] ? 1 : 0;
  }
  std::printf("split at full resolution: %zu of %zu channel values differ from the unsplit frame; %zu carry the term\n",
              differ, full.rgb.size(), carry);
  EXPECT_EQ(differ, 0u);
  EXPECT_GT(carry, 1000u);

  // Below full resolution the pass is not split (measured dearer: Node::addFused).
  render(all, 4, true, &splitQuarter);
  EXPECT_FALSE(splitQuarter);
}

// The fused term's rule (Runtime::addFused; the level load's warning counts by the same function):
// the fused mode, no intrusion map, and an entity id + 1 the G-buffer normal's w holds (1…2047).
TEST(DnrtFused, EligibleIsTheFusedModeWithoutIntrusionAndAnIdTheNormalHolds) {
  using dnrt::fusedEligible;
  using Mode = dnrt::Mode;
  EXPECT_TRUE(fusedEligible(Mode::Fused, false, 1u));
  EXPECT_TRUE(fusedEligible(Mode::Fused, false, render::kEntityInNormalMax));
  EXPECT_FALSE(fusedEligible(Mode::Fused, false, 0u)) << "no entity: the self test cannot skip its pixels";
  EXPECT_FALSE(fusedEligible(Mode::Fused, false, render::kEntityInNormalMax + 1u)) << "id past the normal's w";
  EXPECT_FALSE(fusedEligible(Mode::Fused, true, 1u)) << "an intrusion map is drawn by the node";
  for (Mode m : {Mode::Box, Mode::Clustered, Mode::FullScreen}) EXPECT_FALSE(fusedEligible(m, false, 1u));
}

// Two fused objects with "resolution": "quarter" (two-boxes.json): the reduced term's position-only
// factor is one object's, so with both in the probes pass (kDnrt 2) the runtime shades them at full
// resolution (Runtime::addFused) — exactly the full-resolution fused frame: its passes (no
// "dnrt.fused.reduced") and its image bit for bit (the same pipelines and inputs) — and the level load
// says so in one warning (counted against the same level at full resolution, whose load warns of
// nothing more).
TEST(DnrtGpu, SeveralFusedObjectsAreShadedAtFullResolutionAndTheLevelLoadSaysSo) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const auto render = [&](std::uint32_t step, std::size_t& warnings) {
    scene::Level level = game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/two-boxes.json",
                                                    std::vector<std::string>{"direct", "probes", "dnrt"});
    level.dnrt.step = step;
    for (auto& e : level.entities)
      if (e.dnrt) e.dnrt->mode = Mode::Fused;
    log::resetWarningCount();
    game::Session session(ctx, std::move(level));
    warnings = log::warningCount();
    session.update(0.0);
    return renderOnce(session, ctx);
  };
  std::size_t fullWarnings = 0, quarterWarnings = 0;
  const Frame full = render(1, fullWarnings);
  const Frame quarter = render(4, quarterWarnings);
  EXPECT_EQ(quarterWarnings, fullWarnings + 1) << "one warning at level load";
  EXPECT_EQ(std::count(full.passes.begin(), full.passes.end(), "dnrt.combine.fused"), 1);
  EXPECT_EQ(std::count(full.passes.begin(), full.passes.end(), "dnrt"), 0) << "both objects in the probes pass";
  EXPECT_EQ(quarter.passes, full.passes);
  ASSERT_EQ(quarter.rgb.size(), full.rgb.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < full.rgb.size(); ++i) differ += quarter.rgb[i] != full.rgb[i] ? 1 : 0;
  EXPECT_EQ(differ, 0u);
}

// The fused mode with an occlusion term: two-boxes-lamp.json's box-a says "lights_in_anti_radiance":
// false, so its combined volume sums its field and its occlusion-only field (−k_j, the lamp's c_j
// negated; combine.comp kOcclusion) — in dnrt.combine for the box mode and in dnrt.combine.fused for
// the probes pass. box-b is left out (one object: the bound of FusedModeIsTheBoxImageInsideTheProbesPass
// holds as it stands, half-ulps of |probesOnly| + 2|box|). The occlusion term must change the image:
// the same object with the lamp in its anti-radiance (no occlusion field) differs by more than the bound.
TEST(DnrtGpu, FusedModeWithAnOcclusionTermIsTheBoxImage) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const auto render = [&](std::vector<std::string> effects, Mode mode, bool lightsIn = false) {
    scene::Level level = game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/two-boxes-lamp.json",
                                                    effects);
    std::erase_if(level.entities, [](const scene::EntityDesc& e) { return e.id == "box-b"; });
    for (auto& e : level.entities)
      if (e.dnrt) {
        EXPECT_FALSE(e.dnrt->lightsInAntiRadiance) << "the level's box-a carries an occlusion term";
        e.dnrt->mode = mode;
        e.dnrt->lightsInAntiRadiance = lightsIn;
      }
    game::Session session(ctx, std::move(level));
    session.update(0.0);
    return renderOnce(session, ctx);
  };
  const std::vector<std::string> all = {"direct", "probes", "dnrt"};
  const Frame box = render(all, Mode::Box), fused = render(all, Mode::Fused);
  const Frame probesOnly = render({"direct", "probes"}, Mode::Fused);
  const Frame lightsIn = render(all, Mode::Fused, true);
  const auto count = [](const Frame& f, const char* pass) { return std::count(f.passes.begin(), f.passes.end(), pass); };
  EXPECT_EQ(count(box, "dnrt"), 1);
  EXPECT_EQ(count(fused, "dnrt"), 0);
  EXPECT_EQ(count(fused, "dnrt.combine.fused"), 1);
  EXPECT_EQ(fused.passes, lightsIn.passes);

  ASSERT_EQ(fused.rgb.size(), box.rgb.size());
  ASSERT_EQ(probesOnly.rgb.size(), box.rgb.size());
  ASSERT_EQ(lightsIn.rgb.size(), box.rgb.size());
  constexpr float kHalfUlp = 1.0f / 2048.0f;
  float largest = 0.0f, worstRatio = 0.0f, worstAbs = 0.0f, occlusionRatio = 0.0f;
  int covered = 0;
  for (std::size_t i = 0; i < box.rgb.size(); ++i) {
    ASSERT_TRUE(std::isfinite(fused.rgb[i])) << i;
    const float term = box.rgb[i] - probesOnly.rgb[i];  // DNRT's term with its occlusion part (box mode)
    const float tolerance = kHalfUlp * (std::abs(probesOnly.rgb[i]) + 2.0f * std::abs(box.rgb[i])) + 1e-7f;
    worstRatio = std::max(worstRatio, std::abs(fused.rgb[i] - box.rgb[i]) / tolerance);
    worstAbs = std::max(worstAbs, std::abs(fused.rgb[i] - box.rgb[i]));
    occlusionRatio = std::max(occlusionRatio, std::abs(lightsIn.rgb[i] - fused.rgb[i]) / tolerance);
    largest = std::max(largest, std::abs(term));
    covered += term != 0.0f ? 1 : 0;
  }
  std::printf("fused vs box with an occlusion term: %d channel values carry DNRT's term, largest |term| %.4f, worst "
              "difference %.3g (%.3f of its tolerance); lamp in the anti-radiance instead: %.1f× the tolerance\n",
              covered, largest, worstAbs, worstRatio, occlusionRatio);
  EXPECT_GT(covered, 1000);
  EXPECT_GT(largest, 0.005f);
  EXPECT_LE(worstRatio, 1.0f);
  EXPECT_GT(occlusionRatio, 10.0f) << "the occlusion term shows in the fused image";
}

// A frame that throws after the probes node handed the fused object to the probes pass
// (Runtime::addFused) and before DNRT's node ran leaves that frame's objects behind; the next frame,
// here one without the probes effect, must not take them (node() takes them only when the graph's
// blackboard has the entry addFused put there, i.e. in the same frame): its DNRT node draws the
// object as a box, the image and passes of the frame before the throw.
TEST(DnrtGpu, FusedObjectOfAFrameThatThrewIsNotTheNextFrames) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  scene::Level level = game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/floor-box.json",
                                                  std::vector<std::string>{"direct", "dnrt"});
  for (auto& e : level.entities)
    if (e.dnrt) e.dnrt->mode = Mode::Fused;
  game::Session session(ctx, std::move(level));
  session.update(0.0);
  Runtime* dnrt = session.dnrt();
  ASSERT_NE(dnrt, nullptr);
  session.renderer().setNode("dnrt", dnrt->node());
  const Frame before = renderOnce(session, ctx);
  ASSERT_EQ(std::count(before.passes.begin(), before.passes.end(), "dnrt"), 1) << "no probes: a box";

  bool handed = false;
  session.renderer().setNode("dnrt", [&](rg::RenderGraph& graph, render::PassContext& pc) {
    handed = dnrt->addFused(graph, pc).has_value();
    throw std::runtime_error("test: thrown between the probes and DNRT nodes");
  });
  EXPECT_THROW(renderOnce(session, ctx), std::runtime_error);
  EXPECT_TRUE(handed) << "the object went to the probes pass in the frame that threw";

  session.renderer().setNode("dnrt", dnrt->node());
  const Frame after = renderOnce(session, ctx);
  EXPECT_EQ(after.passes, before.passes);
  EXPECT_EQ(after.rgb, before.rgb) << "the object's term is drawn, as before the throw";
}

// Clustered mode's tile cull (tile_cull.comp): each tile's CPU screen-hull mask cut by the depth range of
// the tile's pixels. It may only narrow which objects a pixel visits, never what a pixel adds
// (clustered.frag tests every pixel exactly), so the image is the uncut one bit for bit; the cut masks
// are subsets of the CPU's, and on this level (camera above the floor, so each outer cube's screen hull
// reaches beyond the cube's footprint on the floor) they are strictly smaller.
TEST(DnrtGpu, TileCullKeepsTheClusteredImageAndOnlyClearsMaskBits) {
  TwoBoxes boxes("tile-cull-cache");
  gpu::Context& ctx = boxes.ctx;
  game::Session& session = boxes.session;
  const std::vector<NodeObject>& all = boxes.objects;
  ASSERT_EQ(all.size(), 2u);
  Node& node = boxes.node;
  const auto renderWith = [&](const std::vector<NodeObject>& objects, bool cull) {
    session.renderer().setNode("dnrt", [&, objects, cull](rg::RenderGraph& graph, render::PassContext& pc) {
      NodeSettings settings{Mode::Clustered};
      settings.tileCull = cull;
      node.addTo(graph, pc, objects, settings);
    });
    Frame f = renderOnce(session, ctx);  // waits for the frame: its tile masks are final
    return std::make_pair(f, node.lastTileMasks());
  };
  // Both boxes (one batch, the loops), box A alone (kSingle) and 17 copies of both (two batches).
  std::vector<std::vector<NodeObject>> sets = {all, {all[0]}, {}};
  for (int k = 0; k < 17; ++k)
    for (const NodeObject& o : all) {
      sets.back().push_back(o);
      sets.back().back().name = o.name + "-" + std::to_string(k);
    }
  for (const std::vector<NodeObject>& objects : sets) {
    const auto [uncut, uncutMasks] = renderWith(objects, false);
    const auto [cut, cutMasks] = renderWith(objects, true);
    ASSERT_EQ(uncutMasks.size(), cutMasks.size());
    ASSERT_FALSE(cutMasks.empty());
    EXPECT_EQ(cut.passes, uncut.passes);
    ASSERT_EQ(cut.rgb.size(), uncut.rgb.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < cut.rgb.size(); ++i) differing += cut.rgb[i] != uncut.rgb[i] ? 1 : 0;
    EXPECT_EQ(differing, 0u) << objects.size() << " objects: the cull changed the image";
    int bitsBefore = 0, bitsAfter = 0, added = 0;
    for (std::size_t t = 0; t < cutMasks.size(); ++t) {
      bitsBefore += std::popcount(uncutMasks[t]);
      bitsAfter += std::popcount(cutMasks[t]);
      added += std::popcount(cutMasks[t] & ~uncutMasks[t]);
    }
    std::printf("tile cull, %zu objects: %d of %d tile-object bits kept\n", objects.size(), bitsAfter, bitsBefore);
    EXPECT_EQ(added, 0) << "a cut mask sets a bit the CPU's screen hull did not";
    EXPECT_GT(bitsAfter, 0);
    EXPECT_LT(bitsAfter, bitsBefore) << "the depth ranges cut nothing";
  }
}

// The c_j the runtime packs each frame (update.cpp) are the incident-light service's SH at the object's
// bounding sphere, with the lights' part Hanning-windowed for a field baked with App. B.2's improved
// anti-radiance and unwindowed for the paper's Eq. 12 (issue 15: the window keeps the improved
// anti-radiance's ×4 on band 2 from amplifying a lamp's ringing). cornell-1's lamp makes band 2 non-zero,
// so the two choices differ and the test can tell which one was taken.
TEST(DnrtGpu, ImprovedAntiRadianceFieldsGetTheLightsSHWindowedAndPaperFieldsDoNot) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  // Third case: improved, but the lights out of the anti-radiance (cornell-1's prop as shipped):
  // the lights then reach only t_j, no band factor scales them, and there is no window.
  for (const auto& [improved, lightsIn] : {std::pair{true, true}, std::pair{false, true}, std::pair{true, false}}) {
    scene::Level level = game::loadLevelWithEffects(fs::path(BOUNCE_SOURCE_DIR) / "content/levels/cornell-1.json",
                                                    std::vector<std::string>{"direct", "shadows"});
    for (scene::EntityDesc& e : level.entities)
      if (e.dnrt) {
        e.dnrt->improvedAntiRadiance = improved;
        e.dnrt->lightsInAntiRadiance = lightsIn;
        e.dnrt->shCount = 9;
        e.dnrt->grid = 16;
        e.dnrt->samplesPerAxis = 4;  // the field's values do not matter here, only which c_j are packed
      }
    game::Session session(ctx, level);
    session.update(0.0);
    renderOnce(session, ctx);
    ref::ReferenceAssets assets;
    assets.load(session.registry(), fs::path(BOUNCE_TEST_OUT) / "dnrt" / "cooked");
    const fs::path cache = fs::path(BOUNCE_TEST_OUT) / "dnrt" / "window-cache";
    Runtime dnrt(ctx, session.renderer().pipelines(), session.registry(), assets, cache,
                 gpu::FrameRing::kDefaultFramesInFlight, session.level().background);
    ASSERT_EQ(dnrt.objectCount(), 1u);
    const render::RenderWorld& world = session.world();
    ASSERT_FALSE(world.lights.empty());
    const std::vector<NodeObject> packed = dnrt.objectsFor(world);
    ASSERT_EQ(packed.size(), 1u);

    ecs::Entity entity{};
    session.registry().view<scene::Dnrt, scene::WorldTransform>().each(
        [&](ecs::Entity e, scene::Dnrt&, scene::WorldTransform&) { entity = e; });
    const glm::mat4 matrix = session.registry().get<scene::WorldTransform>(entity).matrix;
    const Field& field = dnrt.field(0);
    const Placement pl = place(field, matrix);
    const auto expect = [&](const incident::BandWindow& window) {
      return packObject(field, matrix, dnrt.incidentSH(pl.centreWorld, pl.radiusWorld, world.lights, window),
                        entity.index());
    };
    const DnrtObjectGpu windowed = expect(incident::kHanningWindow), plain = expect(incident::kNoWindow);
    float differ = 0.0f;
    for (int j = 4; j < 9; ++j) differ = std::max(differ, glm::length(glm::vec3(windowed.c[j] - plain.c[j])));
    EXPECT_GT(differ, 1e-4f * glm::length(glm::vec3(plain.c[0]))) << "band 2 carries the lamp: the window shows";
    const DnrtObjectGpu& want = improved && lightsIn ? windowed : plain;
    for (int j = 0; j < 9; ++j)
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_FLOAT_EQ(packed[0].data.c[j][ch], want.c[j][ch])
            << (improved ? "improved" : "paper") << (lightsIn ? "" : ", lights out of k_j") << " c_" << j;
  }
}

// Lights left out of the anti-radiance ("lights_in_anti_radiance": false, runtime.hpp; README "DNRT
// with the relit probes, session 10"): each such object carries a second term, its occlusion-only
// field (−k_j) with the lights' c_j negated, which combine.comp sums into the object's own combined
// volume in the same dispatch (kOcclusion). Checked against the same terms drawn as separate objects
// (the additive blend, as RuntimeBakesThroughTheCacheAndOverlappingObjectsAdd) in the box and the
// clustered modes, and the packed c_j of the two terms sum to the indirect source's alone (the lamp
// cancels in k_j).
TEST(DnrtGpu, LightsLeftOutOfTheAntiRadianceAddTheirTermInTheCombinedVolume) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path levelPath = fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/two-boxes-lamp.json";
  const auto frames = gpu::FrameRing::kDefaultFramesInFlight;
  const fs::path cache = fs::path(BOUNCE_TEST_OUT) / "dnrt" / "occlusion-cache";
  {  // As the level says: box-a's entry says "lights_in_anti_radiance": false, box-b's does not.
    game::Session session(ctx, game::loadLevelWithEffects(levelPath, std::nullopt));
    session.update(0.0);
    ref::ReferenceAssets assets;
    assets.load(session.registry(), fs::path(BOUNCE_TEST_OUT) / "dnrt" / "cooked");
    Runtime dnrt(ctx, session.renderer().pipelines(), session.registry(), assets, cache, frames,
                 session.level().background);
    renderOnce(session, ctx);  // the frame's draws: objectsFor packs the drawn objects
    const std::vector<NodeObject> asShipped = dnrt.objectsFor(session.world());
    ASSERT_EQ(asShipped.size(), 2u);
    EXPECT_NE(asShipped[0].occlusion, nullptr);
    EXPECT_EQ(asShipped[1].occlusion, nullptr);
  }
  // Both boxes with the lights out of their anti-radiance.
  scene::Level level = game::loadLevelWithEffects(levelPath, std::nullopt);
  for (scene::EntityDesc& e : level.entities)
    if (e.dnrt) e.dnrt->lightsInAntiRadiance = false;
  game::Session session(ctx, level);
  session.update(0.0);
  ref::ReferenceAssets assets;
  assets.load(session.registry(), fs::path(BOUNCE_TEST_OUT) / "dnrt" / "cooked");
  Runtime dnrt(ctx, session.renderer().pipelines(), session.registry(), assets, cache, frames,
               session.level().background);
  session.renderer().setNode("dnrt", dnrt.node());
  renderOnce(session, ctx);
  const std::vector<NodeObject> all = dnrt.objectsFor(session.world());
  ASSERT_EQ(all.size(), 2u);
  ASSERT_EQ(session.world().lights.size(), 1u);

  // c_j of the two terms: full + (−lights) = the background alone, per coefficient and channel.
  for (std::size_t i = 0; i < all.size(); ++i) {
    ASSERT_NE(all[i].occlusion, nullptr);
    EXPECT_TRUE(all[i].occlusion->field().settings.occlusionOnly);
    EXPECT_FALSE(all[i].textures->field().settings.occlusionOnly);
    const glm::vec3 o(all[i].data.centreWorld);
    const float radius = all[i].data.centreWorld.w;
    // No window on the lights' SH for an object whose lights are out of k_j (update.cpp).
    const incident::RadianceSH full = dnrt.incidentSH(o, radius, session.world().lights);
    const incident::RadianceSH indirect = dnrt.incidentSH(o, radius, {});
    float lightPart = 0.0f;
    for (std::size_t j = 0; j < 9; ++j) lightPart = std::max(lightPart, glm::length(full[j] - indirect[j]));
    EXPECT_GT(lightPart, 0.01f) << "the lamp reaches the object";
    // packObject convolves and rotates into the object's frame, both linear; the background is
    // uniform, so the sum is its band 0 alone (rotation-invariant) and zero in bands 1–2.
    const incident::RadianceSH c = irradianceSH(indirect);
    const int sh = all[i].textures->field().settings.shCount;
    for (int j = 0; j < sh; ++j) {
      const glm::vec3 sum = glm::vec3(all[i].data.c[j]) + glm::vec3(all[i].occlusionData.c[j]);
      const glm::vec3 want = j == 0 ? c[0] : glm::vec3(0.0f);
      EXPECT_LE(glm::length(sum - want), 1e-5f * (1.0f + glm::length(glm::vec3(all[i].data.c[j])))) << "object " << i << " c_" << j;
    }
  }

  Node node(ctx, session.renderer().pipelines(), frames);
  const auto renderWith = [&](std::vector<NodeObject> objects, std::optional<Mode> mode) {
    session.renderer().setNode("dnrt", [&, objects, mode](rg::RenderGraph& graph, render::PassContext& pc) {
      node.addTo(graph, pc, objects, NodeSettings{mode});
    });
    return renderOnce(session, ctx);
  };
  session.renderer().setNode("dnrt", {});
  const std::vector<float> base = renderOnce(session, ctx).rgb;
  std::vector<NodeObject> plain = all, split = all;
  for (NodeObject& o : plain) o.occlusion = nullptr;
  for (NodeObject& o : split) o.occlusion = nullptr;
  for (const NodeObject& o : all) {
    NodeObject term;
    term.textures = o.occlusion;
    term.data = o.occlusionData;
    term.name = o.name + "-occlusion";
    split.push_back(term);
  }
  float filterStep = 0.0f;  // Σ_terms Σ_slots |k| / 255, as ClusteredModeDrawsThePerObjectImage
  for (const NodeObject& o : split) {
    const DnrtShaderObject f = fold(o.data);
    for (const glm::vec4& kt : f.k) filterStep += (std::abs(kt.x) + std::abs(kt.y) + std::abs(kt.z) + std::abs(kt.w)) / 255.0f;
  }
  const Frame fused = renderWith(all, std::nullopt), separate = renderWith(split, std::nullopt);
  const Frame clustered = renderWith(all, Mode::Clustered), without = renderWith(plain, std::nullopt);
  EXPECT_EQ(clustered.passes, fused.passes);
  constexpr float kHalfUlp = 1.0f / 2048.0f;
  const float n = float(split.size());
  float largestTerm = 0.0f, worstSeparate = 0.0f, worstClustered = 0.0f, worstAbs = 0.0f;
  for (std::size_t i = 0; i < fused.rgb.size(); ++i) {
    const float v = fused.rgb[i] - base[i];
    const float tolerance = (n + 2.0f) * kHalfUlp * (std::abs(base[i]) + 2.0f * std::abs(v)) + filterStep + 1e-7f;
    worstSeparate = std::max(worstSeparate, std::abs(separate.rgb[i] - fused.rgb[i]) / tolerance);
    worstClustered = std::max(worstClustered, std::abs(clustered.rgb[i] - fused.rgb[i]) / tolerance);
    largestTerm = std::max(largestTerm, std::abs(fused.rgb[i] - without.rgb[i]));
    worstAbs = std::max({worstAbs, std::abs(separate.rgb[i] - fused.rgb[i]), std::abs(clustered.rgb[i] - fused.rgb[i])});
  }
  std::printf("lights out of the anti-radiance: largest |lights' k term| %.4f; fused vs separate draws %.3f, "
              "clustered vs box %.3f of the tolerance (filter step %.2g); worst |difference| %.2g\n",
              largestTerm, worstSeparate, worstClustered, filterStep, worstAbs);
  EXPECT_GT(largestTerm, 0.005f) << "the lamp's anti-radiance is a visible term";
  EXPECT_LE(worstSeparate, 1.0f);
  EXPECT_LE(worstClustered, 1.0f);
  // As a whole, within 1 % of the term (a term added to the wrong brick or left out would show).
  EXPECT_LE(worstAbs, 0.01f * largestTerm);
}

// "lights_in_anti_radiance": false is meant with relit probes (they carry the lamp's bounce off the
// object's shadow that the anti-radiance no longer subtracts): a session of a level that sets it
// without them warns once (dnrt's SessionRuntime), naming every such entity; the same level with the
// key true does not. Only that warning is counted (stderr lines naming the key), not others.
TEST(DnrtGpu, LightsOutOfTheAntiRadianceWithoutRelitProbesWarnsOnce) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const fs::path levelPath = fs::path(BOUNCE_SOURCE_DIR) / "tests/data/dnrt/two-boxes-lamp.json";
  struct Case {
    std::vector<std::string> lightsOut;  // entities with the key false
    std::string named;                   // what the warning names ("" = no warning)
  };
  for (const Case& c : {Case{{"box-a"}, "dnrt box-a: "}, Case{{"box-a", "box-b"}, "dnrt box-a, box-b: "}, Case{{}, ""}}) {
    scene::Level level = game::loadLevelWithEffects(levelPath, std::nullopt);  // "effects": ["dnrt"], no probes
    for (scene::EntityDesc& e : level.entities)
      if (e.dnrt) e.dnrt->lightsInAntiRadiance = std::find(c.lightsOut.begin(), c.lightsOut.end(), e.id) == c.lightsOut.end();
    ::testing::internal::CaptureStderr();
    { game::Session session(ctx, level); }
    const std::string err = ::testing::internal::GetCapturedStderr();
    std::vector<std::string> warnings;
    for (std::size_t at = 0, end; at < err.size(); at = end + 1) {
      end = std::min(err.find('\n', at), err.size());
      const std::string line = err.substr(at, end - at);
      if (line.find("lights_in_anti_radiance") != std::string::npos) warnings.push_back(line);
    }
    ASSERT_EQ(warnings.size(), c.named.empty() ? 0u : 1u) << err;
    if (!c.named.empty()) {
      EXPECT_EQ(warnings[0].rfind("warning: ", 0), 0u) << warnings[0];
      EXPECT_NE(warnings[0].find(c.named), std::string::npos) << warnings[0];
    }
  }
}


// The graph's passes as its DOT text (rg::RenderGraph::toDot) names them: per pass, the names of the
// resources it reads and writes, and each resource's "WxH FORMAT" detail.
struct DotGraph {
  std::map<std::string, std::set<std::string>> reads, writes;
  std::map<std::string, std::string> detail;
};
DotGraph parseDot(const std::string& dot) {
  DotGraph g;
  std::map<std::string, std::string> passOf, resourceOf;
  const std::regex pass(R"re(^\s+(p\d+) \[label="([^"]*)", shape=box)re");
  const std::regex version(R"re(^\s+(r\d+_v\d+) \[label="([^"\\]*)\\nv\d+\\n([^"]*)")re");
  const std::regex read(R"re(^\s+(r\d+_v\d+) -> (p\d+) \[label=)re"), write(R"re(^\s+(p\d+) -> (r\d+_v\d+) \[label=)re");
  std::istringstream in(dot);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::smatch m;
  for (const std::string& line : lines)
    if (std::regex_search(line, m, pass)) passOf[m[1]] = m[2];
    else if (std::regex_search(line, m, version)) {
      resourceOf[m[1]] = m[2];
      g.detail[m[2]] = m[3];
    }
  for (const std::string& line : lines)
    if (std::regex_search(line, m, read)) g.reads[passOf[m[2]]].insert(resourceOf[m[1]]);
    else if (std::regex_search(line, m, write)) g.writes[passOf[m[1]]].insert(resourceOf[m[2]]);
  return g;
}

// "dnrt": {"resolution": "half" | "quarter"} (NodeSettings::step), box and clustered draws, on the
// floor of floor-box.json (a plane seen straight down; the HDR image IS L_DNRT):
// - structure: "dnrt" writes the transient "dnrt.half" / "dnrt.quarter" of ⌈size/step⌉ (98×94 →
//   49×47 / 25×24) and not "lighting.hdr"; "dnrt.upsample" reads it with the G-buffer and writes
//   "lighting.hdr"; at full resolution neither exists and "dnrt" writes "lighting.hdr";
// - values: on a plane every receiver matches every sample (tangent-plane distance 0, n·n_q = 1), so
//   the upsample is exactly the bilinear blend (gi::upsampleTaps' fractions) of the full-resolution
//   image at the samples' G-buffer pixels step·j (the same shader arithmetic there, ρ_r applied
//   after the blend: equal for a constant albedo), to fp16 rounding (kUpsampleTol); pixels whose
//   taps see the box are skipped.
TEST(DnrtGpu, ReducedResolutionIsTheBilinearUpsampleOfTheFullImageOnAPlane) {
  FloorBox f;
  ASSERT_FALSE(f.box.isNull());
  gpu::Context& ctx = f.ctx;
  game::Session& session = f.session;
  ecs::Registry& reg = f.reg;
  ref::ReferenceAssets& assets = f.assets;
  const ecs::Entity box = f.box;
  FieldSettings fieldSettings = settingsFrom(reg.get<scene::Dnrt>(box));
  fieldSettings.shCount = 4;
  const BakeResult baked = bake(objectScene(reg, box, assets), fieldSettings);
  const FieldTextures textures(ctx, baked.field, "box");
  Node node(ctx, session.renderer().pipelines(), gpu::FrameRing::kDefaultFramesInFlight);
  std::array<glm::vec3, 9> sky{};
  const float v[9] = {3.0f, 0.8f, 1.4f, -0.6f, 0.5f, -0.9f, 0.7f, 0.4f, -1.1f};
  for (int i = 0; i < 9; ++i) sky[std::size_t(i)] = v[i] * glm::vec3(1.0f, 0.8f, 0.6f);
  const NodeObject object{&textures, packObject(baked.field, reg.get<scene::WorldTransform>(box).matrix, sky), "box"};
  constexpr std::uint32_t kW = 98, kH = 94;  // odd multiples of 2: the reduced size rounds up
  // fp16: the reduced target's E and the two images each round to 2⁻¹¹ relative; 2e-3 of the largest
  // |tap| covers the three roundings and the blend's float weights.
  constexpr float kUpsampleTol = 2e-3f;
  const auto render = [&](std::uint32_t step, Mode mode) {
    NodeSettings settings;
    settings.step = step;
    settings.mode = mode;
    session.renderer().setNode("dnrt", [&, settings](rg::RenderGraph& graph, render::PassContext& pc) {
      node.addTo(graph, pc, {object}, settings);
    });
    gpu::OffscreenPresenter presenter(ctx, {kW, kH});
    render::FrameSettings frame;
    frame.keepHdr = true;
    session.render(presenter, frame);
    return Frame{session.renderer().readHdr(), session.renderer().executedPasses()};
  };
  const rtest::FloorScene floor = rtest::readFloorScene(session.level());
  const auto nearBox = [&](std::uint32_t x, std::uint32_t y) {
    const auto p = rtest::floorPoint(floor, kW, kH, x, y);
    return !p || glm::length(glm::vec2(p->x - 0.05f, p->z + 0.03f)) < 0.16f;  // as the test above, + 1 px
  };
  for (const Mode mode : {Mode::Box, Mode::Clustered}) {
    const Frame full = render(1, mode);
    {
      const DotGraph g = parseDot(session.renderer().graphDot(session.world(), {kW, kH}, {}));
      EXPECT_EQ(g.writes.at("dnrt"), std::set<std::string>{"lighting.hdr"});
      EXPECT_EQ(g.reads.count("dnrt.upsample"), 0u);
      EXPECT_EQ(g.detail.count("dnrt.half") + g.detail.count("dnrt.quarter"), 0u);
      EXPECT_EQ(std::count(full.passes.begin(), full.passes.end(), "dnrt.upsample"), 0);
    }
    for (const std::uint32_t step : {2u, 4u}) {
      const Frame reduced = render(step, mode);
      const std::string target = step == 2u ? "dnrt.half" : "dnrt.quarter";
      const DotGraph g = parseDot(session.renderer().graphDot(session.world(), {kW, kH}, {}));
      EXPECT_EQ(g.writes.at("dnrt"), std::set<std::string>{target});
      EXPECT_EQ(g.detail.at(target), step == 2u ? "49x47 RGBA16F" : "25x24 RGBA16F");
      EXPECT_EQ(g.reads.at("dnrt.upsample"),
                (std::set<std::string>{target, "gbuffer.albedo", "gbuffer.normal", "gbuffer.depth"}));
      EXPECT_EQ(g.writes.at("dnrt.upsample"), std::set<std::string>{"lighting.hdr"});
      ASSERT_EQ(std::count(reduced.passes.begin(), reduced.passes.end(), "dnrt.upsample"), 1);
      EXPECT_LT(std::find(reduced.passes.begin(), reduced.passes.end(), "dnrt") - reduced.passes.begin(),
                std::find(reduced.passes.begin(), reduced.passes.end(), "dnrt.upsample") - reduced.passes.begin());

      const glm::ivec2 size{int(kW), int(kH)};
      const glm::ivec2 reducedSize = (size + int(step) - 1) / int(step);
      int compared = 0;
      float worstRatio = 0.0f, largest = 0.0f;
      for (std::uint32_t y = 0; y < kH; ++y)
        for (std::uint32_t x = 0; x < kW; ++x) {
          const UpsampleTaps t = upsampleTaps({int(x), int(y)}, int(step), reducedSize, size);
          bool skip = nearBox(x, y);
          for (const glm::ivec2& q : t.q) skip = skip || nearBox(std::uint32_t(q.x), std::uint32_t(q.y));
          if (skip) continue;
          for (int ch = 0; ch < 3; ++ch) {
            double want = 0.0, tap = 0.0;
            for (int k = 0; k < 4; ++k) {
              const glm::ivec2 q = t.q[std::size_t(k)];
              const double f = full.rgb[(std::size_t(q.y) * kW + std::size_t(q.x)) * 3 + std::size_t(ch)];
              want += ((k & 1) ? t.f.x : 1.0 - t.f.x) * ((k >> 1) ? t.f.y : 1.0 - t.f.y) * f;
              tap = std::max(tap, std::abs(f));
            }
            const double got = reduced.rgb[(std::size_t(y) * kW + x) * 3 + std::size_t(ch)];
            largest = std::max(largest, float(std::abs(want)));
            worstRatio = std::max(worstRatio, float(std::abs(got - want) / (kUpsampleTol * tap + 1e-7)));
          }
          ++compared;
        }
      std::printf("dnrt %s at step %u vs the bilinear blend of the full image: %d floor pixels, largest %.4f, worst "
                  "difference %.2f of its bound\n",
                  mode == Mode::Box ? "box" : "clustered", step, compared, largest, worstRatio);
      EXPECT_GT(compared, 4000);
      EXPECT_GT(largest, 0.01f);
      EXPECT_LE(worstRatio, 1.0f) << "step " << step;
    }
  }
}

}  // namespace
}  // namespace bounce::gi::dnrt
