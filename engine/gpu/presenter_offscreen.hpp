#pragma once
// Headless presenter: no window, no surface. present() submits the frame; when a capture was
// requested it also copies the source image into a host-visible buffer, waits for the frame and
// keeps the pixels (RGBA8, BGRA8, RGBA16F or RGBA32F, as the source is).
#include <cstdint>
#include <optional>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/image_io.hpp"
#include "engine/gpu/presenter.hpp"

namespace bounce::gpu {

class Context;

// The PixelFormat of a readable VkFormat, or nullopt.
std::optional<PixelFormat> pixelFormatOf(VkFormat format);

class OffscreenPresenter : public Presenter {
 public:
  OffscreenPresenter(Context& ctx, VkExtent2D extent) : ctx_(ctx), extent_(extent) {}
  VkExtent2D extent() const override { return extent_; }
  void resize(VkExtent2D extent) { extent_ = extent; }

  // The next present() reads its source back; capture() then holds the pixels.
  void requestCapture() { capture_next_ = true; }
  bool present(FrameRing& frames, Image& source) override;
  const CpuImage& capture() const { return capture_; }
  std::uint64_t presentedFrames() const { return presented_; }

 private:
  Context& ctx_;
  VkExtent2D extent_;
  bool capture_next_ = false;
  Buffer readback_;
  CpuImage capture_;
  std::uint64_t presented_ = 0;
};

}  // namespace bounce::gpu
