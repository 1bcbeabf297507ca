#pragma once
// A render size the device cannot hold is refused before any work starts, with one line naming
// the option (exit 2): `--resolution 16384x16384` used to be accepted and then hang on lavapipe.
#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

namespace bounce::gpu {
class Context;
}

namespace bounce::game {

// Upper estimate of the images one frame keeps per pixel: G-buffer (albedo 4, normal 8, emissive 8,
// entity id 4, depth 4), HDR 8, display 4, AO/GI targets and the capture readbacks (~24).
inline constexpr std::uint64_t kFrameBytesPerPixel = 64;
// A frame may use at most this fraction of the largest device-local heap (the rest: meshes, bakes,
// shadow atlas, the driver; on lavapipe the heap is system memory the OS also needs).
inline constexpr double kMaxHeapFraction = 0.5;

// Bytes the frame's images need at `extent` (kFrameBytesPerPixel per pixel).
std::uint64_t frameImageBytes(VkExtent2D extent);

// Throws InputError "`file`: `where`: WxH ... (expected ...)" when either side exceeds the device's
// maxImageDimension2D or the frame's images exceed kMaxHeapFraction of its largest device-local heap.
void checkRenderSize(const gpu::Context& ctx, VkExtent2D extent, const std::string& file, const std::string& where);

}  // namespace bounce::game
