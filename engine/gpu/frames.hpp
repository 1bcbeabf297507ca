#pragma once
// Frames in flight. Each frame slot owns a command pool + buffer, a fence, a descriptor
// allocator, a timestamp pool and a deferred-deletion list. begin() waits for the slot's
// previous use to finish, and only then frees what was deferred, resolves its timestamps and
// resets its pools — so nothing the GPU may still read is destroyed early.
//
//   Frame& f = frames.begin();            // waits on this slot's fence
//   ... record into f.cmd ...
//   frames.submit({acquired}, {waitStage}, {renderDone});   // or a presenter does it
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/timestamps.hpp"
#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class Context;

struct Frame {
  std::uint32_t slot = 0;    // 0 .. framesInFlight-1
  std::uint64_t number = 0;  // frames begun so far, counting this one from 1
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  std::unique_ptr<DescriptorAllocator> descriptors;
  std::unique_ptr<TimestampPool> timestamps;
  std::vector<std::function<void()>> deletions;
  bool recording = false;
  bool retired = false;  // its timings were resolved (reset when the slot begins again)
};

// The per-pass timings of one completed frame.
struct ResolvedTimings {
  std::uint64_t frame = 0;
  std::vector<TimingResult> timings;
};

class FrameRing {
 public:
  static constexpr std::uint32_t kDefaultFramesInFlight = 2;

  explicit FrameRing(Context& ctx, std::uint32_t framesInFlight = kDefaultFramesInFlight);
  ~FrameRing();  // waits for the GPU, then runs every pending deletion
  FrameRing(const FrameRing&) = delete;
  FrameRing& operator=(const FrameRing&) = delete;

  // Starts the next frame: waits for its slot, runs its deletions, resolves its timestamps into
  // lastTimings(), resets pools and begins its command buffer (with a timestamp pool reset).
  Frame& begin();
  Frame& current() { return frames_[current_]; }
  // Ends and submits the current frame's command buffer, signalling its fence.
  void submit(const std::vector<VkSemaphore>& wait = {}, const std::vector<VkPipelineStageFlags>& waitStages = {},
              const std::vector<VkSemaphore>& signal = {});
  // Runs `deleter` once the GPU has finished the current frame (or at once if none is recording).
  void deferDelete(std::function<void()> deleter);
  // Waits for every submitted frame (captures, resizes, shutdown); resolves their timings.
  void waitIdle();
  // Drops the frame being recorded without submitting it, so that an error thrown while recording
  // unwinds to a ring that shuts down cleanly (waitIdle() returns) instead of ending in std::terminate
  // from a destructor's waitIdle(). Its deletions still run when the slot is next retired; it has no
  // timings. No-op when no frame is recording. The ring records again afterwards; the renderer
  // also rolls back the layouts its graph's barriers recorded (VkBackend::abandonFrame), so its next
  // frame renders as before (RenderUnwind test). Images a pass transitions by itself are not rolled back.
  void abandon() noexcept;

  // Timings of the most recently completed frame whose results were resolved.
  const std::vector<TimingResult>& lastTimings() const { return last_timings_; }
  // Every frame resolved since the last call, oldest first: profiling takes these so that no
  // frame is lost when waitIdle() resolves several at once.
  std::vector<ResolvedTimings> takeResolvedTimings();
  std::uint64_t lastTimingsFrame() const { return last_timings_frame_; }
  std::uint32_t framesInFlight() const { return static_cast<std::uint32_t>(frames_.size()); }

 private:
  void retire(Frame& f);  // after its fence: deletions + timings
  Context& ctx_;
  std::vector<Frame> frames_;
  std::uint32_t current_ = 0;
  std::uint64_t count_ = 0;
  std::vector<TimingResult> last_timings_;
  std::vector<ResolvedTimings> resolved_;
  std::uint64_t last_timings_frame_ = 0;
};

}  // namespace bounce::gpu
