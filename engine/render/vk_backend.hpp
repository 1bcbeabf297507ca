#pragma once
// The render graph's Vulkan backend: turns the graph's abstract barriers into
// vkCmdPipelineBarrier calls, its transient resources into pooled gpu::Images / gpu::Buffers, and
// each pass into a GPU timestamp scope with a debug label of the same name (RenderDoc groups
// commands by pass).
//
// Transient memory is pooled per frame slot: the graph "destroys" a transient when it finishes
// recording, but the GPU runs the frame later, so the physical image goes back to its slot's
// pool and is reused only when that slot records again — after FrameRing::begin() waited for the
// slot's fence. Frames in flight never share a transient.
#include <deque>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/timestamps.hpp"
#include "engine/render/graph/backend.hpp"
#include "engine/render/graph/usage.hpp"

namespace bounce::render {

// What execute callbacks receive: the frame's command buffer and the backend to resolve ids.
class VkBackend;
struct VkCommandContext final : rg::CommandContext {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkBackend* backend = nullptr;
};

VkFormat toVkFormat(rg::Format format);
VkImageLayout toVkLayout(rg::Layout layout);
VkPipelineStageFlags toVkStages(rg::Stage stages);
VkAccessFlags toVkAccess(rg::Access access);

class VkBackend final : public rg::Backend {
 public:
  VkBackend(gpu::Context& ctx, std::uint32_t frameSlots);
  ~VkBackend() override;

  // Call once per frame before the graph executes: selects the slot's pool and timestamp pool.
  void beginFrame(std::uint32_t slot, gpu::TimestampPool* timestamps);
  // The frame begun last will not be submitted (FrameRing::abandon): puts back the tracked layout
  // (gpu::Image::layout()) of every image this frame's barriers changed, so that the next frame's
  // first barriers start from what the GPU holds. Images a pass transitions itself (gpu::transition
  // in an execute callback) are not tracked here.
  void abandonFrame() noexcept;

  // Registers an image / buffer owned elsewhere (swapchain copy source, persistent fields) for
  // RenderGraph::importTexture/importBuffer. Valid until the next beginFrame().
  rg::PhysicalId importImage(gpu::Image& image);
  rg::PhysicalId importBuffer(gpu::Buffer& buffer);

  gpu::Image& image(rg::PhysicalId id);
  gpu::Buffer& buffer(rg::PhysicalId id);

  // rg::Backend
  rg::PhysicalId createTexture(const rg::TextureDesc& desc, rg::UsageSet usages, std::string_view debugName) override;
  rg::PhysicalId createBuffer(const rg::BufferDesc& desc, rg::UsageSet usages, std::string_view debugName) override;
  void destroyTexture(rg::PhysicalId id) override;
  void destroyBuffer(rg::PhysicalId id) override;
  void barrier(rg::CommandContext& ctx, std::span<const rg::Barrier> barriers) override;
  void beginPass(rg::CommandContext& ctx, std::string_view name) override;
  void endPass(rg::CommandContext& ctx) override;

  // Physical images created so far across all slots (tests: pooling keeps this flat).
  std::size_t createdImages() const { return created_images_; }

 private:
  struct PooledImage {
    std::unique_ptr<gpu::Image> image;
    rg::TextureDesc desc;
    VkImageUsageFlags usage = 0;
    bool inUse = false;
  };
  struct PooledBuffer {
    std::unique_ptr<gpu::Buffer> buffer;
    VkDeviceSize size = 0;
    VkBufferUsageFlags usage = 0;
    bool inUse = false;
  };
  struct Slot {
    std::vector<PooledImage> images;
    std::vector<PooledBuffer> buffers;
  };
  // Physical ids: bit 63 set for buffers, bit 62 for imports, low bits index the slot's pool.
  static constexpr std::uint64_t kBufferBit = 1ull << 63, kImportBit = 1ull << 62;

  gpu::Context& ctx_;
  std::vector<Slot> slots_;
  std::uint32_t slot_ = 0;
  gpu::TimestampPool* timestamps_ = nullptr;
  std::vector<gpu::Image*> imported_images_;
  std::vector<gpu::Buffer*> imported_buffers_;
  // Since beginFrame(): each image barrier's image and the layout tracked before it, oldest first
  // (abandonFrame() restores them newest first, so the first one's wins).
  std::vector<std::pair<gpu::Image*, VkImageLayout>> layout_journal_;
  std::size_t created_images_ = 0;
};

}  // namespace bounce::render
