#pragma once
// What the render graph needs from the GPU layer. The Vulkan renderer implements Backend (and
// derives its command-buffer wrapper from CommandContext); tests use RecordingBackend. The graph
// calls, in RenderGraph::execute():
//   createTexture/createBuffer for every physical transient slot, then for each surviving pass
//   barrier(ctx, barriers before it) (only when there are some), beginPass(ctx, name), the
//   pass's execute callback, endPass(ctx); then barrier(ctx, final transitions of the outputs);
//   then destroyTexture/destroyBuffer for every slot it created.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/render/graph/resource.hpp"
#include "engine/render/graph/usage.hpp"

namespace bounce::rg {

// The backend's name for a real image or buffer. 0 means "none"; imported resources carry the
// id the caller gave at import.
using PhysicalId = std::uint64_t;

// Whatever a pass records commands into. The Vulkan backend derives from it; a pass's execute
// callback casts it to that type.
class CommandContext {
 public:
  virtual ~CommandContext() = default;
};

class Backend {
 public:
  virtual ~Backend() = default;

  // Create a transient image / buffer for one physical slot. `usages` lists every usage of every
  // virtual resource that lives in the slot; `debugName` is their names joined by '|'.
  virtual PhysicalId createTexture(const TextureDesc& desc, UsageSet usages, std::string_view debugName) = 0;
  virtual PhysicalId createBuffer(const BufferDesc& desc, UsageSet usages, std::string_view debugName) = 0;
  // Called at the end of execute(), after all commands were recorded but before the GPU ran
  // them: the backend must keep the memory alive until the frame completes (or pool it for the
  // next frame's graph).
  virtual void destroyTexture(PhysicalId id) = 0;
  virtual void destroyBuffer(PhysicalId id) = 0;

  // Record the barriers (Barrier::physical names the resource). Never called with an empty span.
  virtual void barrier(CommandContext& ctx, std::span<const Barrier> barriers) = 0;
  // Bracket one pass: the Vulkan backend writes a timestamp and opens a debug label.
  virtual void beginPass(CommandContext& ctx, std::string_view name) = 0;
  virtual void endPass(CommandContext& ctx) = 0;
};

// A no-op backend that records what the graph asked for, one line per call:
//   "create texture 1 hdr 64x64 RGBA16F", "barrier 2", "begin lighting", "end", "destroy texture 1".
// Physical ids count up from 1 across textures and buffers.
class RecordingBackend final : public Backend {
 public:
  PhysicalId createTexture(const TextureDesc& desc, UsageSet usages, std::string_view debugName) override;
  PhysicalId createBuffer(const BufferDesc& desc, UsageSet usages, std::string_view debugName) override;
  void destroyTexture(PhysicalId id) override;
  void destroyBuffer(PhysicalId id) override;
  void barrier(CommandContext& ctx, std::span<const Barrier> barriers) override;
  void beginPass(CommandContext& ctx, std::string_view name) override;
  void endPass(CommandContext& ctx) override;

  std::vector<std::string> events;
  std::vector<std::vector<Barrier>> barrierBatches;  // every barrier() call's span, in order
  std::vector<UsageSet> createdUsages;               // usages of each create call, in order
  int live = 0;                                      // created minus destroyed physical resources

 private:
  PhysicalId next_ = 1;
};

}  // namespace bounce::rg
