#pragma once
// Buffer: a VkBuffer with its memory, named for debuggers. Move-only; destroying it frees the
// memory at once, so a buffer still used by a frame in flight goes through
// FrameRing::deferDelete instead (frames.hpp).
#include <cstddef>
#include <string>

#include "engine/gpu/memory.hpp"
#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class Context;

struct BufferDesc {
  VkDeviceSize size = 0;
  VkBufferUsageFlags usage = 0;  // exactly what is asked: add TRANSFER_DST to upload by staging
  MemoryUsage memory = MemoryUsage::GpuOnly;
  std::string name;
};

class Buffer {
 public:
  Buffer() = default;
  Buffer(Context& ctx, const BufferDesc& desc);
  ~Buffer() { reset(); }
  Buffer(Buffer&& other) noexcept { *this = std::move(other); }
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  void reset();
  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return desc_.size; }
  VkBufferUsageFlags usage() const { return desc_.usage; }
  MemoryUsage memoryUsage() const { return desc_.memory; }
  const std::string& name() const { return desc_.name; }
  // Host pointer of Upload/Readback buffers. Null for GpuOnly buffers even where their memory is
  // host-visible (lavapipe, integrated GPUs), so code that works there works on discrete GPUs.
  std::byte* mapped() const { return desc_.memory == MemoryUsage::GpuOnly ? nullptr : allocation_.mapped; }
  const Allocation& allocation() const { return allocation_; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

 private:
  Context* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  Allocation allocation_;
  BufferDesc desc_;
};

}  // namespace bounce::gpu
