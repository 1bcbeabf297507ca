#include <algorithm>
#include "engine/gpu/frames.hpp"

#include "engine/core/error.hpp"
#include "engine/gpu/context.hpp"

namespace bounce::gpu {

FrameRing::FrameRing(Context& ctx, std::uint32_t framesInFlight) : ctx_(ctx) {
  if (framesInFlight == 0) throw InternalError("vulkan: a frame ring needs at least one frame");
  frames_.resize(framesInFlight);
  for (std::uint32_t i = 0; i < framesInFlight; ++i) {
    Frame& f = frames_[i];
    f.slot = i;
    VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pi.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pi.queueFamilyIndex = ctx.queueFamily();
    check(vkCreateCommandPool(ctx.device(), &pi, nullptr, &f.pool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = f.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    check(vkAllocateCommandBuffers(ctx.device(), &ai, &f.cmd), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // the first begin() must not wait
    check(vkCreateFence(ctx.device(), &fi, nullptr, &f.fence), "vkCreateFence");
    std::string tag = "frame " + std::to_string(i);
    ctx.setName(VK_OBJECT_TYPE_COMMAND_BUFFER, f.cmd, tag + " commands");
    ctx.setName(VK_OBJECT_TYPE_FENCE, f.fence, tag + " fence");
    f.descriptors = std::make_unique<DescriptorAllocator>(ctx, tag + " descriptors");
    f.timestamps = std::make_unique<TimestampPool>(ctx);
  }
  current_ = framesInFlight - 1;  // begin() advances to slot 0
}

FrameRing::~FrameRing() {
  vkDeviceWaitIdle(ctx_.device());
  for (auto& f : frames_) {
    for (auto& d : f.deletions) d();
    f.deletions.clear();
    f.descriptors.reset();
    f.timestamps.reset();
    vkDestroyFence(ctx_.device(), f.fence, nullptr);
    vkDestroyCommandPool(ctx_.device(), f.pool, nullptr);
  }
}

void FrameRing::retire(Frame& f) {
  for (auto& d : f.deletions) d();
  f.deletions.clear();
  if (f.number > 0 && !f.retired) {
    f.retired = true;
    auto timings = f.timestamps->resolve();
    if (!timings.empty()) {
      resolved_.push_back({f.number, timings});
      if (f.number > last_timings_frame_) {
        last_timings_ = std::move(timings);
        last_timings_frame_ = f.number;
      }
    }
  }
}

std::vector<ResolvedTimings> FrameRing::takeResolvedTimings() {
  std::vector<ResolvedTimings> out = std::move(resolved_);
  resolved_.clear();
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.frame < b.frame; });
  return out;
}

Frame& FrameRing::begin() {
  if (frames_[current_].recording) throw InternalError("vulkan: FrameRing::begin() while a frame is recording");
  current_ = (current_ + 1) % frames_.size();
  Frame& f = frames_[current_];
  check(vkWaitForFences(ctx_.device(), 1, &f.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  retire(f);
  check(vkResetFences(ctx_.device(), 1, &f.fence), "vkResetFences");
  check(vkResetCommandPool(ctx_.device(), f.pool, 0), "vkResetCommandPool");
  f.descriptors->reset();
  f.number = ++count_;
  f.retired = false;
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(f.cmd, &bi), "vkBeginCommandBuffer");
  f.timestamps->reset(f.cmd);
  f.recording = true;
  return f;
}

void FrameRing::submit(const std::vector<VkSemaphore>& wait, const std::vector<VkPipelineStageFlags>& waitStages,
                       const std::vector<VkSemaphore>& signal) {
  Frame& f = frames_[current_];
  if (!f.recording) throw InternalError("vulkan: FrameRing::submit() without begin()");
  if (wait.size() != waitStages.size()) throw InternalError("vulkan: one wait stage per wait semaphore");
  f.recording = false;
  check(vkEndCommandBuffer(f.cmd), "vkEndCommandBuffer");
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.waitSemaphoreCount = static_cast<std::uint32_t>(wait.size());
  si.pWaitSemaphores = wait.data();
  si.pWaitDstStageMask = waitStages.data();
  si.commandBufferCount = 1;
  si.pCommandBuffers = &f.cmd;
  si.signalSemaphoreCount = static_cast<std::uint32_t>(signal.size());
  si.pSignalSemaphores = signal.data();
  ctx_.submit(si, f.fence);
}

void FrameRing::deferDelete(std::function<void()> deleter) {
  Frame& f = frames_[current_];
  if (f.number == 0) {
    deleter();  // nothing submitted yet can use it
    return;
  }
  f.deletions.push_back(std::move(deleter));
}

void FrameRing::waitIdle() {
  if (frames_[current_].recording) throw InternalError("vulkan: FrameRing::waitIdle() while a frame is recording");
  // Oldest first, so lastTimings() ends with the newest frame.
  for (std::size_t k = 1; k <= frames_.size(); ++k) {
    Frame& f = frames_[(current_ + k) % frames_.size()];
    check(vkWaitForFences(ctx_.device(), 1, &f.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    retire(f);
  }
}

void FrameRing::abandon() noexcept {
  Frame& f = frames_[current_];
  if (!f.recording) return;
  f.recording = false;
  f.retired = true;  // its timestamp queries were never written: nothing to resolve
  // No check(): this runs while another error unwinds, and a second throw would replace its message.
  // Resetting the pool is valid for a buffer still in the recording state (even inside a render
  // pass, where vkEndCommandBuffer would not be); nothing of it was submitted.
  vkResetCommandPool(ctx_.device(), f.pool, 0);
  // begin() reset the fence and nothing will signal it: replace it by a signalled one so that
  // waitIdle() and the slot's next begin() do not wait forever. (If even that fails the device is
  // lost or out of memory, and the old fence stays.)
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  VkFence fresh = VK_NULL_HANDLE;
  if (vkCreateFence(ctx_.device(), &fi, nullptr, &fresh) != VK_SUCCESS) return;
  vkDestroyFence(ctx_.device(), f.fence, nullptr);
  f.fence = fresh;
  try {
    ctx_.setName(VK_OBJECT_TYPE_FENCE, f.fence, "frame " + std::to_string(f.slot) + " fence");
  } catch (...) {  // a debug name only
  }
}

}  // namespace bounce::gpu
