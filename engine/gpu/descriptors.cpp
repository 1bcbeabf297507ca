#include "engine/gpu/descriptors.hpp"

#include <algorithm>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"

namespace bounce::gpu {

DescriptorSetLayout::DescriptorSetLayout(Context& ctx, const std::vector<Binding>& bindings, const std::string& name)
    : ctx_(&ctx), bindings_(bindings) {
  std::vector<VkDescriptorSetLayoutBinding> vk;
  for (auto& b : bindings) {
    for (auto& other : vk)
      if (other.binding == b.binding)
        throw InternalError("vulkan: descriptor layout '" + name + "' has binding " + std::to_string(b.binding) +
                            " twice");
    vk.push_back({b.binding, b.type, b.count, b.stages, nullptr});
  }
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.bindingCount = static_cast<std::uint32_t>(vk.size());
  ci.pBindings = vk.data();
  check(vkCreateDescriptorSetLayout(ctx.device(), &ci, nullptr, &layout_), "vkCreateDescriptorSetLayout");
  ctx.setName(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, layout_, name);
}

DescriptorSetLayout& DescriptorSetLayout::operator=(DescriptorSetLayout&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    bindings_ = std::move(o.bindings_);
  }
  return *this;
}

void DescriptorSetLayout::reset() {
  if (layout_) vkDestroyDescriptorSetLayout(ctx_->device(), layout_, nullptr);
  layout_ = VK_NULL_HANDLE;
}

DescriptorAllocator::DescriptorAllocator(Context& ctx, std::string name) : ctx_(ctx), name_(std::move(name)) {}

DescriptorAllocator::~DescriptorAllocator() {
  for (auto& p : pools_) vkDestroyDescriptorPool(ctx_.device(), p.pool, nullptr);
}

namespace {
// Per-set averages typical of our passes: a pool of N sets holds N·count descriptors of each.
constexpr std::pair<VkDescriptorType, std::uint32_t> kPerSet[] = {
    {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2},          {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4},
    {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 2},
    {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 1},          {VK_DESCRIPTOR_TYPE_SAMPLER, 1},
};
}  // namespace

void DescriptorAllocator::refill(Pool& pool) {
  pool.setsLeft = pool.capacity;
  for (std::size_t t = 0; t < kTypes; ++t) pool.left[t] = kPerSet[t].second * pool.capacity;
}

DescriptorAllocator::Pool DescriptorAllocator::createPool(std::uint32_t maxSets) {
  static_assert(std::size(kPerSet) == kTypes);
  std::vector<VkDescriptorPoolSize> sizes;
  for (auto [type, n] : kPerSet) sizes.push_back({type, n * maxSets});
  VkDescriptorPoolCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  ci.maxSets = maxSets;
  ci.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  ci.pPoolSizes = sizes.data();
  Pool p;
  p.capacity = maxSets;
  check(vkCreateDescriptorPool(ctx_.device(), &ci, nullptr, &p.pool), "vkCreateDescriptorPool");
  ctx_.setName(VK_OBJECT_TYPE_DESCRIPTOR_POOL, p.pool, name_ + " pool " + std::to_string(pools_.size()));
  refill(p);
  return p;
}

VkDescriptorSet DescriptorAllocator::allocate(const DescriptorSetLayout& layout) {
  std::uint32_t need[kTypes] = {};
  for (auto& b : layout.bindings()) {
    std::size_t t = 0;
    while (t < kTypes && kPerSet[t].first != b.type) ++t;
    if (t == kTypes)
      throw InternalError("vulkan: descriptor type " + std::to_string(static_cast<int>(b.type)) + " of binding " +
                          std::to_string(b.binding) + " is not one DescriptorAllocator pools hold");
    need[t] += b.count;
  }
  auto fits = [&](const Pool& p) {
    if (p.setsLeft == 0) return false;
    for (std::size_t t = 0; t < kTypes; ++t)
      if (need[t] > p.left[t]) return false;
    return true;
  };
  std::lock_guard lock(mutex_);
  VkDescriptorSetLayout handle = layout.handle();
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &handle;
  for (;;) {
    bool fresh = false;
    if (current_ == pools_.size()) {
      pools_.push_back(createPool(next_size_));
      next_size_ = std::min(next_size_ * 2, kMaxPoolSets);
      fresh = true;
    }
    Pool& p = pools_[current_];
    if (fits(p)) {
      ai.descriptorPool = p.pool;
      VkDescriptorSet set = VK_NULL_HANDLE;
      VkResult r = vkAllocateDescriptorSets(ctx_.device(), &ai, &set);
      if (r == VK_SUCCESS) {
        --p.setsLeft;
        for (std::size_t t = 0; t < kTypes; ++t) p.left[t] -= need[t];
        return set;
      }
      if (r != VK_ERROR_OUT_OF_POOL_MEMORY && r != VK_ERROR_FRAGMENTED_POOL) check(r, "vkAllocateDescriptorSets");
    }
    if (fresh) throw InternalError("vulkan: a descriptor set does not fit in a fresh pool of '" + name_ + "'");
    ++current_;  // this pool is full; move on to (or create) the next one
  }
}

void DescriptorAllocator::reset() {
  std::lock_guard lock(mutex_);
  for (auto& p : pools_) {
    check(vkResetDescriptorPool(ctx_.device(), p.pool, 0), "vkResetDescriptorPool");
    refill(p);
  }
  current_ = 0;
}

DescriptorWriter& DescriptorWriter::buffer(std::uint32_t binding, const Buffer& buffer, VkDescriptorType type,
                                           VkDeviceSize offset, VkDeviceSize range) {
  buffers_.push_back({buffer.handle(), offset, range});
  writes_.push_back({binding, type, buffers_.size() - 1});
  return *this;
}

DescriptorWriter& DescriptorWriter::storageImage(std::uint32_t binding, VkImageView view, VkImageLayout layout) {
  images_.push_back({VK_NULL_HANDLE, view, layout});
  writes_.push_back({binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, images_.size() - 1});
  return *this;
}

DescriptorWriter& DescriptorWriter::sampledImage(std::uint32_t binding, VkImageView view, VkSampler sampler,
                                                 VkImageLayout layout) {
  images_.push_back({sampler, view, layout});
  writes_.push_back({binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, images_.size() - 1});
  return *this;
}

void DescriptorWriter::update(const Context& ctx, VkDescriptorSet set) {
  std::vector<VkWriteDescriptorSet> vk;
  for (auto& w : writes_) {
    VkWriteDescriptorSet d{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    d.dstSet = set;
    d.dstBinding = w.binding;
    d.descriptorCount = 1;
    d.descriptorType = w.type;
    bool isImage = w.type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE || w.type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    if (isImage)
      d.pImageInfo = &images_[w.info];
    else
      d.pBufferInfo = &buffers_[w.info];
    vk.push_back(d);
  }
  vkUpdateDescriptorSets(ctx.device(), static_cast<std::uint32_t>(vk.size()), vk.data(), 0, nullptr);
}

SamplerCache::~SamplerCache() {
  for (auto& [desc, s] : samplers_) vkDestroySampler(ctx_.device(), s, nullptr);
}

VkSampler SamplerCache::get(const SamplerDesc& desc) {
  std::lock_guard lock(mutex_);
  auto it = samplers_.find(desc);
  if (it != samplers_.end()) return it->second;
  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  ci.magFilter = ci.minFilter = desc.filter;
  ci.mipmapMode = desc.mipmap;
  ci.addressModeU = ci.addressModeV = ci.addressModeW = desc.address;
  ci.anisotropyEnable = desc.maxAnisotropy > 1.0f && ctx_.enabledFeatures().samplerAnisotropy;
  ci.maxAnisotropy = std::min(desc.maxAnisotropy, ctx_.limits().maxSamplerAnisotropy);
  ci.compareEnable = desc.compare;
  ci.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  ci.minLod = 0.0f;
  ci.maxLod = VK_LOD_CLAMP_NONE;
  ci.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
  VkSampler s = VK_NULL_HANDLE;
  check(vkCreateSampler(ctx_.device(), &ci, nullptr, &s), "vkCreateSampler");
  samplers_.emplace(desc, s);
  return s;
}

}  // namespace bounce::gpu
