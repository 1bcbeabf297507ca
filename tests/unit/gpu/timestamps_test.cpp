// GPU timestamp scopes through the frame ring.
#include <gtest/gtest.h>

#include <cmath>

#include "draw_helpers.hpp"
#include "engine/core/error.hpp"
#include "engine/gpu/frames.hpp"
#include "engine/gpu/testing.hpp"

using namespace bounce;
using namespace bounce::gpu;

TEST(Timestamps, NestedScopesResolveToFiniteNonNegativeMilliseconds) {
  Context& ctx = testkit::sharedContext();
  Image target(ctx, {ImageType::Tex2D, VK_FORMAT_R16G16B16A16_SFLOAT, 256, 256, 1, 1, 1,
                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_SAMPLE_COUNT_1_BIT, "timed target"});
  testkit::SolidPipeline solid(ctx, VK_FORMAT_R16G16B16A16_SFLOAT);
  FrameRing frames(ctx, 2);
  for (int frame = 0; frame < 3; ++frame) {
    Frame& f = frames.begin();
    {
      GpuScope outer(ctx, *f.timestamps, f.cmd, "outer");
      {
        GpuScope inner(ctx, *f.timestamps, f.cmd, "draw");
        testkit::beginColor(ctx, f.cmd, target, testkit::Color{0, 0, 0, 0});
        solid.draw(f.cmd, {1, 1, 1, 1});
        ctx.cmdEndRendering(f.cmd);
      }
    }
    frames.submit();
  }
  frames.waitIdle();
  if (!frames.current().timestamps->supported()) GTEST_SKIP() << "queue has no timestamps";
  EXPECT_EQ(frames.lastTimingsFrame(), 3u);
  const auto& t = frames.lastTimings();
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].name, "outer");
  EXPECT_EQ(t[0].depth, 0u);
  EXPECT_EQ(t[1].name, "draw");
  EXPECT_EQ(t[1].depth, 1u);
  for (auto& r : t) {
    EXPECT_TRUE(std::isfinite(r.ms)) << r.name;
    EXPECT_GE(r.ms, 0.0) << r.name;
  }
  EXPECT_GE(t[0].ms, t[1].ms);  // the outer scope contains the inner one
}

TEST(Timestamps, UnbalancedEndIsAnError) {
  Context& ctx = testkit::sharedContext();
  FrameRing frames(ctx, 1);
  Frame& f = frames.begin();
  EXPECT_THROW(f.timestamps->end(f.cmd), InternalError);
  frames.submit();
}

TEST(Frames, DeferredDeletionRunsAfterTheFrameCompletes) {
  Context& ctx = testkit::sharedContext();
  FrameRing frames(ctx, 2);
  int deleted = 0;
  frames.begin();
  frames.deferDelete([&] { ++deleted; });
  frames.submit();
  EXPECT_EQ(deleted, 0);  // frame 1 may still run
  frames.begin();         // slot 1: frame 1's slot is not reused yet
  frames.submit();
  EXPECT_EQ(deleted, 0);
  frames.begin();  // slot 0 again: waits for frame 1, then deletes
  EXPECT_EQ(deleted, 1);
  frames.submit();
}

// An error thrown while a frame records (Renderer::render unwinds through abandon()) must leave the
// ring usable: before abandon() existed, the destructor's waitIdle() threw "while a frame is
// recording" and the program ended in std::terminate (exit 134) with the first error lost.
TEST(Frames, AbandonedFrameLeavesTheRingUsable) {
  Context& ctx = testkit::sharedContext();
  Image target(ctx, {ImageType::Tex2D, VK_FORMAT_R16G16B16A16_SFLOAT, 16, 16, 1, 1, 1,
                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, VK_SAMPLE_COUNT_1_BIT, "abandoned target"});
  testkit::SolidPipeline solid(ctx, VK_FORMAT_R16G16B16A16_SFLOAT);
  FrameRing frames(ctx, 2);
  int deleted = 0;
  frames.begin();
  frames.submit();  // frame 1, completes normally
  Frame& f = frames.begin();  // frame 2: stopped inside a render pass, as an exception would leave it
  frames.deferDelete([&] { ++deleted; });
  testkit::beginColor(ctx, f.cmd, target, testkit::Color{0, 0, 0, 0});
  solid.draw(f.cmd, {1, 1, 1, 1});
  EXPECT_THROW(frames.waitIdle(), InternalError);  // the state abandon() exists for
  frames.abandon();
  EXPECT_FALSE(frames.current().recording);
  frames.abandon();  // no frame recording: no-op
  frames.waitIdle();  // returns: the abandoned slot's fence is signalled
  EXPECT_EQ(deleted, 1);  // its deletion ran when the slot was retired
  for (int frame = 0; frame < 3; ++frame) {  // the ring records and submits again, both slots
    Frame& g = frames.begin();
    testkit::beginColor(ctx, g.cmd, target, testkit::Color{0, 0, 0, 0});
    solid.draw(g.cmd, {1, 1, 1, 1});
    ctx.cmdEndRendering(g.cmd);
    frames.submit();
  }
  frames.waitIdle();
  if (frames.current().timestamps->supported()) {
    EXPECT_EQ(frames.lastTimingsFrame(), 0u);  // no scope was opened in any frame
  }
}
