#include "engine/render/graph/pass_resources.hpp"

#include "engine/core/error.hpp"
#include "engine/render/graph/render_graph.hpp"

namespace bounce::rg {

const std::string& PassResources::passName() const { return graph_->passes_[pass_].name; }

std::uint32_t PassResources::checkDeclared(ResourceKind kind, std::uint32_t index) const {
  graph_->resourceChecked(kind, index, "pass '" + passName() + "'");
  const auto& accesses = graph_->passes_[pass_].accesses;
  for (std::uint32_t i = 0; i < accesses.size(); ++i)
    if (accesses[i].resource == index) return i;
  throw InternalError("render graph: pass '" + passName() + "' resolves '" + graph_->resources_[index].name +
                      "', which it did not declare in setup (declare it with read() or write())");
}

PhysicalId PassResources::texture(Handle<Texture> h) const {
  checkDeclared(ResourceKind::Texture, h.index);
  return physical_[h.index];
}

PhysicalId PassResources::buffer(Handle<Buffer> h) const {
  checkDeclared(ResourceKind::Buffer, h.index);
  return physical_[h.index];
}

const TextureDesc& PassResources::desc(Handle<Texture> h) const {
  checkDeclared(ResourceKind::Texture, h.index);
  return graph_->resources_[h.index].texture;
}

const BufferDesc& PassResources::desc(Handle<Buffer> h) const {
  checkDeclared(ResourceKind::Buffer, h.index);
  return graph_->resources_[h.index].buffer;
}

bool PassResources::keepsContents(Handle<Texture> written) const {
  checkDeclared(ResourceKind::Texture, written.index);
  const auto& resource = graph_->resources_[written.index];
  for (const auto& a : graph_->passes_[pass_].accesses)
    if (a.resource == written.index && a.write) return graph_->keepsContents(resource, a.version);
  throw InternalError("render graph: pass '" + passName() + "' asks whether its write keeps the contents of '" +
                      resource.name + "', which it only reads");
}

}  // namespace bounce::rg
