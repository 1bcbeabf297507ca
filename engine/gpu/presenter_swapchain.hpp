#pragma once
// Window presenter: a GLFW window's surface and swapchain. The swapchain is 8-bit BGRA
// (lavapipe offers nothing else; HDR is rendered offscreen and tonemapped first), used as a
// transfer destination only: present() blits the renderer's 8-bit image into it (the blit
// swizzles RGBA → BGRA and scales when sizes differ, e.g. mid-resize).
//
// Recreation: when the framebuffer size changes, or acquire/present report OUT_OF_DATE or
// SUBOPTIMAL, the swapchain is rebuilt (after the device is idle). A minimised (0×0) window
// presents nothing. vsync on = FIFO; off = MAILBOX, else IMMEDIATE, else FIFO.
//
// Semaphores: one "acquired" semaphore per frame in flight (reused only after that frame's
// fence), one "rendered" semaphore per swapchain image (reused only when the image is
// acquired again), the pattern the validation layer recommends.
#include <cstdint>
#include <vector>

#include "engine/gpu/presenter.hpp"

struct GLFWwindow;

namespace bounce::gpu {

class Context;

class SwapchainPresenter : public Presenter {
 public:
  // `ctx` must be windowed (ContextOptions::windowed); `window` created with GLFW_NO_API.
  SwapchainPresenter(Context& ctx, GLFWwindow* window, bool vsync = true);
  ~SwapchainPresenter() override;
  SwapchainPresenter(const SwapchainPresenter&) = delete;
  SwapchainPresenter& operator=(const SwapchainPresenter&) = delete;

  VkExtent2D extent() const override { return extent_; }
  bool present(FrameRing& frames, Image& source) override;

  void setVsync(bool vsync);
  bool vsync() const { return vsync_; }
  VkPresentModeKHR presentMode() const { return present_mode_; }
  VkFormat format() const { return format_; }
  std::uint32_t imageCount() const { return static_cast<std::uint32_t>(images_.size()); }
  // How many times the swapchain was (re)built, the first creation included.
  std::uint32_t buildCount() const { return builds_; }

 private:
  void build();
  void destroySwapchain(VkSwapchainKHR swapchain);
  VkExtent2D framebufferSize() const;

  Context& ctx_;
  GLFWwindow* window_;
  bool vsync_;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkPresentModeKHR present_mode_ = VK_PRESENT_MODE_FIFO_KHR;
  VkExtent2D extent_{0, 0};
  std::vector<VkImage> images_;
  std::vector<VkSemaphore> rendered_;  // per swapchain image
  std::vector<VkSemaphore> acquired_;  // per frame slot
  std::uint32_t builds_ = 0;
  bool stale_ = false;
};

}  // namespace bounce::gpu
