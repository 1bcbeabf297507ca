#pragma once
// Descriptors without bindless (lavapipe has no descriptor indexing):
//  - DescriptorSetLayout from a plain binding list;
//  - DescriptorAllocator: a list of pools that grows when one is full (sizes double up to a cap)
//    and is reset wholesale — one per frame in flight, reset when that frame begins. "Full" is
//    counted here (sets and descriptors of each type left), not left to the driver: some
//    drivers (lavapipe) never report a full pool, and the growth must be the same everywhere;
//  - DescriptorWriter: collects buffer / image / sampler writes and applies them in one call;
//  - SamplerCache: one VkSampler per distinct SamplerDesc, alive as long as the cache.
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class Context;
class Buffer;

struct Binding {
  std::uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  VkShaderStageFlags stages = VK_SHADER_STAGE_ALL;
  std::uint32_t count = 1;
};

class DescriptorSetLayout {
 public:
  DescriptorSetLayout() = default;
  DescriptorSetLayout(Context& ctx, const std::vector<Binding>& bindings, const std::string& name);
  ~DescriptorSetLayout() { reset(); }
  DescriptorSetLayout(DescriptorSetLayout&& o) noexcept { *this = std::move(o); }
  DescriptorSetLayout& operator=(DescriptorSetLayout&& o) noexcept;
  DescriptorSetLayout(const DescriptorSetLayout&) = delete;
  DescriptorSetLayout& operator=(const DescriptorSetLayout&) = delete;
  void reset();
  VkDescriptorSetLayout handle() const { return layout_; }
  const std::vector<Binding>& bindings() const { return bindings_; }

 private:
  Context* ctx_ = nullptr;
  VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
  std::vector<Binding> bindings_;
};

class DescriptorAllocator {
 public:
  static constexpr std::uint32_t kFirstPoolSets = 64;
  static constexpr std::uint32_t kMaxPoolSets = 4096;

  explicit DescriptorAllocator(Context& ctx, std::string name = "descriptors");
  ~DescriptorAllocator();
  DescriptorAllocator(const DescriptorAllocator&) = delete;
  DescriptorAllocator& operator=(const DescriptorAllocator&) = delete;

  // A set valid until the next reset(). Throws InternalError if even a fresh pool cannot hold it.
  VkDescriptorSet allocate(const DescriptorSetLayout& layout);
  // Frees every set at once and keeps the pools for reuse.
  void reset();
  std::size_t poolCount() const { return pools_.size(); }

 private:
  static constexpr std::size_t kTypes = 6;  // descriptor types the pools hold (descriptors.cpp)
  struct Pool {
    VkDescriptorPool pool = VK_NULL_HANDLE;
    std::uint32_t setsLeft = 0;
    std::uint32_t left[kTypes] = {};  // descriptors left per type
    std::uint32_t capacity = 0;       // maxSets
  };
  Pool createPool(std::uint32_t maxSets);
  static void refill(Pool& pool);
  Context& ctx_;
  std::string name_;
  std::vector<Pool> pools_;
  std::size_t current_ = 0;
  std::uint32_t next_size_ = kFirstPoolSets;
  std::mutex mutex_;
};

class DescriptorWriter {
 public:
  DescriptorWriter& buffer(std::uint32_t binding, const Buffer& buffer,
                           VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VkDeviceSize offset = 0,
                           VkDeviceSize range = VK_WHOLE_SIZE);
  DescriptorWriter& storageImage(std::uint32_t binding, VkImageView view,
                                 VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL);
  DescriptorWriter& sampledImage(std::uint32_t binding, VkImageView view, VkSampler sampler,
                                 VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  void update(const Context& ctx, VkDescriptorSet set);

 private:
  struct Write {
    std::uint32_t binding;
    VkDescriptorType type;
    std::size_t info;  // index into buffers_ or images_
  };
  std::vector<Write> writes_;
  std::deque<VkDescriptorBufferInfo> buffers_;
  std::deque<VkDescriptorImageInfo> images_;
};

struct SamplerDesc {
  VkFilter filter = VK_FILTER_LINEAR;
  VkSamplerMipmapMode mipmap = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  float maxAnisotropy = 1.0f;  // > 1 only when the device enables samplerAnisotropy
  bool compare = false;        // depth comparison (shadow maps), LESS_OR_EQUAL
  auto key() const { return std::tuple(filter, mipmap, address, maxAnisotropy, compare); }
  bool operator<(const SamplerDesc& o) const { return key() < o.key(); }
};

class SamplerCache {
 public:
  explicit SamplerCache(Context& ctx) : ctx_(ctx) {}
  ~SamplerCache();
  SamplerCache(const SamplerCache&) = delete;
  SamplerCache& operator=(const SamplerCache&) = delete;
  VkSampler get(const SamplerDesc& desc);
  std::size_t size() const { return samplers_.size(); }

 private:
  Context& ctx_;
  std::map<SamplerDesc, VkSampler> samplers_;
  std::mutex mutex_;
};

}  // namespace bounce::gpu
