#include "engine/gpu/memory.hpp"

#include <string>

#include "engine/core/error.hpp"
#include "engine/gpu/context.hpp"

namespace bounce::gpu {
namespace {
const char* usageName(MemoryUsage u) {
  switch (u) {
    case MemoryUsage::GpuOnly: return "gpu-only";
    case MemoryUsage::Upload: return "upload";
    case MemoryUsage::Readback: return "readback";
  }
  return "?";
}
}  // namespace

MemoryAllocator::MemoryAllocator(Context& ctx, VkDeviceSize blockSize) : ctx_(ctx), block_size_(blockSize) {
  vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &props_);
}

MemoryAllocator::~MemoryAllocator() {
  for (auto& b : blocks_)
    if (b) vkFreeMemory(ctx_.device(), b->memory, nullptr);  // freeing unmaps
}

std::uint32_t MemoryAllocator::chooseMemoryType(std::uint32_t typeBits, MemoryUsage usage) const {
  VkMemoryPropertyFlags required = 0, preferred = 0;
  switch (usage) {
    case MemoryUsage::GpuOnly: preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
    case MemoryUsage::Upload:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      break;
    case MemoryUsage::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;  // CPU reads of uncached memory crawl
      break;
  }
  int best = -1, bestScore = -1;
  for (std::uint32_t i = 0; i < props_.memoryTypeCount; ++i) {
    if (!(typeBits & (1u << i))) continue;
    VkMemoryPropertyFlags f = props_.memoryTypes[i].propertyFlags;
    if ((f & required) != required) continue;
    int score = (f & preferred) == preferred ? 2 : 0;
    // Upload heaps: plain host memory first, so small device-local BAR space is kept for others.
    if (usage == MemoryUsage::Upload && !(f & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)) score += 1;
    if (score > bestScore) {
      best = static_cast<int>(i);
      bestScore = score;
    }
  }
  if (best < 0)
    throw InternalError(std::string("vulkan: no memory type for ") + usageName(usage) + " memory among type bits " +
                        std::to_string(typeBits));
  return static_cast<std::uint32_t>(best);
}

VkDeviceMemory MemoryAllocator::allocateMemory(VkDeviceSize size, std::uint32_t type, VkBuffer buffer, VkImage image,
                                               const std::string& name) {
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = size;
  ai.memoryTypeIndex = type;
  VkMemoryDedicatedAllocateInfo dedicated{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO};
  dedicated.buffer = buffer;
  dedicated.image = image;
  if (buffer || image) ai.pNext = &dedicated;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkResult r = vkAllocateMemory(ctx_.device(), &ai, nullptr, &memory);
  if (r != VK_SUCCESS)
    throw InternalError("vulkan: allocating " + std::to_string(size >> 20) + " MiB of memory type " +
                        std::to_string(type) + " for '" + name + "' failed: " + resultName(r));
  return memory;
}

Allocation MemoryAllocator::allocate(const VkMemoryRequirements2& req2, bool dedicated, VkBuffer buffer, VkImage image,
                                     MemoryUsage usage, OffsetAllocator::Kind kind, const std::string& name) {
  const VkMemoryRequirements& req = req2.memoryRequirements;
  std::uint32_t type = chooseMemoryType(req.memoryTypeBits, usage);
  bool hostVisible = props_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
  std::lock_guard lock(mutex_);
  Allocation a;
  a.memoryType = type;
  a.size = req.size;
  if (dedicated || req.size > block_size_ / 2) {
    a.memory = allocateMemory(req.size, type, buffer, image, name);
    if (hostVisible) {
      void* p = nullptr;
      check(vkMapMemory(ctx_.device(), a.memory, 0, VK_WHOLE_SIZE, 0, &p), "vkMapMemory");
      a.mapped = static_cast<std::byte*>(p);
    }
    ++dedicated_count_;
    dedicated_bytes_ += req.size;
    return a;
  }
  VkDeviceSize granularity = ctx_.limits().bufferImageGranularity;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    Block* b = blocks_[i].get();
    if (!b || b->memoryType != type) continue;
    if (auto off = b->offsets.allocate(req.size, req.alignment, kind)) {
      a.memory = b->memory;
      a.offset = *off;
      a.mapped = b->mapped ? b->mapped + *off : nullptr;
      a.block = static_cast<std::int32_t>(i);
      return a;
    }
  }
  auto block = std::make_unique<Block>(Block{VK_NULL_HANDLE, type, nullptr, OffsetAllocator(block_size_, granularity)});
  block->memory = allocateMemory(block_size_, type, VK_NULL_HANDLE, VK_NULL_HANDLE, name);
  if (hostVisible) {
    void* p = nullptr;
    check(vkMapMemory(ctx_.device(), block->memory, 0, VK_WHOLE_SIZE, 0, &p), "vkMapMemory");
    block->mapped = static_cast<std::byte*>(p);
  }
  auto off = block->offsets.allocate(req.size, req.alignment, kind);  // fits: size <= half a block
  std::size_t slot = blocks_.size();
  for (std::size_t i = 0; i < blocks_.size(); ++i)
    if (!blocks_[i]) {
      slot = i;
      break;
    }
  a.memory = block->memory;
  a.offset = *off;
  a.mapped = block->mapped ? block->mapped + *off : nullptr;
  a.block = static_cast<std::int32_t>(slot);
  if (slot == blocks_.size())
    blocks_.push_back(std::move(block));
  else
    blocks_[slot] = std::move(block);
  return a;
}

Allocation MemoryAllocator::allocateFor(VkBuffer buffer, MemoryUsage usage, const std::string& name) {
  VkBufferMemoryRequirementsInfo2 info{VK_STRUCTURE_TYPE_BUFFER_MEMORY_REQUIREMENTS_INFO_2};
  info.buffer = buffer;
  VkMemoryDedicatedRequirements ded{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS};
  VkMemoryRequirements2 req{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
  req.pNext = &ded;
  vkGetBufferMemoryRequirements2(ctx_.device(), &info, &req);
  bool dedicated = ded.prefersDedicatedAllocation || ded.requiresDedicatedAllocation;
  Allocation a = allocate(req, dedicated, buffer, VK_NULL_HANDLE, usage, OffsetAllocator::Kind::Linear, name);
  check(vkBindBufferMemory(ctx_.device(), buffer, a.memory, a.offset), "vkBindBufferMemory");
  return a;
}

Allocation MemoryAllocator::allocateFor(VkImage image, MemoryUsage usage, bool linearTiling, const std::string& name) {
  VkImageMemoryRequirementsInfo2 info{VK_STRUCTURE_TYPE_IMAGE_MEMORY_REQUIREMENTS_INFO_2};
  info.image = image;
  VkMemoryDedicatedRequirements ded{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS};
  VkMemoryRequirements2 req{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
  req.pNext = &ded;
  vkGetImageMemoryRequirements2(ctx_.device(), &info, &req);
  bool dedicated = ded.prefersDedicatedAllocation || ded.requiresDedicatedAllocation;
  auto kind = linearTiling ? OffsetAllocator::Kind::Linear : OffsetAllocator::Kind::Optimal;
  Allocation a = allocate(req, dedicated, VK_NULL_HANDLE, image, usage, kind, name);
  check(vkBindImageMemory(ctx_.device(), image, a.memory, a.offset), "vkBindImageMemory");
  return a;
}

void MemoryAllocator::free(const Allocation& a) {
  if (!a) return;
  std::lock_guard lock(mutex_);
  if (a.block < 0) {
    vkFreeMemory(ctx_.device(), a.memory, nullptr);
    --dedicated_count_;
    dedicated_bytes_ -= a.size;
    return;
  }
  auto idx = static_cast<std::size_t>(a.block);
  if (idx >= blocks_.size() || !blocks_[idx] || blocks_[idx]->memory != a.memory)
    throw InternalError("vulkan: freeing an allocation of an unknown memory block");
  Block& b = *blocks_[idx];
  b.offsets.free(a.offset);
  // Keep one empty block per type around, so a resource churning at a block's edge does not
  // allocate and free 64 MiB every frame; release the others.
  if (b.offsets.empty()) {
    std::size_t emptySameType = 0;
    for (auto& other : blocks_)
      if (other && other->memoryType == b.memoryType && other->offsets.empty()) ++emptySameType;
    if (emptySameType > 1) {
      vkFreeMemory(ctx_.device(), b.memory, nullptr);
      blocks_[idx].reset();
    }
  }
}

MemoryAllocator::Stats MemoryAllocator::stats() const {
  std::lock_guard lock(mutex_);
  Stats s;
  s.dedicated = dedicated_count_;
  s.reservedBytes = dedicated_bytes_;
  s.usedBytes = dedicated_bytes_;
  for (auto& b : blocks_) {
    if (!b) continue;
    ++s.blocks;
    s.suballocations += b->offsets.allocationCount();
    s.reservedBytes += b->offsets.capacity();
    s.usedBytes += b->offsets.usedBytes();
  }
  return s;
}

}  // namespace bounce::gpu
