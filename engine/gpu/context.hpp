#pragma once
// Context: the Vulkan instance, the chosen physical device, the logical device and its one
// graphics+compute queue, plus the memory allocator and a one-shot command pool.
//
// Device choice (first match wins):
//   1. ContextOptions::deviceName, else env BOUNCE_DEVICE: a case-insensitive substring of the
//      device name; no match is an InternalError listing every device and why it is (un)usable;
//   2. otherwise the best usable device: discrete > integrated > virtual > CPU (lavapipe).
// A device is usable when it has Vulkan >= 1.2, one queue family with graphics + compute, and
// dynamic rendering (core in 1.3, VK_KHR_dynamic_rendering in 1.2) — we draw with dynamic
// rendering instead of render-pass objects (see pipeline.hpp).
//
// Validation: on when ContextOptions::validation says so, else when env BOUNCE_VALIDATION=1
// (=0 forces it off), else in debug builds (BOUNCE_DEBUG_BUILD). Asking for it explicitly when
// the layer is not installed is an InternalError; the debug-build default only warns. Every
// validation message of severity ERROR is printed and counted (validationErrorCount()); tests
// fail on any (engine/gpu/testing.hpp).
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "engine/gpu/vk.hpp"

namespace bounce::gpu {

class MemoryAllocator;
class PipelineTable;

struct ContextOptions {
  std::string deviceName;          // substring; empty → env BOUNCE_DEVICE → automatic choice
  std::optional<bool> validation;  // empty → env BOUNCE_VALIDATION → on in debug builds
  // Adds GLFW's required instance extensions and VK_KHR_swapchain. glfwInit() must have
  // succeeded before; headless contexts (the default) need no display at all.
  bool windowed = false;
  std::string appName = "bounce";
  // Keep every pipeline built on this context for its life and hand it again to an identical
  // request (pipeline_table.hpp): a second Session on the context builds none. Empty → env
  // BOUNCE_PIPELINE_REUSE (=0 turns it off) → on.
  std::optional<bool> reusePipelines;
};

// One line per physical device: "'name' [discrete, Vulkan 1.3]" plus " unusable: why" if so.
std::vector<std::string> describeDevices();

// Validation errors counted by every Context of the process since the last reset; the test
// listener reads this so a test fails whichever context produced the error.
std::uint64_t validationErrorsTotal();
void resetValidationErrorsTotal();

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queueFamily() const { return queue_family_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
  const VkPhysicalDeviceFeatures& enabledFeatures() const { return features_; }
  std::uint32_t apiVersion() const { return api_version_; }  // the version the device is used at
  std::string deviceName() const { return properties_.deviceName; }
  bool validationEnabled() const { return validation_; }
  bool debugUtilsEnabled() const { return debug_utils_; }
  bool windowed() const { return windowed_; }
  MemoryAllocator& allocator() { return *allocator_; }
  // Every pipeline of this context is created through it (pipeline.hpp); counts and reuse switch.
  PipelineTable& pipelines() { return *pipelines_; }
  const PipelineTable& pipelines() const { return *pipelines_; }

  // Validation messages of severity ERROR seen by this context's messenger.
  std::uint64_t validationErrorCount() const { return validation_errors_.load(); }
  void resetValidationErrorCount() { validation_errors_ = 0; }

  // Names an object for validation messages, RenderDoc and other tools (no-op without
  // VK_EXT_debug_utils).
  void setName(VkObjectType type, std::uint64_t handle, const std::string& name) const;
  template <class Handle>
  void setName(VkObjectType type, Handle handle, const std::string& name) const {
    setName(type, reinterpret_cast<std::uint64_t>(handle), name);
  }

  // Debug labels around command ranges (no-op without VK_EXT_debug_utils). Prefer ScopedLabel.
  void beginLabel(VkCommandBuffer cmd, const std::string& name, const float color[4] = nullptr) const;
  void endLabel(VkCommandBuffer cmd) const;

  // Dynamic rendering through the core (1.3) or KHR (1.2) entry point.
  void cmdBeginRendering(VkCommandBuffer cmd, const VkRenderingInfo& info) const { begin_rendering_(cmd, &info); }
  void cmdEndRendering(VkCommandBuffer cmd) const { end_rendering_(cmd); }

  // Queue submission is externally synchronised in Vulkan: every submit goes through here.
  void submit(const VkSubmitInfo& info, VkFence fence);
  VkResult present(const VkPresentInfoKHR& info);
  void waitIdle();

  // Pool for one-shot command buffers (submitAndWait); guarded by oneShotMutex().
  VkCommandPool oneShotPool() const { return one_shot_pool_; }
  std::mutex& oneShotMutex() { return one_shot_mutex_; }

 private:
  void createInstance(const ContextOptions& options);
  void pickPhysicalDevice(const ContextOptions& options);
  void createDevice();
  void release();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  std::uint32_t api_version_ = 0;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceFeatures features_{};
  bool validation_ = false;
  bool debug_utils_ = false;
  bool windowed_ = false;
  std::atomic<std::uint64_t> validation_errors_{0};
  std::unique_ptr<MemoryAllocator> allocator_;
  std::unique_ptr<PipelineTable> pipelines_;  // destroyed after vkDeviceWaitIdle, before the device
  VkCommandPool one_shot_pool_ = VK_NULL_HANDLE;
  std::mutex one_shot_mutex_;
  std::mutex queue_mutex_;

  PFN_vkCmdBeginRendering begin_rendering_ = nullptr;
  PFN_vkCmdEndRendering end_rendering_ = nullptr;
  PFN_vkSetDebugUtilsObjectNameEXT set_name_ = nullptr;
  PFN_vkCmdBeginDebugUtilsLabelEXT begin_label_ = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT end_label_ = nullptr;
};

// RAII debug label: `ScopedLabel label(ctx, cmd, "gbuffer");`
class ScopedLabel {
 public:
  ScopedLabel(const Context& ctx, VkCommandBuffer cmd, const std::string& name) : ctx_(ctx), cmd_(cmd) {
    ctx_.beginLabel(cmd_, name);
  }
  ~ScopedLabel() { ctx_.endLabel(cmd_); }
  ScopedLabel(const ScopedLabel&) = delete;
  ScopedLabel& operator=(const ScopedLabel&) = delete;

 private:
  const Context& ctx_;
  VkCommandBuffer cmd_;
};

}  // namespace bounce::gpu
