#include "engine/render/graph/builder.hpp"

#include "engine/core/error.hpp"
#include "engine/render/graph/render_graph.hpp"

namespace bounce::rg {

namespace {

// Layout a pass needs when it uses one image in two ways, or Undefined when no single layout
// serves both. Sampling a depth image while depth-testing against it is legal in
// DepthReadOnly (VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL allows sampling).
bool mergeLayouts(Layout a, Layout b, Layout& merged) {
  if (a == b) {
    merged = a;
    return true;
  }
  if ((a == Layout::DepthReadOnly && b == Layout::ShaderReadOnly) ||
      (a == Layout::ShaderReadOnly && b == Layout::DepthReadOnly)) {
    merged = Layout::DepthReadOnly;
    return true;
  }
  return false;
}

}  // namespace

void Builder::sideEffect() {
  graph_->passes_[pass_].sideEffect = true;
  graph_->invalidate();
}

const std::string& Builder::passName() const { return graph_->passes_[pass_].name; }

const TextureDesc& Builder::desc(Handle<Texture> h) const {
  return graph_->resourceChecked(ResourceKind::Texture, h.index, "pass '" + passName() + "'").texture;
}

const BufferDesc& Builder::desc(Handle<Buffer> h) const {
  return graph_->resourceChecked(ResourceKind::Buffer, h.index, "pass '" + passName() + "'").buffer;
}

std::uint32_t Builder::createResource(std::string name, const TextureDesc& desc) {
  validate(desc, name);
  RenderGraph::ResourceNode node;
  node.name = std::move(name);
  node.kind = ResourceKind::Texture;
  node.texture = desc;
  return graph_->addResource(std::move(node));
}

std::uint32_t Builder::createResource(std::string name, const BufferDesc& desc) {
  validate(desc, name);
  RenderGraph::ResourceNode node;
  node.name = std::move(name);
  node.kind = ResourceKind::Buffer;
  node.buffer = desc;
  return graph_->addResource(std::move(node));
}

std::uint32_t Builder::declare(ResourceKind kind, std::uint32_t index, std::uint32_t version, Usage usage,
                               bool write) {
  RenderGraph& g = *graph_;
  const std::string who = "render graph: pass '" + passName() + "'";
  g.resourceChecked(kind, index, "pass '" + passName() + "'");
  RenderGraph::ResourceNode& r = g.resources_[index];
  const std::string res = "'" + r.name + "'";
  const char* verb = write ? "writes" : "reads";
  if (usage == Usage::Present) throw InternalError(who + " declares Present on " + res + " (Present is only a final state: use markOutput)");
  if (!appliesTo(usage, kind))
    throw InternalError(who + " declares " + usageName(usage) + " on " + res + ", which is a " +
                        (kind == ResourceKind::Texture ? "texture" : "buffer"));
  if (write != isWrite(usage))
    throw InternalError(who + " passes " + (write ? "read" : "write") + " usage " + usageName(usage) + " to " +
                        (write ? "write()" : "read()") + " for " + res);
  if (kind == ResourceKind::Texture) {
    bool depth = isDepthFormat(r.texture.format);
    bool depthUsage = usage == Usage::DepthAttachment || usage == Usage::DepthRead;
    bool colorOnly = usage == Usage::ColorAttachment || usage == Usage::StorageRead || usage == Usage::StorageWrite;
    if ((depthUsage && !depth) || (colorOnly && depth))
      throw InternalError(who + " declares " + usageName(usage) + " on " + res + " of format " +
                          formatName(r.texture.format));
  }
  const std::uint32_t current = static_cast<std::uint32_t>(r.producers.size() - 1);
  if (version > current)
    throw InternalError(who + " " + verb + " " + res + " version " + std::to_string(version) +
                        ", which does not exist (a handle from another graph?)");
  if (version < current)
    throw InternalError(who + " " + verb + " " + res + " version " + std::to_string(version) + ", but pass '" +
                        g.passes_[r.producers[current]].name + "' already wrote version " + std::to_string(current) +
                        " (use the handle that write() returned)");
  if (r.producers[version] == static_cast<std::int32_t>(pass_))
    throw InternalError(who + " " + verb + " " + res + " after writing it (declare the read before the write)");
  if (!write && !r.imported && version == 0)
    throw InternalError(who + " reads " + res + " before any pass wrote it");

  RenderGraph::PassNode& pass = g.passes_[pass_];
  Layout layout = stateFor(usage, kind, false).layout;
  for (const auto& a : pass.accesses) {
    if (a.resource != index) continue;
    Layout other = stateFor(a.usage, kind, false).layout;
    Layout merged;
    if (!mergeLayouts(layout, other, merged))
      throw InternalError(who + " uses " + res + " as " + usageName(a.usage) + " and as " + usageName(usage) +
                          ", which need different layouts (" + layoutName(other) + ", " + layoutName(layout) + ")");
    layout = merged;
  }
  pass.accesses.push_back({index, version, usage, write});
  g.invalidate();
  if (!write) return version;
  r.producers.push_back(static_cast<std::int32_t>(pass_));
  return version + 1;
}

}  // namespace bounce::rg
