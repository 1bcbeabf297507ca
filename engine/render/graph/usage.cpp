#include "engine/render/graph/usage.hpp"

#include <array>
#include <utility>

namespace bounce::rg {

bool isWrite(Usage u) {
  return u == Usage::StorageWrite || u == Usage::ColorAttachment || u == Usage::DepthAttachment ||
         u == Usage::TransferDst;
}

bool appliesTo(Usage u, ResourceKind kind) {
  switch (u) {
    case Usage::StorageRead:
    case Usage::StorageWrite:
    case Usage::TransferSrc:
    case Usage::TransferDst: return true;
    case Usage::UniformBuffer:
    case Usage::VertexBuffer:
    case Usage::IndexBuffer:
    case Usage::IndirectBuffer: return kind == ResourceKind::Buffer;
    default: return kind == ResourceKind::Texture;
  }
}

const char* usageName(Usage u) {
  switch (u) {
    case Usage::SampledFragment: return "SampledFragment";
    case Usage::SampledCompute: return "SampledCompute";
    case Usage::SampledGraphics: return "SampledGraphics";
    case Usage::StorageRead: return "StorageRead";
    case Usage::StorageWrite: return "StorageWrite";
    case Usage::ColorAttachment: return "ColorAttachment";
    case Usage::DepthAttachment: return "DepthAttachment";
    case Usage::DepthRead: return "DepthRead";
    case Usage::TransferSrc: return "TransferSrc";
    case Usage::TransferDst: return "TransferDst";
    case Usage::UniformBuffer: return "UniformBuffer";
    case Usage::VertexBuffer: return "VertexBuffer";
    case Usage::IndexBuffer: return "IndexBuffer";
    case Usage::IndirectBuffer: return "IndirectBuffer";
    case Usage::Present: return "Present";
  }
  return "?";
}

const char* layoutName(Layout l) {
  switch (l) {
    case Layout::Undefined: return "Undefined";
    case Layout::General: return "General";
    case Layout::ColorAttachment: return "ColorAttachment";
    case Layout::DepthAttachment: return "DepthAttachment";
    case Layout::DepthReadOnly: return "DepthReadOnly";
    case Layout::ShaderReadOnly: return "ShaderReadOnly";
    case Layout::TransferSrc: return "TransferSrc";
    case Layout::TransferDst: return "TransferDst";
    case Layout::Present: return "Present";
  }
  return "?";
}

namespace {

template <typename Bits, std::size_t N>
std::string joinNames(Bits bits, const std::array<std::pair<Bits, const char*>, N>& names) {
  std::string s;
  for (auto& [bit, name] : names) {
    if ((static_cast<std::uint32_t>(bits) & static_cast<std::uint32_t>(bit)) == 0) continue;
    if (!s.empty()) s += '|';
    s += name;
  }
  return s.empty() ? "None" : s;
}

}  // namespace

std::string stageNames(Stage stages) {
  static constexpr std::array<std::pair<Stage, const char*>, 9> names{{
      {Stage::DrawIndirect, "DrawIndirect"},
      {Stage::VertexInput, "VertexInput"},
      {Stage::VertexShader, "VertexShader"},
      {Stage::FragmentShader, "FragmentShader"},
      {Stage::EarlyFragmentTests, "EarlyFragmentTests"},
      {Stage::LateFragmentTests, "LateFragmentTests"},
      {Stage::ColorAttachmentOutput, "ColorAttachmentOutput"},
      {Stage::ComputeShader, "ComputeShader"},
      {Stage::Transfer, "Transfer"},
  }};
  return joinNames(stages, names);
}

std::string accessNames(Access access) {
  static constexpr std::array<std::pair<Access, const char*>, 13> names{{
      {Access::IndirectCommandRead, "IndirectCommandRead"},
      {Access::IndexRead, "IndexRead"},
      {Access::VertexAttributeRead, "VertexAttributeRead"},
      {Access::UniformRead, "UniformRead"},
      {Access::ShaderSampledRead, "ShaderSampledRead"},
      {Access::ShaderStorageRead, "ShaderStorageRead"},
      {Access::ShaderStorageWrite, "ShaderStorageWrite"},
      {Access::ColorAttachmentRead, "ColorAttachmentRead"},
      {Access::ColorAttachmentWrite, "ColorAttachmentWrite"},
      {Access::DepthStencilRead, "DepthStencilRead"},
      {Access::DepthStencilWrite, "DepthStencilWrite"},
      {Access::TransferRead, "TransferRead"},
      {Access::TransferWrite, "TransferWrite"},
  }};
  return joinNames(access, names);
}

Access writeAccesses(Access access) {
  return access & (Access::ShaderStorageWrite | Access::ColorAttachmentWrite | Access::DepthStencilWrite |
                   Access::TransferWrite);
}

ResourceState stateFor(Usage usage, ResourceKind kind, bool priorContents) {
  const bool image = kind == ResourceKind::Texture;
  auto layout = [&](Layout l) { return image ? l : Layout::Undefined; };
  constexpr Stage kDepthTests = Stage::EarlyFragmentTests | Stage::LateFragmentTests;
  switch (usage) {
    case Usage::SampledFragment:
      return {Layout::ShaderReadOnly, Stage::FragmentShader, Access::ShaderSampledRead};
    case Usage::SampledCompute:
      return {Layout::ShaderReadOnly, Stage::ComputeShader, Access::ShaderSampledRead};
    case Usage::SampledGraphics:
      return {Layout::ShaderReadOnly, Stage::VertexShader | Stage::FragmentShader, Access::ShaderSampledRead};
    case Usage::StorageRead:
      return {layout(Layout::General), Stage::ComputeShader, Access::ShaderStorageRead};
    case Usage::StorageWrite:
      return {layout(Layout::General), Stage::ComputeShader, Access::ShaderStorageWrite};
    case Usage::ColorAttachment:
      // Keeping earlier content means loadOp LOAD, which reads the attachment.
      return {Layout::ColorAttachment, Stage::ColorAttachmentOutput,
              priorContents ? Access::ColorAttachmentRead | Access::ColorAttachmentWrite
                            : Access::ColorAttachmentWrite};
    case Usage::DepthAttachment:
      // The depth test reads the attachment even when the pass clears it first.
      return {Layout::DepthAttachment, kDepthTests, Access::DepthStencilRead | Access::DepthStencilWrite};
    case Usage::DepthRead: return {Layout::DepthReadOnly, kDepthTests, Access::DepthStencilRead};
    case Usage::TransferSrc: return {layout(Layout::TransferSrc), Stage::Transfer, Access::TransferRead};
    case Usage::TransferDst: return {layout(Layout::TransferDst), Stage::Transfer, Access::TransferWrite};
    case Usage::UniformBuffer:
      return {Layout::Undefined, Stage::VertexShader | Stage::FragmentShader | Stage::ComputeShader,
              Access::UniformRead};
    case Usage::VertexBuffer: return {Layout::Undefined, Stage::VertexInput, Access::VertexAttributeRead};
    case Usage::IndexBuffer: return {Layout::Undefined, Stage::VertexInput, Access::IndexRead};
    case Usage::IndirectBuffer: return {Layout::Undefined, Stage::DrawIndirect, Access::IndirectCommandRead};
    case Usage::Present: return {Layout::Present, Stage::None, Access::None};
  }
  return {};
}

std::string describe(const Barrier& b, const std::string& name) {
  auto side = [&](const ResourceState& s) {
    std::string t = stageNames(s.stages) + "/" + accessNames(s.access);
    return b.kind == ResourceKind::Texture ? std::string(layoutName(s.layout)) + "/" + t : t;
  };
  return name + ": " + side(b.before) + " -> " + side(b.after);
}

}  // namespace bounce::rg
