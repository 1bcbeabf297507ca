#include "engine/gpu/buffer.hpp"

#include <utility>

#include "engine/core/error.hpp"
#include "engine/gpu/context.hpp"

namespace bounce::gpu {

Buffer::Buffer(Context& ctx, const BufferDesc& desc) : ctx_(&ctx), desc_(desc) {
  if (desc.size == 0) throw InternalError("vulkan: buffer '" + desc.name + "' has size 0");
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = desc.size;
  ci.usage = desc.usage;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(ctx.device(), &ci, nullptr, &buffer_), "vkCreateBuffer");
  try {
    allocation_ = ctx.allocator().allocateFor(buffer_, desc.memory, desc.name);
  } catch (...) {
    vkDestroyBuffer(ctx.device(), buffer_, nullptr);
    throw;
  }
  ctx.setName(VK_OBJECT_TYPE_BUFFER, buffer_, desc.name);
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    reset();
    ctx_ = std::exchange(other.ctx_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    allocation_ = std::exchange(other.allocation_, {});
    desc_ = std::move(other.desc_);
  }
  return *this;
}

void Buffer::reset() {
  if (buffer_) {
    vkDestroyBuffer(ctx_->device(), buffer_, nullptr);
    ctx_->allocator().free(allocation_);
  }
  buffer_ = VK_NULL_HANDLE;
  allocation_ = {};
}

}  // namespace bounce::gpu
