// An exception thrown from inside a frame's recording (a pass's execute callback, after earlier
// passes recorded their barriers) unwinds through Renderer::render's catch: the frame is abandoned
// (FrameRing::abandon, nothing submitted), the graph's layout tracking is rolled back to what the
// GPU really holds, and the next frames render the same image as before the throw, with no
// validation errors (the listener in engine/gpu/testing.hpp fails the test on any).
//
// Level: tests/data/render/plane-point.json (a lit floor seen from above, effects ["direct"]). The
// throwing pass is a node on "direct" that writes "lighting.hdr" after the lighting pass, so the
// lighting pass has already recorded hdr's transition to a colour attachment when it throws.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "engine/gpu/commands.hpp"
#include "engine/gpu/presenter_offscreen.hpp"
#include "engine/gpu/testing.hpp"
#include "game/session.hpp"

using namespace bounce;

namespace {

constexpr std::uint32_t kWidth = 64, kHeight = 48;

struct ThrowData {
  rg::Handle<rg::Texture> hdr;
};

// A node whose one pass throws from its execute callback (never from setup: the graph is built and
// compiled, and the passes before it have recorded into the frame's command buffer).
render::Renderer::GraphNode throwingNode() {
  return [](rg::RenderGraph& graph, render::PassContext&) {
    auto& bb = graph.blackboard();
    const auto& d = graph.addPass<ThrowData>(
        "test.throw",
        [&](rg::Builder& b, ThrowData& data) {
          data.hdr = b.write(bb.get<rg::Texture>("lighting.hdr"), rg::Usage::ColorAttachment);
        },
        [](const ThrowData&, const rg::PassResources&, rg::CommandContext&) {
          throw std::runtime_error("test: thrown while the frame records");
        });
    bb.put("lighting.hdr", d.hdr);
  };
}

TEST(RenderUnwind, FrameThatThrowsIsDroppedAndTheNextRendersTheSameImage) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  game::Session session(ctx, scene::loadLevel(std::filesystem::path(BOUNCE_SOURCE_DIR) / "tests/data/render/plane-point.json"));
  session.update(0.0);
  gpu::OffscreenPresenter presenter(ctx, {kWidth, kHeight});
  render::Renderer& renderer = session.renderer();
  gpu::FrameRing& frames = renderer.frames();
  ASSERT_EQ(frames.framesInFlight(), 2u);

  // Frame 1 (slot 0): the reference image, and the layouts the GPU leaves its targets in.
  session.render(presenter, render::FrameSettings{});
  frames.waitIdle();
  const std::vector<std::uint8_t> reference = gpu::readback(ctx, renderer.displayImage());
  ASSERT_EQ(reference.size(), std::size_t(kWidth) * kHeight * 4);
  std::size_t lit = 0;  // a real image, not a cleared one
  for (std::size_t i = 0; i < reference.size(); i += 4) lit += reference[i] > 0;
  ASSERT_GT(lit, reference.size() / 8);
  const VkImageLayout hdrLayout = renderer.hdrImage().layout(), displayLayout = renderer.displayImage().layout();

  // Frame 2 (slot 1) throws from inside the graph's execution: the error reaches the caller as is.
  renderer.setNode("direct", throwingNode());
  try {
    session.render(presenter, render::FrameSettings{});
    FAIL() << "the throwing pass did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "test: thrown while the frame records");
  }
  ASSERT_EQ(renderer.executedPasses().back(), "tonemap");  // the compiled graph: test.throw was not culled
  EXPECT_NE(std::find(renderer.executedPasses().begin(), renderer.executedPasses().end(), "test.throw"),
            renderer.executedPasses().end());
  // The ring: slot 1 holds frame 2, not recording, its fence signalled (nothing will ever signal
  // the one begin() reset), no timings to resolve.
  EXPECT_FALSE(frames.current().recording);
  EXPECT_EQ(frames.current().slot, 1u);
  EXPECT_EQ(frames.current().number, 2u);
  EXPECT_TRUE(frames.current().retired);
  EXPECT_EQ(vkGetFenceStatus(ctx.device(), frames.current().fence), VK_SUCCESS);
  // The tracked layouts are what the GPU holds (frame 1's), not what frame 2's unsubmitted
  // barriers named: the next frame's first barriers start from them.
  EXPECT_EQ(renderer.hdrImage().layout(), hdrLayout);
  EXPECT_EQ(renderer.displayImage().layout(), displayLayout);
  frames.waitIdle();  // returns: no frame recording, every fence signalled

  // Frames 3 (slot 0) and 4 (slot 1, the abandoned slot again) render the reference image exactly.
  renderer.setNode("direct", {});
  for (std::uint64_t number = 3; number <= 4; ++number) {
    session.render(presenter, render::FrameSettings{});
    EXPECT_EQ(frames.current().number, number);
    EXPECT_EQ(frames.current().slot, std::uint32_t(number - 1) % 2u);
    frames.waitIdle();
    EXPECT_EQ(renderer.executedPasses().back(), "tonemap");
    EXPECT_EQ(gpu::readback(ctx, renderer.displayImage()), reference) << "frame " << number;
  }
}

// A presenter that submits the frame (OffscreenPresenter's present) and then throws, as a present
// error or the capture's waitIdle can: the frame's barriers ran on the GPU, so Renderer::render's
// catch must keep the layouts they tracked instead of rolling them back.
class ThrowAfterSubmit final : public gpu::Presenter {
 public:
  explicit ThrowAfterSubmit(gpu::OffscreenPresenter& inner) : inner_(inner) {}
  VkExtent2D extent() const override { return inner_.extent(); }
  bool present(gpu::FrameRing& frames, gpu::Image& source) override {
    inner_.present(frames, source);
    throw std::runtime_error("test: thrown after the frame was submitted");
  }

 private:
  gpu::OffscreenPresenter& inner_;
};

// The first frame of a session starts its targets from UNDEFINED, so a wrong roll-back shows: the
// tracked layouts would go back to UNDEFINED while the GPU holds the frame's final ones.
TEST(RenderUnwind, FrameThatThrowsAfterSubmitKeepsItsLayouts) {
  gpu::Context& ctx = gpu::testkit::sharedContext();
  const auto level = std::filesystem::path(BOUNCE_SOURCE_DIR) / "tests/data/render/plane-point.json";
  // The layouts and image of one normal first frame, from a session of its own.
  VkImageLayout hdrLayout{}, displayLayout{};
  std::vector<std::uint8_t> reference;
  {
    game::Session normal(ctx, scene::loadLevel(level));
    normal.update(0.0);
    gpu::OffscreenPresenter presenter(ctx, {kWidth, kHeight});
    normal.render(presenter, render::FrameSettings{});
    normal.renderer().frames().waitIdle();
    hdrLayout = normal.renderer().hdrImage().layout();
    displayLayout = normal.renderer().displayImage().layout();
    reference = gpu::readback(ctx, normal.renderer().displayImage());
  }
  ASSERT_NE(hdrLayout, VK_IMAGE_LAYOUT_UNDEFINED);
  ASSERT_NE(displayLayout, VK_IMAGE_LAYOUT_UNDEFINED);

  game::Session session(ctx, scene::loadLevel(level));
  session.update(0.0);
  gpu::OffscreenPresenter inner(ctx, {kWidth, kHeight});
  ThrowAfterSubmit presenter(inner);
  render::Renderer& renderer = session.renderer();
  try {
    session.render(presenter, render::FrameSettings{});
    FAIL() << "the presenter did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "test: thrown after the frame was submitted");
  }
  renderer.frames().waitIdle();
  EXPECT_EQ(renderer.hdrImage().layout(), hdrLayout);
  EXPECT_EQ(renderer.displayImage().layout(), displayLayout);
  EXPECT_EQ(gpu::readback(ctx, renderer.displayImage()), reference);  // the submitted frame ran
  // The next frame, presented normally, renders the same image.
  session.render(inner, render::FrameSettings{});
  renderer.frames().waitIdle();
  EXPECT_EQ(gpu::readback(ctx, renderer.displayImage()), reference);
}

}  // namespace
