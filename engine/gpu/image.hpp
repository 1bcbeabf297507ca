#pragma once
// Image: a VkImage with its memory and a default view covering every mip and layer (made only
// when the usage allows views: sampled, storage or attachment; transfer-only images have none).
//   Tex2D: layers > 1 makes a 2D array view.   Tex3D: depth > 1, one layer.
//   Cube:  layers = 6 · cubes (faces +X −X +Y −Y +Z −Z), a cube or cube-array view.
// `layout()` is the last known layout of the whole image, kept up to date by the helpers in
// commands.hpp (upload, readback, transition); code that records its own barriers calls
// setLayout() so the next helper starts from the truth.
#include <cstdint>
#include <string>

#include "engine/gpu/memory.hpp"
#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class Context;

enum class ImageType { Tex2D, Tex3D, Cube };

struct ImageDesc {
  ImageType type = ImageType::Tex2D;
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  std::uint32_t width = 1, height = 1, depth = 1;
  std::uint32_t mipLevels = 1;
  std::uint32_t layers = 1;
  VkImageUsageFlags usage = 0;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  std::string name;
};

// Mip count of a full chain for the largest of the dimensions: floor(log2(max)) + 1.
std::uint32_t fullMipCount(std::uint32_t width, std::uint32_t height, std::uint32_t depth = 1);

// An extra view (one mip for a storage write, one face, one layer). Move-only.
class ImageView {
 public:
  ImageView() = default;
  ImageView(Context& ctx, VkImageViewCreateInfo info, const std::string& name);
  ~ImageView() { reset(); }
  ImageView(ImageView&& other) noexcept { *this = std::move(other); }
  ImageView& operator=(ImageView&& other) noexcept;
  ImageView(const ImageView&) = delete;
  ImageView& operator=(const ImageView&) = delete;
  void reset();
  VkImageView handle() const { return view_; }

 private:
  Context* ctx_ = nullptr;
  VkImageView view_ = VK_NULL_HANDLE;
};

class Image {
 public:
  Image() = default;
  Image(Context& ctx, const ImageDesc& desc);
  ~Image() { reset(); }
  Image(Image&& other) noexcept { *this = std::move(other); }
  Image& operator=(Image&& other) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  void reset();
  VkImage handle() const { return image_; }
  VkImageView view() const { return view_.handle(); }  // every mip and layer
  const ImageDesc& desc() const { return desc_; }
  const Allocation& allocation() const { return allocation_; }
  VkFormat format() const { return desc_.format; }
  VkExtent3D extent(std::uint32_t mip = 0) const;
  VkImageAspectFlags aspect() const;
  VkImageSubresourceRange fullRange() const;
  const std::string& name() const { return desc_.name; }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

  VkImageLayout layout() const { return layout_; }
  void setLayout(VkImageLayout layout) { layout_ = layout; }

  // A view of mips [baseMip, baseMip+mipCount) and layers [baseLayer, baseLayer+layerCount) of
  // the given view type (e.g. one cube face as VK_IMAGE_VIEW_TYPE_2D).
  ImageView createView(VkImageViewType type, std::uint32_t baseMip, std::uint32_t mipCount, std::uint32_t baseLayer,
                       std::uint32_t layerCount, const std::string& name) const;

 private:
  Context* ctx_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  Allocation allocation_;
  ImageView view_;
  ImageDesc desc_;
  VkImageLayout layout_ = VK_IMAGE_LAYOUT_UNDEFINED;
};

}  // namespace bounce::gpu
