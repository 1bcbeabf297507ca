#pragma once
// What a pass's execute callback sees: the physical resource behind each handle it declared.
// Resolving a resource the pass did not declare in setup throws InternalError naming both the
// pass and the resource: an undeclared access would get no barrier.
#include <cstdint>
#include <span>
#include <string>

#include "engine/render/graph/backend.hpp"
#include "engine/render/graph/resource.hpp"

namespace bounce::rg {

class RenderGraph;

class PassResources {
 public:
  PhysicalId texture(Handle<Texture> handle) const;
  PhysicalId buffer(Handle<Buffer> handle) const;
  const TextureDesc& desc(Handle<Texture> handle) const;
  const BufferDesc& desc(Handle<Buffer> handle) const;

  // For a resource this pass writes: whether the content before the write must be kept
  // (attachment loadOp LOAD) or may be discarded (CLEAR / DONT_CARE) because nothing wrote it
  // before (a fresh transient, or an imported image whose initial layout is Undefined).
  bool keepsContents(Handle<Texture> written) const;

  const std::string& passName() const;

 private:
  friend class RenderGraph;
  PassResources(const RenderGraph& graph, std::uint32_t pass, std::span<const PhysicalId> physical)
      : graph_(&graph), pass_(pass), physical_(physical) {}

  // The declaration of `index` by this pass; throws naming pass and resource when there is none.
  std::uint32_t checkDeclared(ResourceKind kind, std::uint32_t index) const;

  const RenderGraph* graph_;
  std::uint32_t pass_;
  std::span<const PhysicalId> physical_;
};

}  // namespace bounce::rg
