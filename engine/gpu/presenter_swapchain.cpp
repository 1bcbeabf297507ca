#include "engine/gpu/presenter_swapchain.hpp"

#include <algorithm>

#include "engine/core/error.hpp"
#include "engine/gpu/commands.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/frames.hpp"
#include "engine/gpu/image.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace bounce::gpu {
namespace {
VkSemaphore makeSemaphore(Context& ctx, const std::string& name) {
  VkSemaphoreCreateInfo ci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore s = VK_NULL_HANDLE;
  check(vkCreateSemaphore(ctx.device(), &ci, nullptr, &s), "vkCreateSemaphore");
  ctx.setName(VK_OBJECT_TYPE_SEMAPHORE, s, name);
  return s;
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags srcAccess,
                  VkAccessFlags dstAccess, VkPipelineStageFlags srcStage, VkPipelineStageFlags dstStage) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}
}  // namespace

SwapchainPresenter::SwapchainPresenter(Context& ctx, GLFWwindow* window, bool vsync)
    : ctx_(ctx), window_(window), vsync_(vsync) {
  if (!ctx.windowed()) throw InternalError("vulkan: SwapchainPresenter needs a Context created with windowed = true");
  check(glfwCreateWindowSurface(ctx.instance(), window, nullptr, &surface_), "glfwCreateWindowSurface");
  VkBool32 supported = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice(), ctx.queueFamily(), surface_, &supported);
  if (!supported) {
    vkDestroySurfaceKHR(ctx.instance(), surface_, nullptr);
    throw InternalError("vulkan: device '" + ctx.deviceName() + "' cannot present to this window");
  }
  try {
    build();
  } catch (...) {
    destroySwapchain(swapchain_);
    vkDestroySurfaceKHR(ctx.instance(), surface_, nullptr);
    throw;
  }
}

SwapchainPresenter::~SwapchainPresenter() {
  vkDeviceWaitIdle(ctx_.device());
  destroySwapchain(swapchain_);
  for (auto s : acquired_) vkDestroySemaphore(ctx_.device(), s, nullptr);
  vkDestroySurfaceKHR(ctx_.instance(), surface_, nullptr);
}

void SwapchainPresenter::destroySwapchain(VkSwapchainKHR swapchain) {
  for (auto s : rendered_) vkDestroySemaphore(ctx_.device(), s, nullptr);
  rendered_.clear();
  if (swapchain) vkDestroySwapchainKHR(ctx_.device(), swapchain, nullptr);
}

VkExtent2D SwapchainPresenter::framebufferSize() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {static_cast<std::uint32_t>(std::max(w, 0)), static_cast<std::uint32_t>(std::max(h, 0))};
}

void SwapchainPresenter::build() {
  VkPhysicalDevice pd = ctx_.physicalDevice();
  VkSurfaceCapabilitiesKHR caps;
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface_, &caps), "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");

  std::uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface_, &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface_, &n, formats.data());
  if (formats.empty()) throw InternalError("vulkan: the window surface offers no formats");
  // UNORM, not SRGB: the tonemap pass already wrote sRGB-encoded bytes, which a blit copies.
  VkSurfaceFormatKHR chosen = formats[0];
  for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM}) {
    auto it = std::find_if(formats.begin(), formats.end(), [&](auto& f) { return f.format == want; });
    if (it != formats.end()) {
      chosen = *it;
      break;
    }
  }
  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(pd, chosen.format, &fp);
  if (!(fp.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) ||
      !(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    throw InternalError("vulkan: the swapchain cannot be a blit destination on '" + ctx_.deviceName() + "'");

  n = 0;
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface_, &n, nullptr);
  std::vector<VkPresentModeKHR> modes(n);
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface_, &n, modes.data());
  present_mode_ = VK_PRESENT_MODE_FIFO_KHR;  // always supported
  if (!vsync_)
    for (VkPresentModeKHR want : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
      if (std::find(modes.begin(), modes.end(), want) != modes.end()) {
        present_mode_ = want;
        break;
      }

  VkExtent2D extent = caps.currentExtent;
  if (extent.width == 0xFFFFFFFFu) {
    VkExtent2D fb = framebufferSize();
    extent.width = std::clamp(fb.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(fb.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  std::uint32_t count = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);

  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface_;
  ci.minImageCount = count;
  ci.imageFormat = chosen.format;
  ci.imageColorSpace = chosen.colorSpace;
  ci.imageExtent = extent;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                          ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                          : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha &
                                                                     -caps.supportedCompositeAlpha);
  ci.presentMode = present_mode_;
  ci.clipped = VK_TRUE;
  VkSwapchainKHR old = swapchain_;
  ci.oldSwapchain = old;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  check(vkCreateSwapchainKHR(ctx_.device(), &ci, nullptr, &created), "vkCreateSwapchainKHR");
  destroySwapchain(old);  // also frees the old per-image semaphores
  swapchain_ = created;
  format_ = chosen.format;
  extent_ = extent;

  n = 0;
  vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, nullptr);
  images_.resize(n);
  vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &n, images_.data());
  for (std::uint32_t i = 0; i < n; ++i) {
    ctx_.setName(VK_OBJECT_TYPE_IMAGE, images_[i], "swapchain image " + std::to_string(i));
    rendered_.push_back(makeSemaphore(ctx_, "rendered " + std::to_string(i)));
  }
  ++builds_;
  stale_ = false;
}

void SwapchainPresenter::setVsync(bool vsync) {
  if (vsync == vsync_) return;
  vsync_ = vsync;
  stale_ = true;  // rebuilt at the next present
}

bool SwapchainPresenter::present(FrameRing& frames, Image& source) {
  VkExtent2D fb = framebufferSize();
  if (fb.width == 0 || fb.height == 0) {  // minimised: keep the frame loop going, show nothing
    frames.submit();
    return false;
  }
  if (stale_ || fb.width != extent_.width || fb.height != extent_.height) {
    ctx_.waitIdle();
    build();
  }
  Frame& frame = frames.current();
  while (acquired_.size() < frames.framesInFlight())
    acquired_.push_back(makeSemaphore(ctx_, "acquired " + std::to_string(acquired_.size())));
  VkSemaphore acquired = acquired_[frame.slot];

  std::uint32_t index = 0;
  VkResult r = vkAcquireNextImageKHR(ctx_.device(), swapchain_, UINT64_MAX, acquired, VK_NULL_HANDLE, &index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) {
    frames.submit();
    stale_ = true;
    return false;
  }
  if (r != VK_SUBOPTIMAL_KHR) check(r, "vkAcquireNextImageKHR");
  if (r == VK_SUBOPTIMAL_KHR) stale_ = true;

  VkCommandBuffer cmd = frame.cmd;
  VkImage target = images_[index];
  transition(cmd, source, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  // The acquire semaphore is waited at TRANSFER, so the layout change is ordered after it.
  imageBarrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
               VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
  VkExtent3D se = source.extent();
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {static_cast<std::int32_t>(se.width), static_cast<std::int32_t>(se.height), 1};
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.dstOffsets[1] = {static_cast<std::int32_t>(extent_.width), static_cast<std::int32_t>(extent_.height), 1};
  VkFilter filter = (se.width == extent_.width && se.height == extent_.height) ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
  vkCmdBlitImage(cmd, source.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, filter);
  imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
               VK_ACCESS_TRANSFER_WRITE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
  frames.submit({acquired}, {VK_PIPELINE_STAGE_TRANSFER_BIT}, {rendered_[index]});

  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &rendered_[index];
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &index;
  r = ctx_.present(pi);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) {
    stale_ = true;
    return r == VK_SUBOPTIMAL_KHR;  // a suboptimal present still showed the frame
  }
  check(r, "vkQueuePresentKHR");
  return true;
}

}  // namespace bounce::gpu
