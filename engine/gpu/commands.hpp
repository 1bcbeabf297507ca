#pragma once
// One-shot command recording and CPU ↔ GPU copies. These wait for the GPU: use them for loading
// and tests and captures, not inside the frame loop (frames.hpp records into the frame's
// command buffer instead).
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class Context;
class Buffer;
class Image;

// Records `record` into a fresh command buffer, submits it and waits for it to finish.
void submitAndWait(Context& ctx, const std::function<void(VkCommandBuffer)>& record);

// Copies `bytes` to `buffer` at `offset`: a memcpy for host-visible buffers, else through a
// staging buffer (the buffer then needs TRANSFER_DST usage). Checks the range.
void upload(Context& ctx, Buffer& buffer, std::span<const std::uint8_t> bytes, VkDeviceSize offset = 0);
// Every byte of `buffer` (host-visible: a memcpy; else staging, needs TRANSFER_SRC usage).
std::vector<std::uint8_t> readback(Context& ctx, const Buffer& buffer);

// Fills mip `mip` of every layer (and depth slice) of `image` from tightly packed texels, layer
// after layer, rows top to bottom; the size must match exactly. Needs TRANSFER_DST usage.
// The whole image ends in `finalLayout`.
void upload(Context& ctx, Image& image, std::span<const std::uint8_t> bytes, std::uint32_t mip = 0,
            VkImageLayout finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
// Mip `mip` of every layer, packed as upload() takes it. Needs TRANSFER_SRC usage. The image
// returns to the layout it had (TRANSFER_SRC when it had none).
std::vector<std::uint8_t> readback(Context& ctx, Image& image, std::uint32_t mip = 0);

// Whole-image layout change with a full (ALL_COMMANDS → ALL_COMMANDS) barrier. Correct and
// simple; the render graph derives precise barriers instead.
void transition(VkCommandBuffer cmd, Image& image, VkImageLayout newLayout);
// The same layout transition between exactly these stages and accesses, for a per-frame barrier
// where the full one above would drain the whole GPU.
void transition(VkCommandBuffer cmd, Image& image, VkImageLayout newLayout, VkPipelineStageFlags src,
                VkAccessFlags srcAccess, VkPipelineStageFlags dst, VkAccessFlags dstAccess);

// Full memory barrier between everything before and after (tests, one-shot work).
void fullBarrier(VkCommandBuffer cmd);

}  // namespace bounce::gpu
