#pragma once
// What a pass's setup callback sees: it creates transient resources and declares every read and
// write, each with the usage it needs. Declarations are checked here, at setup time, so a
// mistake points at the pass that made it (stale handle, wrong usage for the resource kind, a
// write usage passed to read(), a conflicting layout, reading a resource nothing wrote yet).
#include <cstdint>
#include <string>

#include "engine/render/graph/resource.hpp"
#include "engine/render/graph/usage.hpp"

namespace bounce::rg {

class RenderGraph;

class Builder {
 public:
  // A new transient resource, owned by the graph and allocated only if a surviving pass uses it.
  // Its version 0 has no content: write it before anyone reads it.
  template <typename T>
  Handle<T> create(std::string name, const typename T::Desc& desc) {
    return Handle<T>{createResource(std::move(name), desc), 0};
  }

  // Declare that this pass reads `handle` (the newest version) with a read usage. Returns it.
  template <typename T>
  Handle<T> read(Handle<T> handle, Usage usage) {
    declare(T::kind, handle.index, handle.version, usage, false);
    return handle;
  }

  // Declare that this pass writes `handle` (the newest version) with a write usage. The content
  // before the write is kept (a colour attachment loads it, a storage image keeps texels the
  // shader does not store), so the previous writer stays alive through culling. Returns the new
  // version; the old handle is stale from now on.
  template <typename T>
  [[nodiscard]] Handle<T> write(Handle<T> handle, Usage usage) {
    return Handle<T>{handle.index, declare(T::kind, handle.index, handle.version, usage, true)};
  }

  // Never cull this pass (it writes something outside the graph: a readback, a persistent buffer).
  void sideEffect();

  const TextureDesc& desc(Handle<Texture> handle) const;
  const BufferDesc& desc(Handle<Buffer> handle) const;
  const std::string& passName() const;

 private:
  friend class RenderGraph;
  Builder(RenderGraph& graph, std::uint32_t pass) : graph_(&graph), pass_(pass) {}

  std::uint32_t createResource(std::string name, const TextureDesc& desc);
  std::uint32_t createResource(std::string name, const BufferDesc& desc);
  // Returns the version after the access (version + 1 for a write).
  std::uint32_t declare(ResourceKind kind, std::uint32_t index, std::uint32_t version, Usage usage, bool write);

  RenderGraph* graph_;
  std::uint32_t pass_;
};

}  // namespace bounce::rg
