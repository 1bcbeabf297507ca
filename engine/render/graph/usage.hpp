#pragma once
// How a pass uses a resource, and the abstract GPU state that usage needs. A pass declares only
// its usage; the graph derives layouts, pipeline stages, memory accesses and therefore every
// barrier from it (no pass writes a barrier by hand). The enums mirror Vulkan synchronization2
// (VkImageLayout, VkPipelineStageFlags2, VkAccessFlags2) one to one, so the Vulkan backend maps
// them with a table, but nothing here depends on Vulkan.
#include <cstdint>
#include <string>

#include "engine/render/graph/resource.hpp"

namespace bounce::rg {

enum class Usage : std::uint8_t {
  SampledFragment,  // texture sampled in a fragment shader
  SampledCompute,   // texture sampled in a compute shader
  SampledGraphics,  // texture sampled in the vertex and fragment shaders (e.g. a tile's vertices read depth)
  StorageRead,      // storage image / buffer read by a compute shader
  StorageWrite,     // storage image / buffer written by a compute shader (write)
  ColorAttachment,  // rendered to as a colour attachment (write)
  DepthAttachment,  // depth test and depth write (write)
  DepthRead,        // depth test without depth write
  TransferSrc,      // copy / blit source
  TransferDst,      // copy / blit / clear destination (write)
  UniformBuffer,    // uniform buffer read by any shader stage
  VertexBuffer,
  IndexBuffer,
  IndirectBuffer,   // indirect draw / dispatch arguments
  Present,          // handed to the presentation engine (only as a final state, see markOutput)
};

// A set of usages (bit i = Usage i): everything a physical resource is used for, so the backend
// can create it with exactly those capabilities (VkImageUsageFlags / VkBufferUsageFlags).
struct UsageSet {
  std::uint32_t bits = 0;

  void add(Usage u) { bits |= 1u << static_cast<unsigned>(u); }
  bool has(Usage u) const { return (bits >> static_cast<unsigned>(u)) & 1u; }
  void add(UsageSet other) { bits |= other.bits; }
  bool operator==(const UsageSet&) const = default;
};

// Usages that change the content (and therefore return a new handle version).
bool isWrite(Usage usage);
// Whether `usage` makes sense for a resource of `kind` (no vertex-buffer textures).
bool appliesTo(Usage usage, ResourceKind kind);
const char* usageName(Usage usage);

enum class Layout : std::uint8_t {
  Undefined,  // content may be discarded; also the (absent) layout of every buffer
  General,    // storage images
  ColorAttachment,
  DepthAttachment,
  DepthReadOnly,
  ShaderReadOnly,
  TransferSrc,
  TransferDst,
  Present,
};
const char* layoutName(Layout layout);

// Pipeline stages, a bit set.
enum class Stage : std::uint32_t {
  None = 0,
  DrawIndirect = 1u << 0,
  VertexInput = 1u << 1,
  VertexShader = 1u << 2,
  FragmentShader = 1u << 3,
  EarlyFragmentTests = 1u << 4,
  LateFragmentTests = 1u << 5,
  ColorAttachmentOutput = 1u << 6,
  ComputeShader = 1u << 7,
  Transfer = 1u << 8,
};

// Memory accesses, a bit set.
enum class Access : std::uint32_t {
  None = 0,
  IndirectCommandRead = 1u << 0,
  IndexRead = 1u << 1,
  VertexAttributeRead = 1u << 2,
  UniformRead = 1u << 3,
  ShaderSampledRead = 1u << 4,
  ShaderStorageRead = 1u << 5,
  ShaderStorageWrite = 1u << 6,
  ColorAttachmentRead = 1u << 7,
  ColorAttachmentWrite = 1u << 8,
  DepthStencilRead = 1u << 9,
  DepthStencilWrite = 1u << 10,
  TransferRead = 1u << 11,
  TransferWrite = 1u << 12,
};

constexpr Stage operator|(Stage a, Stage b) {
  return Stage(static_cast<std::uint32_t>(a) | static_cast<std::uint32_t>(b));
}
constexpr Stage operator&(Stage a, Stage b) {
  return Stage(static_cast<std::uint32_t>(a) & static_cast<std::uint32_t>(b));
}
constexpr Access operator|(Access a, Access b) {
  return Access(static_cast<std::uint32_t>(a) | static_cast<std::uint32_t>(b));
}
constexpr Access operator&(Access a, Access b) {
  return Access(static_cast<std::uint32_t>(a) & static_cast<std::uint32_t>(b));
}
inline Stage& operator|=(Stage& a, Stage b) { return a = a | b; }
inline Access& operator|=(Access& a, Access b) { return a = a | b; }
// Names joined by '|', "None" for the empty set: "EarlyFragmentTests|LateFragmentTests".
std::string stageNames(Stage stages);
std::string accessNames(Access access);
// The write bits of an access set (the ones a later barrier must make available).
Access writeAccesses(Access access);

// Where a resource is (layout) and who touches it (stages, accesses).
struct ResourceState {
  Layout layout = Layout::Undefined;
  Stage stages = Stage::None;
  Access access = Access::None;

  bool operator==(const ResourceState&) const = default;
};

// The state a usage needs. `priorContents` tells whether a write keeps what was there (a colour
// attachment then loads, which is a read); it does not matter for reads. For buffers the layout
// is always Undefined.
ResourceState stateFor(Usage usage, ResourceKind kind, bool priorContents);

// One image or buffer memory barrier: everything in `before` (stages, writes) completes and is
// made visible to `after`, and an image moves from before.layout to after.layout. A barrier with
// before.layout Undefined discards the content (first use of a transient).
struct Barrier {
  std::uint32_t resource = 0;  // virtual resource index (RenderGraph::resourceName gives its name)
  ResourceKind kind = ResourceKind::Texture;
  std::uint64_t physical = 0;  // filled in at execute(): the backend's id (see backend.hpp)
  ResourceState before;
  ResourceState after;

  bool operator==(const Barrier&) const = default;
};

// "hdr: Undefined/None/None -> ColorAttachment/ColorAttachmentOutput/ColorAttachmentWrite";
// buffers print no layout: "sh: ComputeShader/ShaderStorageWrite -> FragmentShader/UniformRead".
std::string describe(const Barrier& barrier, const std::string& resourceName);

}  // namespace bounce::rg
