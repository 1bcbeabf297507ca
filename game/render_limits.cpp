#include "game/render_limits.hpp"

#include <algorithm>
#include <cstdio>

#include "engine/core/error.hpp"
#include "engine/gpu/context.hpp"

namespace bounce::game {

std::uint64_t frameImageBytes(VkExtent2D extent) {
  return std::uint64_t(extent.width) * extent.height * kFrameBytesPerPixel;
}

void checkRenderSize(const gpu::Context& ctx, VkExtent2D extent, const std::string& file, const std::string& where) {
  const std::string size = std::to_string(extent.width) + "x" + std::to_string(extent.height);
  const std::uint32_t maxSide = ctx.limits().maxImageDimension2D;
  if (extent.width > maxSide || extent.height > maxSide)
    throwInputError(file, where, size + " exceeds the device's largest image side (" + ctx.deviceName() + ")",
                    "each side at most " + std::to_string(maxSide));
  VkPhysicalDeviceMemoryProperties memory{};
  vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice(), &memory);
  VkDeviceSize heap = 0;
  for (std::uint32_t i = 0; i < memory.memoryHeapCount; ++i)
    if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) heap = std::max(heap, memory.memoryHeaps[i].size);
  const double gib = 1024.0 * 1024.0 * 1024.0;
  const std::uint64_t need = frameImageBytes(extent);
  if (heap > 0 && double(need) > kMaxHeapFraction * double(heap)) {
    char text[256];
    std::snprintf(text, sizeof text, "%s needs about %.1f GiB of frame images; the device (%s) has %.1f GiB", size.c_str(),
                  double(need) / gib, ctx.deviceName().c_str(), double(heap) / gib);
    char expected[128];
    std::snprintf(expected, sizeof expected, "at most %.1f GiB, e.g. %ux%u", kMaxHeapFraction * double(heap) / gib, 3840u, 2160u);
    throwInputError(file, where, text, expected);
  }
}

}  // namespace bounce::game
