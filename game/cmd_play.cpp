// bounce play LEVEL: an interactive window (GLFW + Vulkan swapchain).
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/image_io.hpp"
#include "engine/gpu/presenter_swapchain.hpp"
#include "game/commands.hpp"
#include "game/session.hpp"

namespace bounce::game {

int runPlay(const cli::Args& args) {
  const int frameLimit = args.has("--frames") ? args.positiveInt("--frames", 1) : 0;
  const auto res = args.resolution("--resolution").value_or(std::pair{1280, 720});
  const std::string vsync = args.str("--vsync", "on");
  if (vsync != "on" && vsync != "off") throwInputError("bounce play", "--vsync", "'" + vsync + "'", "on or off");
  if (args.has("--screenshot") && !frameLimit)
    throwInputError("bounce play", "--screenshot", "needs --frames N", "--frames N --screenshot FILE");
  scene::Level level = loadLevelWithEffects(args.positional[0], args.list("--effects"));
  if (!glfwInit()) throw InternalError("no display: GLFW could not initialise (use 'bounce capture' headless)");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  GLFWwindow* window = glfwCreateWindow(res.first, res.second, ("bounce — " + level.name).c_str(), nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    throw InternalError("could not open a window");
  }
  int code = 0;
  {
    gpu::ContextOptions options;
    options.deviceName = args.str("--device");
    options.windowed = true;
    gpu::Context ctx(options);
    Session session(ctx, level);
    gpu::SwapchainPresenter presenter(ctx, window, vsync == "on");
    const auto start = std::chrono::steady_clock::now();
    for (int frame = 0; !glfwWindowShouldClose(window) && (!frameLimit || frame < frameLimit); ++frame) {
      glfwPollEvents();
      const double t = frameLimit ? frame / 60.0 : std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      session.update(t);
      session.render(presenter, {});
    }
    session.renderer().frames().waitIdle();
    if (args.has("--screenshot")) {
      auto bytes = gpu::readback(ctx, session.renderer().displayImage());
      auto& img = session.renderer().displayImage();
      gpu::writePng(args.str("--screenshot"), img.desc().width, img.desc().height, 4, bytes);
    }
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace bounce::game
