#pragma once
// Virtual resources of the render graph: what a pass asks for (a description) and how it
// names a particular state of it (a versioned handle). No Vulkan here: formats are an engine
// enum that the Vulkan backend maps to VkFormat.
#include <cstdint>
#include <limits>
#include <string>

namespace bounce::rg {

// Pixel formats the engine renders to or samples. Depth formats can only be depth attachments
// or sampled; the rest can be colour attachments (see usage.hpp for which usage needs what).
enum class Format : std::uint8_t {
  R8_UNORM,
  RGBA8_UNORM,
  RGBA8_SRGB,
  BGRA8_UNORM,  // the swapchain's format on the target machine (8-bit BGRA only)
  BGRA8_SRGB,
  R16F,
  RG16F,
  RGBA16F,
  R32F,
  RG32F,
  RGBA32F,
  R32_UINT,
  D16_UNORM,
  D32F,
};

bool isDepthFormat(Format format);
const char* formatName(Format format);

enum class ResourceKind : std::uint8_t { Texture, Buffer };

// A 2D, 2D-array, cube(-array) or 3D texture. `depth` > 1 makes it 3D (voxel grids such as baked
// transfer fields); `layers` > 1 makes it an array; `cube` needs `layers` a multiple of 6 and a
// square face.
struct TextureDesc {
  std::uint32_t width = 1;   // texels
  std::uint32_t height = 1;  // texels
  std::uint32_t depth = 1;   // texels along z for a 3D texture, 1 otherwise
  std::uint32_t layers = 1;  // array layers (6 per cube)
  std::uint32_t mips = 1;    // mip levels, 1 = no mip chain
  Format format = Format::RGBA8_UNORM;
  bool cube = false;

  bool operator==(const TextureDesc&) const = default;
};

struct BufferDesc {
  std::uint64_t size = 0;  // bytes

  bool operator==(const BufferDesc&) const = default;
};

// Throw InternalError naming `resource` when the description cannot describe a real image or
// buffer (zero size, too many mips, a non-square cube, a 3D array ...).
void validate(const TextureDesc& desc, const std::string& resource);
void validate(const BufferDesc& desc, const std::string& resource);

// "1280x720 RGBA16F", "64x64x64 R32F mips 7", "4096 bytes": for errors and the DOT dump.
std::string describe(const TextureDesc& desc);
std::string describe(const BufferDesc& desc);

// Type tags: Handle<Texture>, Handle<Buffer>, builder.create<Texture>(name, TextureDesc{...}).
struct Texture {
  using Desc = TextureDesc;
  static constexpr ResourceKind kind = ResourceKind::Texture;
};
struct Buffer {
  using Desc = BufferDesc;
  static constexpr ResourceKind kind = ResourceKind::Buffer;
};

// Names one version of one virtual resource. Version 0 is the content a resource starts with
// (undefined for a created resource, the imported content for an imported one); each write()
// returns the next version. Only the newest version may be read or written: holding on to an
// older handle after another pass wrote the resource is an error (the graph throws, naming the
// pass and the resource), because it would silently read data that is no longer there.
template <typename T>
struct Handle {
  static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t index = kInvalid;  // index of the virtual resource in its graph
  std::uint32_t version = 0;

  bool valid() const { return index != kInvalid; }
  bool operator==(const Handle&) const = default;
};

}  // namespace bounce::rg
