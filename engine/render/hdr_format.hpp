#pragma once
// The format of "lighting.hdr", the HDR target every lighting and GI pass adds into (renderer.cpp creates
// it; the passes' pipelines must name the same colour format). One constant, so the two cannot drift.
#include <vulkan/vulkan.h>

namespace bounce::render {

inline constexpr VkFormat kLightingHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

}  // namespace bounce::render
