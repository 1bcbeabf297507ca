#include "engine/gpu/pipeline_table.hpp"

#include "engine/gpu/context.hpp"

namespace bounce::gpu {
namespace {

void put(std::string& key, std::uint32_t v) { key.append(reinterpret_cast<const char*>(&v), sizeof v); }

}  // namespace

PipelineTable::PipelineTable(Context& ctx, bool reuse) : ctx_(ctx), reuse_(reuse) {}

PipelineTable::~PipelineTable() {
  // Pipelines first (they were created with these layouts), then pipeline layouts, then set layouts.
  for (auto& [key, p] : pipelines_) vkDestroyPipeline(ctx_.device(), p, nullptr);
  for (auto& [key, l] : layouts_) vkDestroyPipelineLayout(ctx_.device(), l.layout, nullptr);
  for (auto& [key, l] : layouts_)
    for (VkDescriptorSetLayout s : l.sets) vkDestroyDescriptorSetLayout(ctx_.device(), s, nullptr);
}

PipelineTable::Counts PipelineTable::counts() const {
  std::lock_guard lock(mutex_);
  return {built_, reused_, pipelines_.size()};
}

std::string PipelineTable::layoutKey(const PipelineLayout& layout) {
  std::string key;
  put(key, std::uint32_t(layout.setBindings().size()));
  for (const auto& set : layout.setBindings()) {
    put(key, std::uint32_t(set.size()));
    for (const Binding& b : set) {
      put(key, b.binding);
      put(key, std::uint32_t(b.type));
      put(key, b.count);
      put(key, b.stages);
    }
  }
  put(key, std::uint32_t(layout.pushConstants().size()));
  for (const VkPushConstantRange& r : layout.pushConstants()) {
    put(key, r.stageFlags);
    put(key, r.offset);
    put(key, r.size);
  }
  return key;
}

VkPipelineLayout PipelineTable::ownLayout(const std::string& key, const PipelineLayout& layout) {
  auto it = layouts_.find(key);
  if (it != layouts_.end()) return it->second.layout;
  OwnedLayout own;
  try {
    for (const auto& set : layout.setBindings()) {
      std::vector<VkDescriptorSetLayoutBinding> vk;
      for (const Binding& b : set) vk.push_back({b.binding, b.type, b.count, b.stages, nullptr});
      VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
      ci.bindingCount = std::uint32_t(vk.size());
      ci.pBindings = vk.data();
      VkDescriptorSetLayout s = VK_NULL_HANDLE;
      check(vkCreateDescriptorSetLayout(ctx_.device(), &ci, nullptr, &s), "vkCreateDescriptorSetLayout");
      own.sets.push_back(s);
      ctx_.setName(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, s, "pipeline table");
    }
    VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    ci.setLayoutCount = std::uint32_t(own.sets.size());
    ci.pSetLayouts = own.sets.data();
    ci.pushConstantRangeCount = std::uint32_t(layout.pushConstants().size());
    ci.pPushConstantRanges = layout.pushConstants().data();
    check(vkCreatePipelineLayout(ctx_.device(), &ci, nullptr, &own.layout), "vkCreatePipelineLayout");
    ctx_.setName(VK_OBJECT_TYPE_PIPELINE_LAYOUT, own.layout, "pipeline table");
  } catch (...) {
    for (VkDescriptorSetLayout s : own.sets) vkDestroyDescriptorSetLayout(ctx_.device(), s, nullptr);
    throw;
  }
  return layouts_.emplace(key, std::move(own)).first->second.layout;
}

Pipeline PipelineTable::obtain(const std::string& key, const PipelineLayout& layout, VkPipelineBindPoint bindPoint,
                               const std::string& name, const Build& build) {
  if (!reuse_) {
    VkPipeline p = build(layout.handle());
    ctx_.setName(VK_OBJECT_TYPE_PIPELINE, p, name);
    std::lock_guard lock(mutex_);
    ++built_;
    return Pipeline(ctx_, p, bindPoint, layout.handle());
  }
  const std::string layoutBytes = layoutKey(layout);
  const std::string fullKey = key + layoutBytes;
  VkPipelineLayout own = VK_NULL_HANDLE;
  {
    std::lock_guard lock(mutex_);
    if (auto it = pipelines_.find(fullKey); it != pipelines_.end()) {
      ++reused_;
      return Pipeline(ctx_, it->second, bindPoint, layout.handle(), true);
    }
    own = ownLayout(layoutBytes, layout);  // lives as long as the table: safe to use unlocked
  }
  VkPipeline p = build(own);  // outside the lock: the driver's work, seconds for SL's shaders
  std::lock_guard lock(mutex_);
  ++built_;
  auto [it, inserted] = pipelines_.emplace(fullKey, p);
  if (inserted)
    ctx_.setName(VK_OBJECT_TYPE_PIPELINE, p, name);
  else
    vkDestroyPipeline(ctx_.device(), p, nullptr);  // another thread built the same one meanwhile
  return Pipeline(ctx_, it->second, bindPoint, layout.handle(), true);
}

}  // namespace bounce::gpu
