#include "engine/gpu/commands.hpp"

#include <cstring>
#include <mutex>
#include <string>

#include "engine/core/error.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/format.hpp"
#include "engine/gpu/image.hpp"

namespace bounce::gpu {

void submitAndWait(Context& ctx, const std::function<void(VkCommandBuffer)>& record) {
  std::lock_guard lock(ctx.oneShotMutex());
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = ctx.oneShotPool();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  check(vkAllocateCommandBuffers(ctx.device(), &ai, &cmd), "vkAllocateCommandBuffers");
  VkFence fence = VK_NULL_HANDLE;
  auto cleanup = [&] {
    if (fence) vkDestroyFence(ctx.device(), fence, nullptr);
    vkFreeCommandBuffers(ctx.device(), ctx.oneShotPool(), 1, &cmd);
  };
  try {
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
    record(cmd);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(ctx.device(), &fi, nullptr, &fence), "vkCreateFence");
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    ctx.submit(si, fence);
    check(vkWaitForFences(ctx.device(), 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  } catch (...) {
    cleanup();
    throw;
  }
  cleanup();
}

void upload(Context& ctx, Buffer& buffer, std::span<const std::uint8_t> bytes, VkDeviceSize offset) {
  if (offset > buffer.size() || bytes.size() > buffer.size() - offset)
    throw InternalError("vulkan: upload of " + std::to_string(bytes.size()) + " bytes at offset " +
                        std::to_string(offset) + " overruns buffer '" + buffer.name() + "' of " +
                        std::to_string(buffer.size()) + " bytes");
  if (bytes.empty()) return;
  if (buffer.mapped()) {
    std::memcpy(buffer.mapped() + offset, bytes.data(), bytes.size());
    return;
  }
  if (!(buffer.usage() & VK_BUFFER_USAGE_TRANSFER_DST_BIT))
    throw InternalError("vulkan: upload to buffer '" + buffer.name() + "' needs TRANSFER_DST usage");
  Buffer staging(ctx, {bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging upload"});
  std::memcpy(staging.mapped(), bytes.data(), bytes.size());
  submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, offset, bytes.size()};
    vkCmdCopyBuffer(cmd, staging.handle(), buffer.handle(), 1, &region);
  });
}

std::vector<std::uint8_t> readback(Context& ctx, const Buffer& buffer) {
  std::vector<std::uint8_t> out(buffer.size());
  if (buffer.mapped()) {
    std::memcpy(out.data(), buffer.mapped(), out.size());
    return out;
  }
  if (!(buffer.usage() & VK_BUFFER_USAGE_TRANSFER_SRC_BIT))
    throw InternalError("vulkan: readback of buffer '" + buffer.name() + "' needs TRANSFER_SRC usage");
  Buffer staging(ctx, {buffer.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "staging readback"});
  submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    fullBarrier(cmd);  // earlier shader writes → transfer read
    VkBufferCopy region{0, 0, buffer.size()};
    vkCmdCopyBuffer(cmd, buffer.handle(), staging.handle(), 1, &region);
  });
  std::memcpy(out.data(), staging.mapped(), out.size());
  return out;
}

namespace {
// Bytes of mip `mip` over all layers and slices, and the matching copy region.
VkDeviceSize mipBytes(const Image& image, std::uint32_t mip, VkBufferImageCopy* region) {
  VkExtent3D e = image.extent(mip);
  if (region) {
    *region = {};
    VkImageAspectFlags a = image.aspect();
    region->imageSubresource = {(a & VK_IMAGE_ASPECT_DEPTH_BIT) ? VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT) : a, mip, 0,
                                image.desc().layers};
    region->imageExtent = e;
  }
  return VkDeviceSize(texelBytes(image.format())) * e.width * e.height * e.depth * image.desc().layers;
}
}  // namespace

void upload(Context& ctx, Image& image, std::span<const std::uint8_t> bytes, std::uint32_t mip,
            VkImageLayout finalLayout) {
  if (mip >= image.desc().mipLevels)
    throw InternalError("vulkan: upload to mip " + std::to_string(mip) + " of image '" + image.name() + "' with " +
                        std::to_string(image.desc().mipLevels) + " mips");
  VkBufferImageCopy region;
  VkDeviceSize need = mipBytes(image, mip, &region);
  if (bytes.size() != need)
    throw InternalError("vulkan: upload to image '" + image.name() + "' got " + std::to_string(bytes.size()) +
                        " bytes (expected " + std::to_string(need) + ")");
  if (!(image.desc().usage & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    throw InternalError("vulkan: upload to image '" + image.name() + "' needs TRANSFER_DST usage");
  Buffer staging(ctx, {need, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload, "staging image upload"});
  std::memcpy(staging.mapped(), bytes.data(), bytes.size());
  submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    transition(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transition(cmd, image, finalLayout);
  });
}

std::vector<std::uint8_t> readback(Context& ctx, Image& image, std::uint32_t mip) {
  if (mip >= image.desc().mipLevels)
    throw InternalError("vulkan: readback of mip " + std::to_string(mip) + " of image '" + image.name() + "' with " +
                        std::to_string(image.desc().mipLevels) + " mips");
  if (!(image.desc().usage & VK_IMAGE_USAGE_TRANSFER_SRC_BIT))
    throw InternalError("vulkan: readback of image '" + image.name() + "' needs TRANSFER_SRC usage");
  VkBufferImageCopy region;
  VkDeviceSize need = mipBytes(image, mip, &region);
  Buffer staging(ctx, {need, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback, "staging image readback"});
  VkImageLayout previous = image.layout();
  submitAndWait(ctx, [&](VkCommandBuffer cmd) {
    transition(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1, &region);
    if (previous != VK_IMAGE_LAYOUT_UNDEFINED && previous != VK_IMAGE_LAYOUT_PREINITIALIZED)
      transition(cmd, image, previous);
    fullBarrier(cmd);  // transfer write → host read happens at the fence, but be explicit
  });
  std::vector<std::uint8_t> out(need);
  std::memcpy(out.data(), staging.mapped(), out.size());
  return out;
}

void transition(VkCommandBuffer cmd, Image& image, VkImageLayout newLayout) {
  transition(cmd, image, newLayout, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
             VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
}

void transition(VkCommandBuffer cmd, Image& image, VkImageLayout newLayout, VkPipelineStageFlags src,
                VkAccessFlags srcAccess, VkPipelineStageFlags dst, VkAccessFlags dstAccess) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  b.oldLayout = image.layout();
  b.newLayout = newLayout;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image.handle();
  b.subresourceRange = image.fullRange();
  vkCmdPipelineBarrier(cmd, src, dst, 0, 0, nullptr, 0, nullptr, 1, &b);
  image.setLayout(newLayout);
}

void fullBarrier(VkCommandBuffer cmd) {
  VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT | VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &b, 0, nullptr, 0,
                       nullptr);
}

}  // namespace bounce::gpu
