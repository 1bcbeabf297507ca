#pragma once
// Facts about the VkFormats Bounce uses, and half-float conversion for readbacks.
#include <cstdint>

#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

// Bytes per texel; throws InternalError for formats this table does not know (compressed ones).
std::uint32_t texelBytes(VkFormat format);
bool isDepthFormat(VkFormat format);
bool hasStencil(VkFormat format);
VkImageAspectFlags aspectOf(VkFormat format);
const char* formatName(VkFormat format);

// IEEE 754 binary16 ↔ binary32, round to nearest even; Inf/NaN preserved.
float halfToFloat(std::uint16_t h);
std::uint16_t floatToHalf(float f);

}  // namespace bounce::gpu
