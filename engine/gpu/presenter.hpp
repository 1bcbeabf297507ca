#pragma once
// Presenter: where a finished frame goes. The renderer draws its final image (8-bit, tonemapped;
// or float for captures), then hands it over; the presenter records the copy into the current
// frame, submits the frame (FrameRing::submit) and shows or keeps the result.
//   OffscreenPresenter (presenter_offscreen.hpp): headless; reads frames back for captures.
//   SwapchainPresenter (presenter_swapchain.hpp): a GLFW window.
#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class FrameRing;
class Image;

class Presenter {
 public:
  virtual ~Presenter() = default;
  // The size the renderer should draw at (the window's framebuffer, or the capture size).
  virtual VkExtent2D extent() const = 0;
  // Ends the current frame of `frames` with `source` (mip 0, layer 0) as its picture. Returns
  // false when nothing was shown (window minimised, or swapchain out of date and recreated);
  // the frame is submitted either way.
  virtual bool present(FrameRing& frames, Image& source) = 0;
};

}  // namespace bounce::gpu
