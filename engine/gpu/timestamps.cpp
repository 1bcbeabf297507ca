#include "engine/gpu/timestamps.hpp"

#include "engine/core/error.hpp"
#include "engine/gpu/context.hpp"

namespace bounce::gpu {

TimestampPool::TimestampPool(Context& ctx, std::uint32_t maxScopes) : ctx_(ctx), max_scopes_(maxScopes) {
  std::uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &n, nullptr);
  std::vector<VkQueueFamilyProperties> fams(n);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &n, fams.data());
  std::uint32_t bits = fams.at(ctx.queueFamily()).timestampValidBits;
  supported_ = bits > 0 && ctx.limits().timestampPeriod > 0.0f;
  if (!supported_) return;
  valid_mask_ = bits >= 64 ? ~0ull : (1ull << bits) - 1;
  period_ns_ = ctx.limits().timestampPeriod;
  VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
  ci.queryCount = kQueriesPerScope * max_scopes_;
  check(vkCreateQueryPool(ctx.device(), &ci, nullptr, &pool_), "vkCreateQueryPool");
  ctx.setName(VK_OBJECT_TYPE_QUERY_POOL, pool_, "timestamps");
}

TimestampPool::~TimestampPool() {
  if (pool_) vkDestroyQueryPool(ctx_.device(), pool_, nullptr);
}

void TimestampPool::reset(VkCommandBuffer cmd) {
  scopes_.clear();
  open_.clear();
  dropped_ = 0;
  if (supported_) vkCmdResetQueryPool(cmd, pool_, 0, kQueriesPerScope * max_scopes_);
}

void TimestampPool::begin(VkCommandBuffer cmd, const std::string& name) {
  if (!supported_ || scopes_.size() >= max_scopes_) {
    dropped_ += supported_;
    open_.push_back(-1);
    return;
  }
  auto query = static_cast<std::uint32_t>(kQueriesPerScope * scopes_.size());
  scopes_.push_back({name, static_cast<std::uint32_t>(open_.size()), query});
  open_.push_back(static_cast<std::int64_t>(scopes_.size() - 1));
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, query);
  // A second stamp, never read, only to close the begin stamp's batch (see the header).
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, query + 2);
}

void TimestampPool::end(VkCommandBuffer cmd) {
  if (open_.empty()) throw InternalError("vulkan: timestamp end() without a matching begin()");
  std::int64_t index = open_.back();
  open_.pop_back();
  if (index < 0) return;
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, scopes_[index].query + 1);
}

std::vector<TimingResult> TimestampPool::resolve() {
  std::vector<TimingResult> out;
  if (!supported_ || scopes_.empty()) return out;
  if (!open_.empty()) throw InternalError("vulkan: timestamp scope '" + scopes_[0].name + "' is still open (end() missing)");
  std::vector<std::uint64_t> ticks(kQueriesPerScope * scopes_.size());
  check(vkGetQueryPoolResults(ctx_.device(), pool_, 0, static_cast<std::uint32_t>(ticks.size()),
                              ticks.size() * sizeof(std::uint64_t), ticks.data(), sizeof(std::uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
        "vkGetQueryPoolResults");
  for (auto& s : scopes_) {
    std::uint64_t t0 = ticks[s.query] & valid_mask_, t1 = ticks[s.query + 1] & valid_mask_;
    std::uint64_t delta = (t1 - t0) & valid_mask_;  // wraps correctly for < 64 valid bits
    out.push_back({s.name, s.depth, static_cast<double>(delta) * period_ns_ * 1e-6});
  }
  return out;
}

GpuScope::GpuScope(const Context& ctx, TimestampPool& pool, VkCommandBuffer cmd, const std::string& name)
    : ctx_(ctx), pool_(pool), cmd_(cmd) {
  ctx_.beginLabel(cmd_, name);
  pool_.begin(cmd_, name);
}

GpuScope::~GpuScope() {
  pool_.end(cmd_);
  ctx_.endLabel(cmd_);
}

}  // namespace bounce::gpu
