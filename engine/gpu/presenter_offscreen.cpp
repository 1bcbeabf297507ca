#include "engine/gpu/presenter_offscreen.hpp"

#include <cstring>
#include <memory>

#include "engine/core/error.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/frames.hpp"
#include "engine/gpu/image.hpp"

namespace bounce::gpu {

std::optional<PixelFormat> pixelFormatOf(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB: return PixelFormat::RGBA8;
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB: return PixelFormat::BGRA8;
    case VK_FORMAT_R16G16B16A16_SFLOAT: return PixelFormat::RGBA16F;
    case VK_FORMAT_R32G32B32A32_SFLOAT: return PixelFormat::RGBA32F;
    default: return std::nullopt;
  }
}

bool OffscreenPresenter::present(FrameRing& frames, Image& source) {
  bool capture = capture_next_;
  VkExtent3D e = source.extent();
  std::optional<PixelFormat> pf = pixelFormatOf(source.format());
  if (capture) {
    if (!pf)
      throw InternalError("vulkan: cannot capture image '" + source.name() + "' of format " +
                          std::to_string(static_cast<int>(source.format())) + " (RGBA8, RGBA16F or RGBA32F)");
    if (!(source.desc().usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT))
      throw InternalError("vulkan: capture of image '" + source.name() + "' needs TRANSFER_SRC usage");
    VkDeviceSize size = VkDeviceSize(e.width) * e.height * pixelBytes(*pf);
    if (!readback_ || readback_.size() < size) {
      frames.deferDelete([old = std::make_shared<Buffer>(std::move(readback_))] {});
      readback_ = Buffer(ctx_, {size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "capture readback"});
    }
    VkCommandBuffer cmd = frames.current().cmd;
    transition(cmd, source, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {e.width, e.height, 1};
    vkCmdCopyImageToBuffer(cmd, source.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle(), 1, &region);
    fullBarrier(cmd);  // transfer write → host read
  }
  frames.submit();
  ++presented_;
  if (capture) {
    frames.waitIdle();
    capture_ = CpuImage{e.width, e.height, *pf, {}};
    capture_.bytes.resize(VkDeviceSize(e.width) * e.height * pixelBytes(*pf));
    std::memcpy(capture_.bytes.data(), readback_.mapped(), capture_.bytes.size());
    capture_next_ = false;
  }
  return true;
}

}  // namespace bounce::gpu
