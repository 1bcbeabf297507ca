#include "engine/render/vk_backend.hpp"

#include "engine/core/error.hpp"
#include "engine/gpu/context.hpp"

namespace bounce::render {

VkFormat toVkFormat(rg::Format f) {
  using F = rg::Format;
  switch (f) {
    case F::R8_UNORM: return VK_FORMAT_R8_UNORM;
    case F::RGBA8_UNORM: return VK_FORMAT_R8G8B8A8_UNORM;
    case F::RGBA8_SRGB: return VK_FORMAT_R8G8B8A8_SRGB;
    case F::BGRA8_UNORM: return VK_FORMAT_B8G8R8A8_UNORM;
    case F::BGRA8_SRGB: return VK_FORMAT_B8G8R8A8_SRGB;
    case F::R16F: return VK_FORMAT_R16_SFLOAT;
    case F::RG16F: return VK_FORMAT_R16G16_SFLOAT;
    case F::RGBA16F: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case F::R32F: return VK_FORMAT_R32_SFLOAT;
    case F::RG32F: return VK_FORMAT_R32G32_SFLOAT;
    case F::RGBA32F: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case F::R32_UINT: return VK_FORMAT_R32_UINT;
    case F::D16_UNORM: return VK_FORMAT_D16_UNORM;
    case F::D32F: return VK_FORMAT_D32_SFLOAT;
  }
  throw InternalError("render: unknown graph format");
}

VkImageLayout toVkLayout(rg::Layout l) {
  using L = rg::Layout;
  switch (l) {
    case L::Undefined: return VK_IMAGE_LAYOUT_UNDEFINED;
    case L::General: return VK_IMAGE_LAYOUT_GENERAL;
    case L::ColorAttachment: return VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    case L::DepthAttachment: return VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    case L::DepthReadOnly: return VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
    case L::ShaderReadOnly: return VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    case L::TransferSrc: return VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    case L::TransferDst: return VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    case L::Present: return VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  }
  throw InternalError("render: unknown graph layout");
}

VkPipelineStageFlags toVkStages(rg::Stage s) {
  using S = rg::Stage;
  static const std::pair<S, VkPipelineStageFlags> table[] = {
      {S::DrawIndirect, VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT},
      {S::VertexInput, VK_PIPELINE_STAGE_VERTEX_INPUT_BIT},
      {S::VertexShader, VK_PIPELINE_STAGE_VERTEX_SHADER_BIT},
      {S::FragmentShader, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT},
      {S::EarlyFragmentTests, VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT},
      {S::LateFragmentTests, VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT},
      {S::ColorAttachmentOutput, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT},
      {S::ComputeShader, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT},
      {S::Transfer, VK_PIPELINE_STAGE_TRANSFER_BIT},
  };
  VkPipelineStageFlags out = 0;
  for (auto [bit, vk] : table)
    if ((s & bit) != S::None) out |= vk;
  return out;
}

VkAccessFlags toVkAccess(rg::Access a) {
  using A = rg::Access;
  static const std::pair<A, VkAccessFlags> table[] = {
      {A::IndirectCommandRead, VK_ACCESS_INDIRECT_COMMAND_READ_BIT},
      {A::IndexRead, VK_ACCESS_INDEX_READ_BIT},
      {A::VertexAttributeRead, VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT},
      {A::UniformRead, VK_ACCESS_UNIFORM_READ_BIT},
      {A::ShaderSampledRead, VK_ACCESS_SHADER_READ_BIT},
      {A::ShaderStorageRead, VK_ACCESS_SHADER_READ_BIT},
      {A::ShaderStorageWrite, VK_ACCESS_SHADER_WRITE_BIT},
      {A::ColorAttachmentRead, VK_ACCESS_COLOR_ATTACHMENT_READ_BIT},
      {A::ColorAttachmentWrite, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT},
      {A::DepthStencilRead, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT},
      {A::DepthStencilWrite, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT},
      {A::TransferRead, VK_ACCESS_TRANSFER_READ_BIT},
      {A::TransferWrite, VK_ACCESS_TRANSFER_WRITE_BIT},
  };
  VkAccessFlags out = 0;
  for (auto [bit, vk] : table)
    if ((a & bit) != A::None) out |= vk;
  return out;
}

namespace {

VkImageUsageFlags imageUsage(rg::UsageSet u, bool depth) {
  using U = rg::Usage;
  VkImageUsageFlags f = 0;
  if (u.has(U::SampledFragment) || u.has(U::SampledCompute) || u.has(U::SampledGraphics)) f |= VK_IMAGE_USAGE_SAMPLED_BIT;
  if (u.has(U::StorageRead) || u.has(U::StorageWrite)) f |= VK_IMAGE_USAGE_STORAGE_BIT;
  if (u.has(U::ColorAttachment)) f |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if (u.has(U::DepthAttachment) || u.has(U::DepthRead)) f |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
  if (u.has(U::TransferSrc)) f |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (u.has(U::TransferDst)) f |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  (void)depth;
  return f;
}

VkBufferUsageFlags bufferUsage(rg::UsageSet u) {
  using U = rg::Usage;
  VkBufferUsageFlags f = 0;
  if (u.has(U::StorageRead) || u.has(U::StorageWrite)) f |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (u.has(U::UniformBuffer)) f |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
  if (u.has(U::VertexBuffer)) f |= VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
  if (u.has(U::IndexBuffer)) f |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
  if (u.has(U::IndirectBuffer)) f |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
  if (u.has(U::TransferSrc)) f |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  if (u.has(U::TransferDst)) f |= VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  return f;
}

bool sameDesc(const rg::TextureDesc& a, const rg::TextureDesc& b) {
  return a.width == b.width && a.height == b.height && a.depth == b.depth && a.layers == b.layers &&
         a.mips == b.mips && a.format == b.format && a.cube == b.cube;
}

}  // namespace

VkBackend::VkBackend(gpu::Context& ctx, std::uint32_t frameSlots) : ctx_(ctx), slots_(frameSlots) {}
VkBackend::~VkBackend() = default;

void VkBackend::beginFrame(std::uint32_t slot, gpu::TimestampPool* timestamps) {
  layout_journal_.clear();  // first: abandonFrame() after a throw below must not replay the last frame
  if (slot >= slots_.size()) throw InternalError("render: frame slot out of range");
  slot_ = slot;
  timestamps_ = timestamps;
  imported_images_.clear();
  imported_buffers_.clear();
  for (auto& p : slots_[slot_].images) p.inUse = false;
  for (auto& p : slots_[slot_].buffers) p.inUse = false;
}

void VkBackend::abandonFrame() noexcept {
  for (auto it = layout_journal_.rbegin(); it != layout_journal_.rend(); ++it) it->first->setLayout(it->second);
  layout_journal_.clear();
}

rg::PhysicalId VkBackend::importImage(gpu::Image& image) {
  imported_images_.push_back(&image);
  return kImportBit | imported_images_.size();
}

rg::PhysicalId VkBackend::importBuffer(gpu::Buffer& buffer) {
  imported_buffers_.push_back(&buffer);
  return kBufferBit | kImportBit | imported_buffers_.size();
}

gpu::Image& VkBackend::image(rg::PhysicalId id) {
  if (id & kBufferBit) throw InternalError("render: physical id names a buffer, not an image");
  std::uint64_t index = (id & ~kImportBit) - 1;
  if (id & kImportBit) {
    if (index >= imported_images_.size()) throw InternalError("render: stale imported image id");
    return *imported_images_[index];
  }
  auto& pool = slots_[slot_].images;
  if (index >= pool.size()) throw InternalError("render: unknown transient image id");
  return *pool[index].image;
}

gpu::Buffer& VkBackend::buffer(rg::PhysicalId id) {
  if (!(id & kBufferBit)) throw InternalError("render: physical id names an image, not a buffer");
  std::uint64_t index = (id & ~(kBufferBit | kImportBit)) - 1;
  if (id & kImportBit) {
    if (index >= imported_buffers_.size()) throw InternalError("render: stale imported buffer id");
    return *imported_buffers_[index];
  }
  auto& pool = slots_[slot_].buffers;
  if (index >= pool.size()) throw InternalError("render: unknown transient buffer id");
  return *pool[index].buffer;
}

rg::PhysicalId VkBackend::createTexture(const rg::TextureDesc& desc, rg::UsageSet usages, std::string_view name) {
  const VkImageUsageFlags usage = imageUsage(usages, rg::isDepthFormat(desc.format));
  auto& pool = slots_[slot_].images;
  for (std::size_t i = 0; i < pool.size(); ++i) {
    auto& p = pool[i];
    if (!p.inUse && sameDesc(p.desc, desc) && (p.usage & usage) == usage) {
      p.inUse = true;
      return i + 1;
    }
  }
  gpu::ImageDesc d;
  d.type = desc.cube ? gpu::ImageType::Cube : (desc.depth > 1 ? gpu::ImageType::Tex3D : gpu::ImageType::Tex2D);
  d.format = toVkFormat(desc.format);
  d.width = desc.width;
  d.height = desc.height;
  d.depth = desc.depth;
  d.mipLevels = desc.mips;
  d.layers = desc.layers;  // already 6 per cube (rg::TextureDesc)
  d.usage = usage;
  d.name = std::string(name);
  pool.push_back({std::make_unique<gpu::Image>(ctx_, d), desc, usage, true});
  ++created_images_;
  return pool.size();
}

rg::PhysicalId VkBackend::createBuffer(const rg::BufferDesc& desc, rg::UsageSet usages, std::string_view name) {
  const VkBufferUsageFlags usage = bufferUsage(usages);
  auto& pool = slots_[slot_].buffers;
  for (std::size_t i = 0; i < pool.size(); ++i) {
    auto& p = pool[i];
    if (!p.inUse && p.size == desc.size && (p.usage & usage) == usage) {
      p.inUse = true;
      return kBufferBit | (i + 1);
    }
  }
  gpu::BufferDesc d;
  d.size = desc.size;
  d.usage = usage;
  d.name = std::string(name);
  pool.push_back({std::make_unique<gpu::Buffer>(ctx_, d), desc.size, usage, true});
  return kBufferBit | pool.size();
}

// Pooled: the memory stays with the slot until the slot records again (see the header).
void VkBackend::destroyTexture(rg::PhysicalId) {}
void VkBackend::destroyBuffer(rg::PhysicalId) {}

void VkBackend::barrier(rg::CommandContext& base, std::span<const rg::Barrier> barriers) {
  auto& ctx = static_cast<VkCommandContext&>(base);
  std::vector<VkImageMemoryBarrier> images;
  std::vector<VkBufferMemoryBarrier> buffers;
  VkPipelineStageFlags src = 0, dst = 0;
  for (const auto& b : barriers) {
    src |= toVkStages(b.before.stages);
    dst |= toVkStages(b.after.stages);
    // Only writes need to be made available; reads need execution ordering only.
    const VkAccessFlags srcAccess = toVkAccess(rg::writeAccesses(b.before.access));
    const VkAccessFlags dstAccess = toVkAccess(b.after.access);
    if (b.kind == rg::ResourceKind::Texture) {
      gpu::Image& img = image(b.physical);
      VkImageMemoryBarrier m{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      m.srcAccessMask = srcAccess;
      m.dstAccessMask = dstAccess;
      m.oldLayout = toVkLayout(b.before.layout);
      m.newLayout = toVkLayout(b.after.layout);
      m.srcQueueFamilyIndex = m.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      m.image = img.handle();
      m.subresourceRange = img.fullRange();
      images.push_back(m);
      layout_journal_.emplace_back(&img, img.layout());
      img.setLayout(m.newLayout);
    } else {
      gpu::Buffer& buf = buffer(b.physical);
      VkBufferMemoryBarrier m{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
      m.srcAccessMask = srcAccess;
      m.dstAccessMask = dstAccess;
      m.srcQueueFamilyIndex = m.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      m.buffer = buf.handle();
      m.size = VK_WHOLE_SIZE;
      buffers.push_back(m);
    }
  }
  if (!src) src = VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT;
  if (!dst) dst = VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT;
  vkCmdPipelineBarrier(ctx.cmd, src, dst, 0, 0, nullptr, static_cast<std::uint32_t>(buffers.size()), buffers.data(),
                       static_cast<std::uint32_t>(images.size()), images.data());
}

void VkBackend::beginPass(rg::CommandContext& base, std::string_view name) {
  auto& ctx = static_cast<VkCommandContext&>(base);
  if (timestamps_) {
    timestamps_->begin(ctx.cmd, std::string(name));
  }
  ctx_.beginLabel(ctx.cmd, std::string(name));
}

void VkBackend::endPass(rg::CommandContext& base) {
  auto& ctx = static_cast<VkCommandContext&>(base);
  ctx_.endLabel(ctx.cmd);
  if (timestamps_) timestamps_->end(ctx.cmd);
}

}  // namespace bounce::render
