#pragma once
// Device memory suballocation. vkAllocateMemory is slow and the number of allocations is
// limited (maxMemoryAllocationCount, often 4096), so resources share 64 MiB blocks, one set of
// blocks per memory type, carved up by OffsetAllocator (best fit + bufferImageGranularity).
// Large resources (more than half a block) and those the driver prefers dedicated
// (VkMemoryDedicatedRequirements) get their own VkDeviceMemory.
//
// Host-visible memory is always HOST_COHERENT here (no flush/invalidate needed) and mapped
// persistently once per block; Allocation::mapped points at the resource's bytes.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "engine/gpu/offset_allocator.hpp"
#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class Context;

enum class MemoryUsage {
  GpuOnly,   // device-local; filled by copies or shaders
  Upload,    // host-visible + coherent: staging, per-frame constants written by the CPU
  Readback,  // host-visible + coherent, preferably cached: GPU → CPU results
};

struct Allocation {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  VkDeviceSize size = 0;
  std::byte* mapped = nullptr;  // non-null for host-visible memory
  std::uint32_t memoryType = 0;
  std::int32_t block = -1;  // index into the allocator's blocks; -1 = dedicated
  explicit operator bool() const { return memory != VK_NULL_HANDLE; }
};

class MemoryAllocator {
 public:
  static constexpr VkDeviceSize kDefaultBlockSize = 64ull << 20;

  explicit MemoryAllocator(Context& ctx, VkDeviceSize blockSize = kDefaultBlockSize);
  ~MemoryAllocator();
  MemoryAllocator(const MemoryAllocator&) = delete;
  MemoryAllocator& operator=(const MemoryAllocator&) = delete;

  // Allocates and binds memory for a buffer / an image. `name` appears in error messages.
  Allocation allocateFor(VkBuffer buffer, MemoryUsage usage, const std::string& name);
  Allocation allocateFor(VkImage image, MemoryUsage usage, bool linearTiling, const std::string& name);
  void free(const Allocation& allocation);

  // Index of the memory type for `usage` among `typeBits`, or throws InternalError.
  std::uint32_t chooseMemoryType(std::uint32_t typeBits, MemoryUsage usage) const;

  struct Stats {
    std::size_t blocks = 0;          // live shared blocks
    std::size_t dedicated = 0;       // live dedicated allocations
    std::size_t suballocations = 0;  // live resources inside shared blocks
    VkDeviceSize reservedBytes = 0;  // blocks + dedicated
    VkDeviceSize usedBytes = 0;      // bytes of live resources
  };
  Stats stats() const;
  VkDeviceSize blockSize() const { return block_size_; }

 private:
  struct Block {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    std::uint32_t memoryType = 0;
    std::byte* mapped = nullptr;
    OffsetAllocator offsets;
  };
  Allocation allocate(const VkMemoryRequirements2& req, bool dedicated, VkBuffer buffer, VkImage image,
                      MemoryUsage usage, OffsetAllocator::Kind kind, const std::string& name);
  VkDeviceMemory allocateMemory(VkDeviceSize size, std::uint32_t type, VkBuffer buffer, VkImage image,
                                const std::string& name);

  Context& ctx_;
  VkDeviceSize block_size_;
  VkPhysicalDeviceMemoryProperties props_{};
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<Block>> blocks_;  // null slots are reused
  std::size_t dedicated_count_ = 0;
  VkDeviceSize dedicated_bytes_ = 0;
};

}  // namespace bounce::gpu
