#include "engine/gpu/pipeline.hpp"

#include <cstring>
#include <type_traits>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/core/file.hpp"
#include "engine/core/hash.hpp"
#include "engine/core/paths.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/pipeline_table.hpp"

namespace bounce::gpu {

std::filesystem::path shaderPath(const std::string& relative) {
  return shaderDir() / relative;
}

ShaderModule::ShaderModule(Context& ctx, const std::string& relative) {
  *this = fromFile(ctx, shaderPath(relative));
  name_ = relative;
}

ShaderModule ShaderModule::fromFile(Context& ctx, const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InternalError("vulkan: shader " + path.string() +
                        " not found (is its source under shaders/ and the bounce_shaders target built?)");
  std::vector<std::uint8_t> bytes = readFileBytes(path);
  constexpr std::uint32_t kSpirvMagic = 0x07230203;
  std::uint32_t magic = 0;
  if (bytes.size() >= 4) std::memcpy(&magic, bytes.data(), 4);
  if (bytes.size() < 20 || bytes.size() % 4 != 0 || magic != kSpirvMagic)
    throw InternalError("vulkan: shader " + path.string() + " is not SPIR-V (" + std::to_string(bytes.size()) +
                        " bytes)");
  std::vector<std::uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), bytes.size());
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = bytes.size();
  ci.pCode = words.data();
  ShaderModule m;
  m.ctx_ = &ctx;
  m.name_ = path.filename().string();
  m.spirv_hash_ = Hasher().u64(words.size()).bytes(words.data(), bytes.size()).digest();
  check(vkCreateShaderModule(ctx.device(), &ci, nullptr, &m.module_), "vkCreateShaderModule");
  ctx.setName(VK_OBJECT_TYPE_SHADER_MODULE, m.module_, m.name_);
  return m;
}

ShaderModule& ShaderModule::operator=(ShaderModule&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    module_ = std::exchange(o.module_, VK_NULL_HANDLE);
    name_ = std::move(o.name_);
    spirv_hash_ = std::exchange(o.spirv_hash_, 0);
  }
  return *this;
}

void ShaderModule::reset() {
  if (module_) vkDestroyShaderModule(ctx_->device(), module_, nullptr);
  module_ = VK_NULL_HANDLE;
}

PipelineLayout::PipelineLayout(Context& ctx, const SetLayouts& sets,
                               const std::vector<VkPushConstantRange>& pushConstants, const std::string& name)
    : ctx_(&ctx), push_constants_(pushConstants) {
  std::vector<VkDescriptorSetLayout> handles;
  for (const DescriptorSetLayout& s : sets) {
    handles.push_back(s.handle());
    set_bindings_.push_back(s.bindings());
  }
  VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  ci.setLayoutCount = static_cast<std::uint32_t>(handles.size());
  ci.pSetLayouts = handles.data();
  ci.pushConstantRangeCount = static_cast<std::uint32_t>(pushConstants.size());
  ci.pPushConstantRanges = pushConstants.data();
  check(vkCreatePipelineLayout(ctx.device(), &ci, nullptr, &layout_), "vkCreatePipelineLayout");
  ctx.setName(VK_OBJECT_TYPE_PIPELINE_LAYOUT, layout_, name);
}

PipelineLayout& PipelineLayout::operator=(PipelineLayout&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    set_bindings_ = std::move(o.set_bindings_);
    push_constants_ = std::move(o.push_constants_);
  }
  return *this;
}

void PipelineLayout::reset() {
  if (layout_) vkDestroyPipelineLayout(ctx_->device(), layout_, nullptr);
  layout_ = VK_NULL_HANDLE;
}

PipelineCache::PipelineCache(Context& ctx, std::filesystem::path file) : ctx_(ctx), file_(std::move(file)) {
  std::vector<std::uint8_t> data;
  std::error_code ec;
  if (!file_.empty() && std::filesystem::is_regular_file(file_, ec)) data = readFileBytes(file_);
  VkPipelineCacheCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  ci.initialDataSize = data.size();
  ci.pInitialData = data.empty() ? nullptr : data.data();
  check(vkCreatePipelineCache(ctx.device(), &ci, nullptr, &cache_), "vkCreatePipelineCache");
}

PipelineCache::~PipelineCache() { vkDestroyPipelineCache(ctx_.device(), cache_, nullptr); }

void PipelineCache::save() const {
  if (file_.empty()) return;
  std::size_t size = 0;
  check(vkGetPipelineCacheData(ctx_.device(), cache_, &size, nullptr), "vkGetPipelineCacheData");
  std::vector<std::uint8_t> data(size);
  check(vkGetPipelineCacheData(ctx_.device(), cache_, &size, data.data()), "vkGetPipelineCacheData");
  data.resize(size);
  writeFileAtomic(file_, data);
}

Pipeline::Pipeline(Context& ctx, VkPipeline pipeline, VkPipelineBindPoint bindPoint, VkPipelineLayout layout,
                   bool heldByTable)
    : ctx_(&ctx), pipeline_(pipeline), bind_point_(bindPoint), layout_(layout), held_by_table_(heldByTable) {}

Pipeline& Pipeline::operator=(Pipeline&& o) noexcept {
  if (this != &o) {
    reset();
    ctx_ = std::exchange(o.ctx_, nullptr);
    pipeline_ = std::exchange(o.pipeline_, VK_NULL_HANDLE);
    bind_point_ = o.bind_point_;
    layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
    held_by_table_ = std::exchange(o.held_by_table_, false);
  }
  return *this;
}

void Pipeline::reset() {
  if (pipeline_ && !held_by_table_) vkDestroyPipeline(ctx_->device(), pipeline_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
  held_by_table_ = false;
}

namespace {

// Map entries for constant_id 0..n-1 over `values` (kept alive by the caller for the create call).
struct Specialization {
  std::vector<VkSpecializationMapEntry> entries;
  VkSpecializationInfo info{};
  explicit Specialization(const SpecConstants& values) {
    for (std::uint32_t i = 0; i < values.size(); ++i)
      entries.push_back({i, i * std::uint32_t(sizeof(std::uint32_t)), sizeof(std::uint32_t)});
    info.mapEntryCount = std::uint32_t(entries.size());
    info.pMapEntries = entries.data();
    info.dataSize = values.size() * sizeof(std::uint32_t);
    info.pData = values.data();
  }
  const VkSpecializationInfo* get() const { return entries.empty() ? nullptr : &info; }
};

// The pipeline table's key bytes (pipeline_table.hpp): each value appended whole, field by field
// (never a struct with padding), so equal keys mean equal creation inputs — the SPIR-V by hash.
struct Key {
  std::string bytes;
  template <class T>
    requires std::is_trivially_copyable_v<T>
  Key& pod(const T& v) {
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
    return *this;
  }
  Key& shader(const ShaderModule* m) {
    pod(m != nullptr);
    return m ? pod(m->spirvHash()) : *this;
  }
  Key& constants(const SpecConstants& values) {
    pod(std::uint64_t(values.size()));
    for (std::uint32_t v : values) pod(v);
    return *this;
  }
};

std::string computeKey(const ShaderModule& shader, const SpecConstants& specialization) {
  return Key().pod('C').shader(&shader).constants(specialization).bytes;
}

std::string graphicsKey(const GraphicsPipelineDesc& desc) {
  // Every member of the desc, in order: a member added to GraphicsPipelineDesc fails to compile
  // here until it joins the key (or is named as left out, as `name` is: a debug name only).
  [[maybe_unused]] const auto& [vertex, fragment, bindings, attributes, topology, colorFormats, depthFormat, cull,
                                frontFace, polygonMode, blend, depthTest, depthWrite, depthCompare, depthBias,
                                specialization, name] = desc;
  Key k;
  k.pod('G').shader(vertex).shader(fragment);
  k.pod(std::uint64_t(bindings.size()));
  for (const VertexBinding& b : bindings) k.pod(b.binding).pod(b.stride).pod(b.perInstance);
  k.pod(std::uint64_t(attributes.size()));
  for (const VertexAttribute& a : attributes) k.pod(a.location).pod(a.binding).pod(a.format).pod(a.offset);
  k.pod(topology);
  k.pod(std::uint64_t(colorFormats.size()));
  for (VkFormat f : colorFormats) k.pod(f);
  k.pod(depthFormat).pod(cull).pod(frontFace).pod(polygonMode).pod(blend);
  k.pod(depthTest).pod(depthWrite).pod(depthCompare).pod(depthBias);
  k.constants(specialization);
  return k.bytes;
}

VkPipeline buildCompute(Context& ctx, VkPipelineLayout layout, const ShaderModule& shader,
                        const SpecConstants& specialization, const PipelineCache* cache) {
  const Specialization spec(specialization);
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = shader.handle();
  ci.stage.pName = "main";
  ci.stage.pSpecializationInfo = spec.get();
  ci.layout = layout;
  VkPipeline p = VK_NULL_HANDLE;
  check(vkCreateComputePipelines(ctx.device(), cache ? cache->handle() : VK_NULL_HANDLE, 1, &ci, nullptr, &p),
        "vkCreateComputePipelines");
  return p;
}

VkPipeline buildGraphics(Context& ctx, VkPipelineLayout layout, const GraphicsPipelineDesc& desc,
                         const PipelineCache* cache);

}  // namespace

Pipeline createComputePipeline(Context& ctx, const PipelineLayout& layout, const ShaderModule& shader,
                               const std::string& name, const PipelineCache* cache, const SpecConstants& specialization) {
  return ctx.pipelines().obtain(computeKey(shader, specialization), layout, VK_PIPELINE_BIND_POINT_COMPUTE, name,
                                [&](VkPipelineLayout vkLayout) {
                                  return buildCompute(ctx, vkLayout, shader, specialization, cache);
                                });
}

Pipeline createGraphicsPipeline(Context& ctx, const PipelineLayout& layout, const GraphicsPipelineDesc& desc,
                                const PipelineCache* cache) {
  if (!desc.vertex) throw InternalError("vulkan: graphics pipeline '" + desc.name + "' has no vertex shader");
  return ctx.pipelines().obtain(graphicsKey(desc), layout, VK_PIPELINE_BIND_POINT_GRAPHICS, desc.name,
                                [&](VkPipelineLayout vkLayout) { return buildGraphics(ctx, vkLayout, desc, cache); });
}

namespace {

VkPipeline buildGraphics(Context& ctx, VkPipelineLayout layout, const GraphicsPipelineDesc& desc,
                         const PipelineCache* cache) {
  const Specialization spec(desc.specialization);
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  VkPipelineShaderStageCreateInfo st{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  st.pSpecializationInfo = spec.get();  // ids a stage does not declare are ignored
  st.stage = VK_SHADER_STAGE_VERTEX_BIT;
  st.module = desc.vertex->handle();
  st.pName = "main";
  stages.push_back(st);
  if (desc.fragment) {
    st.stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    st.module = desc.fragment->handle();
    stages.push_back(st);
  }

  std::vector<VkVertexInputBindingDescription> bindings;
  for (auto& b : desc.bindings)
    bindings.push_back({b.binding, b.stride, b.perInstance ? VK_VERTEX_INPUT_RATE_INSTANCE : VK_VERTEX_INPUT_RATE_VERTEX});
  std::vector<VkVertexInputAttributeDescription> attributes;
  for (auto& a : desc.attributes) attributes.push_back({a.location, a.binding, a.format, a.offset});
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vi.vertexBindingDescriptionCount = static_cast<std::uint32_t>(bindings.size());
  vi.pVertexBindingDescriptions = bindings.data();
  vi.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(attributes.size());
  vi.pVertexAttributeDescriptions = attributes.data();

  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = desc.topology;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = desc.polygonMode;
  rs.cullMode = desc.cull;
  rs.frontFace = desc.frontFace;
  rs.depthBiasEnable = desc.depthBias;
  rs.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = desc.depthTest;
  ds.depthWriteEnable = desc.depthWrite;
  ds.depthCompareOp = desc.depthCompare;

  VkPipelineColorBlendAttachmentState att{};
  att.colorWriteMask =
      VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  if (desc.blend != Blend::None) {
    att.blendEnable = VK_TRUE;
    att.colorBlendOp = att.alphaBlendOp = VK_BLEND_OP_ADD;
    if (desc.blend == Blend::Additive) {
      att.srcColorBlendFactor = att.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
      att.srcAlphaBlendFactor = att.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    } else {
      att.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
      att.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      att.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      att.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    }
  }
  std::vector<VkPipelineColorBlendAttachmentState> atts(desc.colorFormats.size(), att);
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = static_cast<std::uint32_t>(atts.size());
  cb.pAttachments = atts.data();

  std::vector<VkDynamicState> dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  if (desc.depthBias) dynamic.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
  VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dyn.dynamicStateCount = static_cast<std::uint32_t>(dynamic.size());
  dyn.pDynamicStates = dynamic.data();

  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = static_cast<std::uint32_t>(desc.colorFormats.size());
  rendering.pColorAttachmentFormats = desc.colorFormats.data();
  rendering.depthAttachmentFormat = desc.depthFormat;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.pNext = &rendering;
  ci.stageCount = static_cast<std::uint32_t>(stages.size());
  ci.pStages = stages.data();
  ci.pVertexInputState = &vi;
  ci.pInputAssemblyState = &ia;
  ci.pViewportState = &vp;
  ci.pRasterizationState = &rs;
  ci.pMultisampleState = &ms;
  ci.pDepthStencilState = &ds;
  ci.pColorBlendState = &cb;
  ci.pDynamicState = &dyn;
  ci.layout = layout;
  VkPipeline p = VK_NULL_HANDLE;
  check(vkCreateGraphicsPipelines(ctx.device(), cache ? cache->handle() : VK_NULL_HANDLE, 1, &ci, nullptr, &p),
        "vkCreateGraphicsPipelines");
  return p;
}

}  // namespace

void setViewportAndScissor(VkCommandBuffer cmd, VkExtent2D extent) {
  VkViewport v{0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height), 0.0f, 1.0f};
  VkRect2D s{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &v);
  vkCmdSetScissor(cmd, 0, 1, &s);
}

}  // namespace bounce::gpu
