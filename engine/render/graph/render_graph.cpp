// Declaration side of the render graph (imports, outputs, pass bookkeeping), execution and
// queries. The compile stages are in compile.cpp, the DOT dump in dot.cpp.
#include "engine/render/graph/render_graph.hpp"

#include "engine/core/error.hpp"

namespace bounce::rg {

RenderGraph::Checkpoint RenderGraph::beginPass(std::string name, std::unique_ptr<ExecutorBase> executor) {
  if (name.empty()) throw InternalError("render graph: a pass needs a name");
  for (const auto& p : passes_)
    if (p.name == name)
      throw InternalError("render graph: pass name '" + name + "' is used twice (timings and the DOT dump name passes)");
  PassNode node;
  node.name = std::move(name);
  node.executor = std::move(executor);
  passes_.push_back(std::move(node));
  invalidate();
  return Checkpoint{static_cast<std::uint32_t>(passes_.size() - 1), resources_.size(), blackboard_};
}

void RenderGraph::rollback(const Checkpoint& cp) {
  const auto& accesses = passes_[cp.pass].accesses;
  for (auto it = accesses.rbegin(); it != accesses.rend(); ++it)
    if (it->write) resources_[it->resource].producers.pop_back();
  resources_.erase(resources_.begin() + static_cast<std::ptrdiff_t>(cp.resourceCount), resources_.end());
  passes_.pop_back();
  blackboard_ = cp.blackboard;
  invalidate();
}

std::uint32_t RenderGraph::addResource(ResourceNode node) {
  if (node.name.empty()) throw InternalError("render graph: a resource needs a name (errors and the DOT dump use it)");
  resources_.push_back(std::move(node));
  invalidate();
  return static_cast<std::uint32_t>(resources_.size() - 1);
}

const RenderGraph::ResourceNode& RenderGraph::resourceChecked(ResourceKind kind, std::uint32_t index,
                                                              const std::string& who) const {
  if (index >= resources_.size() || resources_[index].kind != kind)
    throw InternalError("render graph: " + who + " uses an invalid " +
                        (kind == ResourceKind::Texture ? "texture" : "buffer") + " handle");
  return resources_[index];
}

bool RenderGraph::keepsContents(const ResourceNode& r, std::uint32_t version) const {
  if (version > 0) return true;
  // An imported image in layout Undefined (a freshly acquired swapchain image) has no content.
  return r.imported && !(r.kind == ResourceKind::Texture && r.initial.layout == Layout::Undefined);
}

Handle<Texture> RenderGraph::importTexture(std::string name, const TextureDesc& desc, ResourceState initial,
                                           PhysicalId physical) {
  validate(desc, name);
  ResourceNode node;
  node.name = std::move(name);
  node.kind = ResourceKind::Texture;
  node.texture = desc;
  node.imported = true;
  node.initial = initial;
  node.physical = physical;
  return Handle<Texture>{addResource(std::move(node)), 0};
}

Handle<Buffer> RenderGraph::importBuffer(std::string name, const BufferDesc& desc, ResourceState initial,
                                         PhysicalId physical) {
  validate(desc, name);
  ResourceNode node;
  node.name = std::move(name);
  node.kind = ResourceKind::Buffer;
  node.buffer = desc;
  node.imported = true;
  node.initial = {Layout::Undefined, initial.stages, initial.access};  // buffers have no layout
  node.physical = physical;
  return Handle<Buffer>{addResource(std::move(node)), 0};
}

void RenderGraph::markOutput(Handle<Texture> h, Usage finalUsage) {
  markOutputImpl(ResourceKind::Texture, h.index, h.version, finalUsage);
}

void RenderGraph::markOutput(Handle<Buffer> h, Usage finalUsage) {
  markOutputImpl(ResourceKind::Buffer, h.index, h.version, finalUsage);
}

void RenderGraph::markOutputImpl(ResourceKind kind, std::uint32_t index, std::uint32_t version, Usage finalUsage) {
  const ResourceNode& r = resourceChecked(kind, index, "markOutput");
  if (!r.imported)
    throw InternalError("render graph: only an imported resource can be an output ('" + r.name +
                        "' is transient: its memory is released after execute)");
  if (version >= r.producers.size()) throw InternalError("render graph: markOutput of a handle from another graph");
  if (isWrite(finalUsage) || !(finalUsage == Usage::Present || appliesTo(finalUsage, kind)))
    throw InternalError("render graph: output '" + r.name + "' cannot end in usage " + usageName(finalUsage));
  resources_[index].output = true;
  resources_[index].outputUsage = finalUsage;
  invalidate();
}

void RenderGraph::setCullingEnabled(bool enabled) {
  cullingEnabled_ = enabled;
  invalidate();
}

const GraphStats& RenderGraph::stats() const {
  if (!compiled_) throw InternalError("render graph: stats() before compile()");
  return stats_;
}

ResourceState RenderGraph::finalState(Handle<Texture> h) const {
  if (!compiled_) throw InternalError("render graph: finalState() before compile()");
  return resourceChecked(ResourceKind::Texture, h.index, "finalState").finalState;
}

ResourceState RenderGraph::finalState(Handle<Buffer> h) const {
  if (!compiled_) throw InternalError("render graph: finalState() before compile()");
  return resourceChecked(ResourceKind::Buffer, h.index, "finalState").finalState;
}

std::vector<std::string> RenderGraph::describeBarriers(const std::string& pass) const {
  const std::vector<Barrier>* list = nullptr;
  if (pass.empty()) list = &stats().finalBarriers;
  for (const auto& pb : stats().barriers)
    if (!pass.empty() && pb.pass == pass) list = &pb.barriers;
  if (!list) throw InternalError("render graph: no executed pass named '" + pass + "'");
  std::vector<std::string> out;
  for (const auto& b : *list) out.push_back(describe(b, resources_[b.resource].name));
  return out;
}

void RenderGraph::execute(Backend& backend, CommandContext& ctx) {
  if (!compiled_) compile();
  std::vector<PhysicalId> physical(resources_.size(), 0);
  for (std::size_t i = 0; i < resources_.size(); ++i)
    if (resources_[i].imported) physical[i] = resources_[i].physical;

  std::vector<PhysicalId> slotIds;
  auto destroyAll = [&] {
    for (std::size_t i = slotIds.size(); i-- > 0;) {
      if (slots_[i].kind == ResourceKind::Texture) backend.destroyTexture(slotIds[i]);
      else backend.destroyBuffer(slotIds[i]);
    }
  };
  auto record = [&](const std::vector<Barrier>& barriers) {
    if (barriers.empty()) return;
    std::vector<Barrier> resolved = barriers;
    for (auto& b : resolved) b.physical = physical[b.resource];
    backend.barrier(ctx, resolved);
  };
  try {
    for (const Slot& slot : slots_) {
      std::string name;
      for (std::uint32_t r : slot.occupants) name += (name.empty() ? "" : "|") + resources_[r].name;
      PhysicalId id = slot.kind == ResourceKind::Texture ? backend.createTexture(slot.texture, slot.usages, name)
                                                         : backend.createBuffer(slot.buffer, slot.usages, name);
      slotIds.push_back(id);
      for (std::uint32_t r : slot.occupants) physical[r] = id;
    }
    for (std::size_t pos = 0; pos < order_.size(); ++pos) {
      const PassNode& pass = passes_[order_[pos]];
      record(passBarriers_[pos]);
      backend.beginPass(ctx, pass.name);
      pass.executor->run(PassResources(*this, order_[pos], physical), ctx);
      backend.endPass(ctx);
    }
    record(finalBarriers_);
  } catch (...) {
    destroyAll();
    throw;
  }
  destroyAll();
}

}  // namespace bounce::rg
