#include "engine/gpu/image.hpp"

#include <algorithm>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/format.hpp"

namespace bounce::gpu {

std::uint32_t fullMipCount(std::uint32_t w, std::uint32_t h, std::uint32_t d) {
  std::uint32_t m = std::max({w, h, d, 1u}), n = 1;
  while (m >>= 1) ++n;
  return n;
}

ImageView::ImageView(Context& ctx, VkImageViewCreateInfo info, const std::string& name) : ctx_(&ctx) {
  check(vkCreateImageView(ctx.device(), &info, nullptr, &view_), "vkCreateImageView");
  ctx.setName(VK_OBJECT_TYPE_IMAGE_VIEW, view_, name);
}

ImageView& ImageView::operator=(ImageView&& other) noexcept {
  if (this != &other) {
    reset();
    ctx_ = std::exchange(other.ctx_, nullptr);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
  }
  return *this;
}

void ImageView::reset() {
  if (view_) vkDestroyImageView(ctx_->device(), view_, nullptr);
  view_ = VK_NULL_HANDLE;
}

Image::Image(Context& ctx, const ImageDesc& desc) : ctx_(&ctx), desc_(desc) {
  auto fail = [&](const std::string& what) { throw InternalError("vulkan: image '" + desc.name + "': " + what); };
  if (desc.width == 0 || desc.height == 0 || desc.depth == 0 || desc.layers == 0 || desc.mipLevels == 0)
    fail("zero extent, layer or mip count");
  if (desc.mipLevels > fullMipCount(desc.width, desc.height, desc.depth)) fail("more mips than the extent allows");
  if (desc.type == ImageType::Cube && (desc.layers % 6 != 0 || desc.width != desc.height || desc.depth != 1))
    fail("a cube needs square faces, depth 1 and a multiple of 6 layers");
  if (desc.type == ImageType::Tex3D && desc.layers != 1) fail("a 3D image has one layer");
  if (desc.type != ImageType::Tex3D && desc.depth != 1) fail("only 3D images have depth");

  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = desc.type == ImageType::Tex3D ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  ci.flags = desc.type == ImageType::Cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
  ci.format = desc.format;
  ci.extent = {desc.width, desc.height, desc.depth};
  ci.mipLevels = desc.mipLevels;
  ci.arrayLayers = desc.layers;
  ci.samples = desc.samples;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = desc.usage;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  check(vkCreateImage(ctx.device(), &ci, nullptr, &image_), "vkCreateImage");
  try {
    allocation_ = ctx.allocator().allocateFor(image_, MemoryUsage::GpuOnly, false, desc.name);
  } catch (...) {
    vkDestroyImage(ctx.device(), image_, nullptr);
    image_ = VK_NULL_HANDLE;
    throw;
  }
  ctx.setName(VK_OBJECT_TYPE_IMAGE, image_, desc.name);

  VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D;
  switch (desc.type) {
    case ImageType::Tex2D: viewType = desc.layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D; break;
    case ImageType::Tex3D: viewType = VK_IMAGE_VIEW_TYPE_3D; break;
    case ImageType::Cube: viewType = desc.layers > 6 ? VK_IMAGE_VIEW_TYPE_CUBE_ARRAY : VK_IMAGE_VIEW_TYPE_CUBE; break;
  }
  constexpr VkImageUsageFlags kViewable = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                          VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
  if (!(desc.usage & kViewable)) return;
  try {
    view_ = createView(viewType, 0, desc.mipLevels, 0, desc.layers, desc.name + " view");
  } catch (...) {
    reset();
    throw;
  }
}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    reset();
    ctx_ = std::exchange(other.ctx_, nullptr);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    allocation_ = std::exchange(other.allocation_, {});
    view_ = std::move(other.view_);
    desc_ = std::move(other.desc_);
    layout_ = std::exchange(other.layout_, VK_IMAGE_LAYOUT_UNDEFINED);
  }
  return *this;
}

void Image::reset() {
  view_.reset();
  if (image_) {
    vkDestroyImage(ctx_->device(), image_, nullptr);
    ctx_->allocator().free(allocation_);
  }
  image_ = VK_NULL_HANDLE;
  allocation_ = {};
  layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
}

VkExtent3D Image::extent(std::uint32_t mip) const {
  return {std::max(desc_.width >> mip, 1u), std::max(desc_.height >> mip, 1u), std::max(desc_.depth >> mip, 1u)};
}

VkImageAspectFlags Image::aspect() const { return aspectOf(desc_.format); }

VkImageSubresourceRange Image::fullRange() const { return {aspect(), 0, desc_.mipLevels, 0, desc_.layers}; }

ImageView Image::createView(VkImageViewType type, std::uint32_t baseMip, std::uint32_t mipCount,
                            std::uint32_t baseLayer, std::uint32_t layerCount, const std::string& name) const {
  if (baseMip + mipCount > desc_.mipLevels || baseLayer + layerCount > desc_.layers)
    throw InternalError("vulkan: view '" + name + "' exceeds the mips or layers of image '" + desc_.name + "'");
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = image_;
  vi.viewType = type;
  vi.format = desc_.format;
  // Depth+stencil images are sampled through their depth aspect.
  VkImageAspectFlags a = aspect();
  if (a & VK_IMAGE_ASPECT_DEPTH_BIT) a = VK_IMAGE_ASPECT_DEPTH_BIT;
  vi.subresourceRange = {a, baseMip, mipCount, baseLayer, layerCount};
  return ImageView(*ctx_, vi, name);
}

}  // namespace bounce::gpu
