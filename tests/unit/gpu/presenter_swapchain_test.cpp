// Swapchain presenter in a GLFW window. Needs a display: run under `xvfb-run -a`; skipped when
// DISPLAY is unset.
#include <gtest/gtest.h>

#include <cstdlib>

#include "draw_helpers.hpp"
#include "engine/gpu/frames.hpp"
#include "engine/gpu/presenter_swapchain.hpp"
#include "engine/gpu/testing.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

using namespace bounce::gpu;

namespace {
struct Glfw {
  bool ok = glfwInit() == GLFW_TRUE;
  ~Glfw() {
    if (ok) glfwTerminate();
  }
};

// Waits (bounded by a number of event polls, not by time) until the framebuffer has the size.
bool waitForSize(GLFWwindow* window, int w, int h) {
  for (int i = 0; i < 200; ++i) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    if (fw == w && fh == h) return true;
    glfwWaitEventsTimeout(0.01);
  }
  return false;
}
}  // namespace

TEST(SwapchainPresenter, PresentsAndRecreatesOnResize) {
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) GTEST_SKIP() << "no DISPLAY (run under xvfb-run -a)";
  Glfw glfw;
  ASSERT_TRUE(glfw.ok);
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  GLFWwindow* window = glfwCreateWindow(160, 120, "bounce swapchain test", nullptr, nullptr);
  ASSERT_NE(window, nullptr);
  ASSERT_TRUE(waitForSize(window, 160, 120));
  {
    ContextOptions o;
    o.windowed = true;
    Context ctx(o);
    SwapchainPresenter presenter(ctx, window, /*vsync=*/false);
    EXPECT_EQ(presenter.format(), VK_FORMAT_B8G8R8A8_UNORM);
    EXPECT_GE(presenter.imageCount(), 2u);
    EXPECT_EQ(presenter.extent().width, 160u);
    EXPECT_EQ(presenter.extent().height, 120u);
    EXPECT_EQ(presenter.buildCount(), 1u);
    EXPECT_FALSE(presenter.vsync());

    Image source(ctx, {ImageType::Tex2D, VK_FORMAT_R8G8B8A8_UNORM, 160, 120, 1, 1, 1,
                       VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_SAMPLE_COUNT_1_BIT,
                       "window picture"});
    testkit::SolidPipeline solid(ctx, VK_FORMAT_R8G8B8A8_UNORM);
    FrameRing frames(ctx);
    auto frame = [&] {
      Frame& f = frames.begin();
      testkit::beginColor(ctx, f.cmd, source, testkit::Color{0, 0, 0, 1});
      solid.draw(f.cmd, {0.2f, 0.4f, 0.8f, 1.0f});
      ctx.cmdEndRendering(f.cmd);
      return presenter.present(frames, source);
    };
    int shown = 0;
    for (int i = 0; i < 5; ++i) shown += frame();
    EXPECT_EQ(shown, 5);
    EXPECT_EQ(presenter.buildCount(), 1u);

    glfwSetWindowSize(window, 200, 150);
    ASSERT_TRUE(waitForSize(window, 200, 150));
    for (int i = 0; i < 3; ++i) frame();  // the source stays 160×120: the blit scales it
    EXPECT_GE(presenter.buildCount(), 2u);
    EXPECT_EQ(presenter.extent().width, 200u);
    EXPECT_EQ(presenter.extent().height, 150u);

    presenter.setVsync(true);
    frame();
    EXPECT_EQ(presenter.presentMode(), VK_PRESENT_MODE_FIFO_KHR);
    frames.waitIdle();
  }
  glfwDestroyWindow(window);
}
