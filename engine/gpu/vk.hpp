#pragma once
// The one place that includes the Vulkan C API, plus result checking. Every failing Vulkan call
// becomes an InternalError naming the call and the result code, so an environment failure (no
// memory, lost device) reads as a sentence instead of a number.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace bounce::gpu {

// "VK_ERROR_OUT_OF_DEVICE_MEMORY" for a result code (the number for unknown codes).
const char* resultName(VkResult result);

// Throws InternalError "vulkan: <what> failed: <result name>" unless `result` is VK_SUCCESS.
void check(VkResult result, const char* what);

// Bytes of any contiguous container of trivially copyable values, for upload helpers.
template <class T>
std::span<const std::uint8_t> bytesOf(std::span<const T> values) {
  return {reinterpret_cast<const std::uint8_t*>(values.data()), values.size_bytes()};
}
template <class T>
std::span<const std::uint8_t> bytesOf(const std::vector<T>& values) {
  return bytesOf(std::span<const T>(values));
}

}  // namespace bounce::gpu
