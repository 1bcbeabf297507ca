#pragma once
// The render graph (DESIGN.md "Render graph"). A frame is described as passes that declare, in
// a setup callback, which virtual resources they read and write and how; the graph then
// compiles the frame in named stages and executes it on a Backend:
//   cull       walk backwards from the sinks (outputs and side-effect passes); every other pass
//              is dropped, together with producers only it needed;
//   order      surviving passes keep their declaration order, which is a topological order
//              because a handle can only come from an earlier pass (checked);
//   allocate   each transient gets a physical slot; a slot is reused by a later transient with
//              the same description whose lifetime [first pass, last pass] does not overlap;
//   barriers   layouts, stages and accesses follow from the declared usages: the list of
//              barriers before each pass, plus the final transitions of the outputs.
// execute() wraps each pass in Backend::beginPass/endPass (timestamps and debug labels).
//
// Usage:
//   struct GBuffer { Handle<Texture> normal, depth; };
//   auto& gb = graph.addPass<GBuffer>("gbuffer",
//       [&](Builder& b, GBuffer& d) {
//         d.normal = b.write(b.create<Texture>("gbuffer.normal", desc), Usage::ColorAttachment);
//         ...
//       },
//       [=](const GBuffer& d, const PassResources& r, CommandContext& ctx) { ... });
// The execute callback runs later, after setup's locals are gone: capture by value.
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "engine/render/graph/backend.hpp"
#include "engine/render/graph/blackboard.hpp"
#include "engine/render/graph/builder.hpp"
#include "engine/render/graph/pass_resources.hpp"
#include "engine/render/graph/resource.hpp"
#include "engine/render/graph/usage.hpp"

namespace bounce::rg {

struct PassBarriers {
  std::string pass;
  std::vector<Barrier> barriers;  // to record before the pass, in declaration order of its accesses
};

// What compile() decided, for tests, the overlay and the DOT dump.
struct GraphStats {
  std::vector<std::string> culledPasses;    // declaration order
  std::vector<std::string> executedPasses;  // execution order
  std::vector<PassBarriers> barriers;       // one entry per executed pass, same order
  std::vector<Barrier> finalBarriers;       // transitions of the outputs after the last pass
  std::uint32_t transientTextures = 0;      // virtual transients a surviving pass uses
  std::uint32_t transientBuffers = 0;
  std::uint32_t physicalTextures = 0;       // slots after aliasing
  std::uint32_t physicalBuffers = 0;
};

class RenderGraph {
 public:
  RenderGraph() = default;
  RenderGraph(const RenderGraph&) = delete;
  RenderGraph& operator=(const RenderGraph&) = delete;

  // Add a pass. `setup(Builder&, Data&)` runs now and fills the pass data with handles;
  // `execute(const Data&, const PassResources&, CommandContext&)` runs in execute(). Returns the
  // pass data (valid as long as the graph) so later passes can read its handles. When setup
  // throws, the pass and everything it declared are removed again before the error propagates.
  template <typename Data, typename Setup, typename Execute>
  const Data& addPass(std::string name, Setup&& setup, Execute&& execute) {
    static_assert(std::is_default_constructible_v<Data>, "pass data must be default-constructible");
    static_assert(std::is_invocable_v<Setup&, Builder&, Data&>, "setup must take (Builder&, Data&)");
    static_assert(std::is_invocable_v<const std::decay_t<Execute>&, const Data&, const PassResources&, CommandContext&>,
                  "execute must take (const Data&, const PassResources&, CommandContext&)");
    auto executor = std::make_unique<Executor<Data, std::decay_t<Execute>>>(std::forward<Execute>(execute));
    Data& data = executor->data;
    Checkpoint checkpoint = beginPass(std::move(name), std::move(executor));
    try {
      Builder builder(*this, checkpoint.pass);
      setup(builder, data);
    } catch (...) {
      rollback(checkpoint);
      throw;
    }
    return data;
  }

  // An external resource (swapchain image, persistent buffer). `initial` is its state when the
  // graph starts (e.g. {Undefined, ColorAttachmentOutput, None} for an acquired swapchain image);
  // `physical` is the backend id that PassResources returns for it.
  Handle<Texture> importTexture(std::string name, const TextureDesc& desc, ResourceState initial, PhysicalId physical);
  Handle<Buffer> importBuffer(std::string name, const BufferDesc& desc, ResourceState initial, PhysicalId physical);

  // Make an imported resource a sink: the passes producing its final version survive culling,
  // and after the last pass it is transitioned to `finalUsage` (Present, TransferSrc for a
  // capture, or any read usage).
  void markOutput(Handle<Texture> handle, Usage finalUsage);
  void markOutput(Handle<Buffer> handle, Usage finalUsage);

  Blackboard& blackboard() { return blackboard_; }
  const Blackboard& blackboard() const { return blackboard_; }

  // Off: every pass survives (for debugging a pass that disappears).
  void setCullingEnabled(bool enabled);

  // Run the compile stages (see the top of this file). Called by execute() when needed.
  const GraphStats& compile();
  bool compiled() const { return compiled_; }
  const GraphStats& stats() const;  // throws unless compiled

  // Compile if needed, then create transients, record every surviving pass, destroy transients.
  void execute(Backend& backend, CommandContext& ctx);

  // Graphviz DOT of the graph as compiled (compiles if needed): passes are boxes labelled with
  // their exact name, resource versions ellipses "name\nvN"; culled passes dashed and grey.
  std::string toDot();

  // The state each resource is left in after the last pass and the final transitions (an
  // imported persistent resource's `initial` for the next frame's graph).
  ResourceState finalState(Handle<Texture> handle) const;
  ResourceState finalState(Handle<Buffer> handle) const;

  std::uint32_t passCount() const { return static_cast<std::uint32_t>(passes_.size()); }
  std::uint32_t resourceCount() const { return static_cast<std::uint32_t>(resources_.size()); }
  const std::string& passName(std::uint32_t pass) const { return passes_.at(pass).name; }
  const std::string& resourceName(std::uint32_t resource) const { return resources_.at(resource).name; }
  // describe() of each barrier before `pass` (an executed pass's name), or of the final
  // transitions when `pass` is empty: the readable form tests compare against.
  std::vector<std::string> describeBarriers(const std::string& pass) const;

 private:
  friend class Builder;
  friend class PassResources;

  struct ExecutorBase {
    virtual ~ExecutorBase() = default;
    virtual void run(const PassResources& resources, CommandContext& ctx) const = 0;
  };
  template <typename Data, typename Fn>
  struct Executor final : ExecutorBase {
    explicit Executor(Fn f) : fn(std::move(f)) {}
    void run(const PassResources& resources, CommandContext& ctx) const override { fn(data, resources, ctx); }
    Data data{};
    Fn fn;
  };

  // One declared access of a pass. For a write, `version` is the version written over and the
  // pass produces version + 1.
  struct Declaration {
    std::uint32_t resource;
    std::uint32_t version;
    Usage usage;
    bool write;
  };
  struct PassNode {
    std::string name;
    std::vector<Declaration> accesses;
    std::unique_ptr<ExecutorBase> executor;
    bool sideEffect = false;
    bool culled = false;
  };
  struct ResourceNode {
    std::string name;
    ResourceKind kind;
    TextureDesc texture;
    BufferDesc buffer;
    bool imported = false;
    ResourceState initial;
    PhysicalId physical = 0;  // imported only
    bool output = false;
    Usage outputUsage = Usage::Present;
    std::vector<std::int32_t> producers{-1};  // producers[v]: pass that wrote version v (-1: none)
    std::int32_t slot = -1;                   // physical slot of a used transient (compile)
    ResourceState finalState;                 // compile
  };
  struct Slot {
    ResourceKind kind;
    TextureDesc texture;
    BufferDesc buffer;
    UsageSet usages;
    std::vector<std::uint32_t> occupants;  // resources, in order of first use
    std::uint32_t busyUntil = 0;           // position in execution order of the last use
  };
  struct Checkpoint {
    std::uint32_t pass;
    std::size_t resourceCount;
    Blackboard blackboard;
  };

  Checkpoint beginPass(std::string name, std::unique_ptr<ExecutorBase> executor);
  void rollback(const Checkpoint& checkpoint);
  std::uint32_t addResource(ResourceNode node);
  void markOutputImpl(ResourceKind kind, std::uint32_t index, std::uint32_t version, Usage finalUsage);
  const ResourceNode& resourceChecked(ResourceKind kind, std::uint32_t index, const std::string& who) const;
  bool keepsContents(const ResourceNode& resource, std::uint32_t version) const;
  ResourceState passState(const PassNode& pass, std::uint32_t resource) const;
  void invalidate() { compiled_ = false; }

  // Compile stages (compile.cpp).
  void cull();
  void checkOrder() const;
  void allocateTransients();
  void deriveBarriers();

  std::vector<PassNode> passes_;
  std::vector<ResourceNode> resources_;
  Blackboard blackboard_;
  bool cullingEnabled_ = true;
  bool compiled_ = false;
  // Compile results.
  std::vector<std::uint32_t> order_;                // executed pass indices
  std::vector<std::vector<Barrier>> passBarriers_;  // per executed position
  std::vector<Barrier> finalBarriers_;
  std::vector<Slot> slots_;
  GraphStats stats_;
};

}  // namespace bounce::rg
