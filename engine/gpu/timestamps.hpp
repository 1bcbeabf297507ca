#pragma once
// GPU timestamps for one frame: named, nestable scopes written into a query pool and resolved to
// milliseconds (ticks · timestampPeriod ns / 1e6) once the frame's fence has signalled.
// FrameRing keeps one TimestampPool per frame in flight, so reading frame N's results never
// waits on frame N+1.
//
// Each scope writes its begin and its end at BOTTOM_OF_PIPE, and right after the begin one more
// stamp that is never read. Why: on lavapipe a stamp is executed by llvmpipe's rasteriser as a
// command binned into every tile of the current batch ("scene"), and the query keeps the latest
// tile's time; any stage but top-of-pipe first flushes the batch so far. A begin stamp that shares
// its batch with the pass's draws therefore reads ~when the last tile *started* — the pass then
// measured only its last tile (cornell-1, 1280x720: `probes` read 1.6 ms while adding it cost
// ~0.8 s of wall time per frame). The extra stamp flushes the begin stamp's batch on its own, so
// the draws start a new one; the end stamp flushes the draws. On a GPU the extra stamp costs
// nothing measurable. Any flush perturbs lavapipe a little — DESIGN.md "Machine facts".
#include <cstdint>
#include <string>
#include <vector>

#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class Context;

// Queries per scope: begin, end, and the stamp that closes the begin stamp's batch.
inline constexpr std::uint32_t kQueriesPerScope = 3;

struct TimingResult {
  std::string name;
  std::uint32_t depth = 0;  // nesting depth: 0 for outermost scopes
  double ms = 0.0;
};

class TimestampPool {
 public:
  static constexpr std::uint32_t kDefaultMaxScopes = 256;

  TimestampPool(Context& ctx, std::uint32_t maxScopes = kDefaultMaxScopes);
  ~TimestampPool();
  TimestampPool(const TimestampPool&) = delete;
  TimestampPool& operator=(const TimestampPool&) = delete;

  // False when the queue has no timestamp support (timestampValidBits == 0); scopes then
  // record nothing and resolve() returns an empty list.
  bool supported() const { return supported_; }

  // Records the pool reset; call at the start of the frame's command buffer, outside rendering.
  void reset(VkCommandBuffer cmd);
  // Opens a scope; scopes nest and must close in reverse order (end() closes the innermost).
  // Past maxScopes further scopes are dropped and counted (droppedScopes()).
  void begin(VkCommandBuffer cmd, const std::string& name);
  void end(VkCommandBuffer cmd);
  // Results in the order scopes were opened. Call only after the commands have completed.
  std::vector<TimingResult> resolve();
  std::uint32_t droppedScopes() const { return dropped_; }

 private:
  struct Scope {
    std::string name;
    std::uint32_t depth;
    std::uint32_t query;  // begin query; end = query + 1; query + 2 closes the begin stamp's batch
  };
  Context& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  std::uint32_t max_scopes_;
  bool supported_ = false;
  double period_ns_ = 1.0;
  std::uint64_t valid_mask_ = ~0ull;
  std::vector<Scope> scopes_;
  std::vector<std::int64_t> open_;  // indices into scopes_ (-1 for dropped scopes)
  std::uint32_t dropped_ = 0;
};

// RAII scope with a debug label of the same name: `GpuScope s(ctx, pool, cmd, "shadow");`
class GpuScope {
 public:
  GpuScope(const Context& ctx, TimestampPool& pool, VkCommandBuffer cmd, const std::string& name);
  ~GpuScope();
  GpuScope(const GpuScope&) = delete;
  GpuScope& operator=(const GpuScope&) = delete;

 private:
  const Context& ctx_;
  TimestampPool& pool_;
  VkCommandBuffer cmd_;
};

}  // namespace bounce::gpu
