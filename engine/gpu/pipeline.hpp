#pragma once
// Shaders, pipeline layouts, the pipeline cache, and compute/graphics pipelines.
//
// Graphics pipelines use dynamic rendering (VK_KHR_dynamic_rendering, core in Vulkan 1.3): a
// pipeline names its attachment formats instead of a VkRenderPass, and a pass draws between
// Context::cmdBeginRendering/cmdEndRendering. This keeps the render graph free of render-pass
// and framebuffer objects. Viewport and scissor are always dynamic state.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "engine/gpu/descriptors.hpp"
#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class Context;

// Absolute path of a compiled shader: shaderDir()/<relative> (engine/core/paths.hpp), e.g. "test/fill.comp.spv".
std::filesystem::path shaderPath(const std::string& relative);

class ShaderModule {
 public:
  ShaderModule() = default;
  // Loads shaderDir()/<relative>; a missing or malformed file is an InternalError naming it.
  ShaderModule(Context& ctx, const std::string& relative);
  static ShaderModule fromFile(Context& ctx, const std::filesystem::path& path);
  ~ShaderModule() { reset(); }
  ShaderModule(ShaderModule&& o) noexcept { *this = std::move(o); }
  ShaderModule& operator=(ShaderModule&& o) noexcept;
  ShaderModule(const ShaderModule&) = delete;
  ShaderModule& operator=(const ShaderModule&) = delete;
  void reset();
  VkShaderModule handle() const { return module_; }
  const std::string& name() const { return name_; }
  // 64-bit hash (engine/core/hash.hpp) of the SPIR-V words and their count: the shader's part of
  // the pipeline table's key (pipeline_table.hpp). Two modules from the same bytes hash alike.
  std::uint64_t spirvHash() const { return spirv_hash_; }

 private:
  Context* ctx_ = nullptr;
  VkShaderModule module_ = VK_NULL_HANDLE;
  std::string name_;
  std::uint64_t spirv_hash_ = 0;
};

// A pipeline layout keeps what it was made of (each set layout's bindings, the push ranges) so
// the pipeline table can key pipelines by the layout's content, not its handle: two layouts built
// alike (one per Session) are "compatible" in Vulkan's sense and bind the same pipelines.
class PipelineLayout {
 public:
  using SetLayouts = std::vector<std::reference_wrapper<const DescriptorSetLayout>>;
  PipelineLayout() = default;
  PipelineLayout(Context& ctx, const SetLayouts& sets, const std::vector<VkPushConstantRange>& pushConstants,
                 const std::string& name);
  ~PipelineLayout() { reset(); }
  PipelineLayout(PipelineLayout&& o) noexcept { *this = std::move(o); }
  PipelineLayout& operator=(PipelineLayout&& o) noexcept;
  PipelineLayout(const PipelineLayout&) = delete;
  PipelineLayout& operator=(const PipelineLayout&) = delete;
  void reset();
  VkPipelineLayout handle() const { return layout_; }
  const std::vector<std::vector<Binding>>& setBindings() const { return set_bindings_; }
  const std::vector<VkPushConstantRange>& pushConstants() const { return push_constants_; }

 private:
  Context* ctx_ = nullptr;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  std::vector<std::vector<Binding>> set_bindings_;  // per set, as its DescriptorSetLayout had them
  std::vector<VkPushConstantRange> push_constants_;
};

// VkPipelineCache, optionally loaded from and saved to a file (a stale or foreign file is
// ignored by the driver: the header carries vendor, device and cache UUID).
class PipelineCache {
 public:
  explicit PipelineCache(Context& ctx, std::filesystem::path file = {});
  ~PipelineCache();
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;
  VkPipelineCache handle() const { return cache_; }
  void save() const;  // to `file` when one was given

 private:
  Context& ctx_;
  VkPipelineCache cache_ = VK_NULL_HANDLE;
  std::filesystem::path file_;
};

// A bound pipeline and the layout its sets and push constants go through. Either owned (destroyed
// with this object) or held by the Context's pipeline table (pipeline_table.hpp: shared by every
// identical request, destroyed with the Context); `layout` is the requester's own, compatible with
// the one the table built the pipeline with.
class Pipeline {
 public:
  Pipeline() = default;
  Pipeline(Context& ctx, VkPipeline pipeline, VkPipelineBindPoint bindPoint, VkPipelineLayout layout,
           bool heldByTable = false);
  ~Pipeline() { reset(); }
  Pipeline(Pipeline&& o) noexcept { *this = std::move(o); }
  Pipeline& operator=(Pipeline&& o) noexcept;
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;
  void reset();
  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkPipelineBindPoint bindPoint() const { return bind_point_; }
  bool heldByTable() const { return held_by_table_; }

  void bind(VkCommandBuffer cmd) const { vkCmdBindPipeline(cmd, bind_point_, pipeline_); }
  void bindSet(VkCommandBuffer cmd, std::uint32_t index, VkDescriptorSet set) const {
    vkCmdBindDescriptorSets(cmd, bind_point_, layout_, index, 1, &set, 0, nullptr);
  }
  // Push constants visible to every stage (layouts built with VK_SHADER_STAGE_ALL ranges).
  template <class T>
  void push(VkCommandBuffer cmd, const T& value, std::uint32_t offset = 0,
            VkShaderStageFlags stages = VK_SHADER_STAGE_ALL) const {
    vkCmdPushConstants(cmd, layout_, stages, offset, sizeof(T), &value);
  }

 private:
  Context* ctx_ = nullptr;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;  // not owned
  bool held_by_table_ = false;                // the Context's table destroys it, not reset()
};

// Specialization constants: value i is `layout(constant_id = i)` in every stage of the pipeline
// (32-bit: uint, int, float bits or bool as 0/1). A technique variant is one pipeline per
// combination of constants instead of a runtime branch: llvmpipe runs both sides of a branch under
// a mask, so an untaken variant block costs in full (README "What costs what on lavapipe").
using SpecConstants = std::vector<std::uint32_t>;

// Both create functions go through the Context's pipeline table (pipeline_table.hpp): with reuse
// on (the default) an identical earlier request's pipeline comes back, held by the table; with it
// off every call builds and owns a new one. `cache` only matters when the driver builds.
Pipeline createComputePipeline(Context& ctx, const PipelineLayout& layout, const ShaderModule& shader,
                               const std::string& name, const PipelineCache* cache = nullptr,
                               const SpecConstants& specialization = {});

struct VertexBinding {
  std::uint32_t binding = 0;
  std::uint32_t stride = 0;
  bool perInstance = false;
};
struct VertexAttribute {
  std::uint32_t location = 0;
  std::uint32_t binding = 0;
  VkFormat format = VK_FORMAT_R32G32B32_SFLOAT;
  std::uint32_t offset = 0;
};

enum class Blend {
  None,      // overwrite
  Alpha,     // src·a + dst·(1−a)
  Additive,  // src + dst (accumulating light contributions)
};

struct GraphicsPipelineDesc {
  const ShaderModule* vertex = nullptr;
  const ShaderModule* fragment = nullptr;  // null: depth-only (shadow maps)
  std::vector<VertexBinding> bindings;     // empty: vertices come from gl_VertexIndex
  std::vector<VertexAttribute> attributes;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  std::vector<VkFormat> colorFormats;
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;
  VkCullModeFlags cull = VK_CULL_MODE_NONE;
  VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;  // glTF winding
  VkPolygonMode polygonMode = VK_POLYGON_MODE_FILL;
  Blend blend = Blend::None;  // applied to every colour target
  bool depthTest = false;
  bool depthWrite = false;
  VkCompareOp depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
  bool depthBias = false;  // dynamic state: set with vkCmdSetDepthBias
  SpecConstants specialization;  // constant_id i = specialization[i], vertex and fragment stage
  std::string name;
};

Pipeline createGraphicsPipeline(Context& ctx, const PipelineLayout& layout, const GraphicsPipelineDesc& desc,
                                const PipelineCache* cache = nullptr);

// Sets a viewport (y down, depth 0..1) and scissor covering `extent`.
void setViewportAndScissor(VkCommandBuffer cmd, VkExtent2D extent);

}  // namespace bounce::gpu
