#include "engine/gpu/context.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/gpu/memory.hpp"
#include "engine/gpu/pipeline_table.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace bounce::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
std::atomic<std::uint64_t> g_validation_errors{0};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string versionString(std::uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v));
}

const char* typeName(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

int typeScore(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
  std::uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
  for (auto& e : exts)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

struct Candidate {
  VkPhysicalDevice device;
  VkPhysicalDeviceProperties props;
  std::uint32_t family = 0;
  std::string unusable;  // empty when usable
};

// Why `pd` cannot run Bounce (empty when it can); also finds its graphics+compute family.
Candidate examine(VkPhysicalDevice pd, bool windowed) {
  Candidate c{pd, {}, 0, {}};
  vkGetPhysicalDeviceProperties(pd, &c.props);
  if (c.props.apiVersion < VK_API_VERSION_1_2) {
    c.unusable = "needs Vulkan 1.2";
    return c;
  }
  std::uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
  std::vector<VkQueueFamilyProperties> fams(n);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, fams.data());
  bool found = false;
  for (std::uint32_t i = 0; i < n && !found; ++i) {
    VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if ((fams[i].queueFlags & need) == need) {
      c.family = i;
      found = true;
    }
  }
  if (!found) {
    c.unusable = "no graphics+compute queue family";
    return c;
  }
  if (c.props.apiVersion < VK_API_VERSION_1_3 && !hasDeviceExtension(pd, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME)) {
    c.unusable = "no dynamic rendering";
    return c;
  }
  if (windowed && !hasDeviceExtension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME)) c.unusable = "no VK_KHR_swapchain";
  return c;
}

std::string describe(const Candidate& c) {
  std::string s = std::string("'") + c.props.deviceName + "' [" + typeName(c.props.deviceType) + ", Vulkan " +
                  versionString(c.props.apiVersion) + "]";
  if (!c.unusable.empty()) s += " unusable: " + c.unusable;
  return s;
}

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  std::string msg = std::string("vulkan: ") + (data && data->pMessage ? data->pMessage : "(no message)");
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    if (user) ++*static_cast<std::atomic<std::uint64_t>*>(user);
    ++g_validation_errors;
    log::error(msg);
  } else {
    log::warn(msg);
  }
  return VK_FALSE;  // never abort the call: the count decides
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(std::atomic<std::uint64_t>* counter) {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                     VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = onDebugMessage;
  info.pUserData = counter;
  return info;
}

std::optional<bool> envFlag(const char* name) {
  const char* v = std::getenv(name);
  if (!v || !*v) return std::nullopt;
  return std::string(v) != "0";
}

}  // namespace

std::uint64_t validationErrorsTotal() { return g_validation_errors.load(); }
void resetValidationErrorsTotal() { g_validation_errors = 0; }

std::vector<std::string> describeDevices() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  VkInstance inst = VK_NULL_HANDLE;
  check(vkCreateInstance(&ci, nullptr, &inst), "vkCreateInstance");
  std::uint32_t n = 0;
  vkEnumeratePhysicalDevices(inst, &n, nullptr);
  std::vector<VkPhysicalDevice> pds(n);
  vkEnumeratePhysicalDevices(inst, &n, pds.data());
  std::vector<std::string> out;
  for (auto pd : pds) out.push_back(describe(examine(pd, false)));
  vkDestroyInstance(inst, nullptr);
  return out;
}

Context::Context(const ContextOptions& options) : windowed_(options.windowed) {
  try {
    createInstance(options);
    pickPhysicalDevice(options);
    createDevice();
    const std::optional<bool> reuse =
        options.reusePipelines ? options.reusePipelines : envFlag("BOUNCE_PIPELINE_REUSE");
    pipelines_ = std::make_unique<PipelineTable>(*this, reuse.value_or(true));
  } catch (...) {
    release();  // a constructor that throws runs no destructor: free what exists
    throw;
  }
}

void Context::createInstance(const ContextOptions& options) {
  std::uint32_t instanceVersion = VK_API_VERSION_1_0;
  vkEnumerateInstanceVersion(&instanceVersion);
  if (instanceVersion < VK_API_VERSION_1_2)
    throw InternalError("vulkan: the Vulkan loader is version " + versionString(instanceVersion) + "; Bounce needs 1.2");
  // 1.3 when the loader has it; each device is then used at min(its version, 1.3).
  std::uint32_t apiVersion = std::min<std::uint32_t>(instanceVersion, VK_API_VERSION_1_3);

  std::uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  bool haveValidation = std::any_of(layers.begin(), layers.end(),
                                    [](auto& l) { return std::strcmp(l.layerName, kValidationLayer) == 0; });
  n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, exts.data());
  auto haveExt = [&](const char* name) {
    return std::any_of(exts.begin(), exts.end(), [&](auto& e) { return std::strcmp(e.extensionName, name) == 0; });
  };

  std::optional<bool> wanted = options.validation ? options.validation : envFlag("BOUNCE_VALIDATION");
#ifdef BOUNCE_DEBUG_BUILD
  bool byDefault = true;
#else
  bool byDefault = false;
#endif
  validation_ = wanted.value_or(byDefault);
  if (validation_ && !haveValidation) {
    if (wanted)
      throw InternalError(std::string("vulkan: validation was requested but the layer ") + kValidationLayer +
                          " is not installed (Debian package vulkan-validationlayers)");
    log::warn(std::string("vulkan: ") + kValidationLayer + " is not installed; running without validation");
    validation_ = false;
  }

  std::vector<const char*> extensions;
  debug_utils_ = haveExt(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debug_utils_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (windowed_) {
    std::uint32_t count = 0;
    const char** glfwExts = glfwGetRequiredInstanceExtensions(&count);
    if (!glfwExts)
      throw InternalError("vulkan: GLFW reports no Vulkan surface support (was glfwInit() called? is there a display?)");
    for (std::uint32_t i = 0; i < count; ++i) extensions.push_back(glfwExts[i]);
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = options.appName.c_str();
  app.pEngineName = "bounce";
  app.apiVersion = apiVersion;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  ci.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  // Chained messenger: also reports errors inside vkCreateInstance / vkDestroyInstance.
  VkDebugUtilsMessengerCreateInfoEXT mi = messengerInfo(&validation_errors_);
  if (validation_) {
    ci.enabledLayerCount = 1;
    ci.ppEnabledLayerNames = &kValidationLayer;
    if (debug_utils_) ci.pNext = &mi;
  }
  check(vkCreateInstance(&ci, nullptr, &instance_), "vkCreateInstance");
  api_version_ = apiVersion;

  if (validation_ && debug_utils_) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create) check(create(instance_, &mi, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }
  if (debug_utils_) {
    set_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
    begin_label_ = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
    end_label_ = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
  }
}

void Context::pickPhysicalDevice(const ContextOptions& options) {
  std::uint32_t n = 0;
  vkEnumeratePhysicalDevices(instance_, &n, nullptr);
  std::vector<VkPhysicalDevice> pds(n);
  vkEnumeratePhysicalDevices(instance_, &n, pds.data());
  std::vector<Candidate> cands;
  for (auto pd : pds) cands.push_back(examine(pd, windowed_));
  auto listing = [&] {
    std::string s;
    for (auto& c : cands) s += (s.empty() ? "" : ", ") + describe(c);
    return s.empty() ? std::string("none") : s;
  };

  std::string wanted = options.deviceName;
  std::string source = "--device";
  if (wanted.empty()) {
    if (const char* env = std::getenv("BOUNCE_DEVICE")) wanted = env;
    source = "BOUNCE_DEVICE";
  }
  const Candidate* chosen = nullptr;
  if (!wanted.empty()) {
    for (auto& c : cands)
      if (lower(c.props.deviceName).find(lower(wanted)) != std::string::npos) {
        if (!c.unusable.empty())
          throw InternalError("vulkan: device " + describe(c) + " matches " + source + " '" + wanted + "'");
        chosen = &c;
        break;
      }
    if (!chosen)  // the user named it: bad input (exit 2), not an internal error
      throwInputError("vulkan", source, "no Vulkan device matches " + source + " '" + wanted + "'",
                      "a substring of a device name; available: " + listing());
  } else {
    for (auto& c : cands)
      if (c.unusable.empty() && (!chosen || typeScore(c.props.deviceType) > typeScore(chosen->props.deviceType)))
        chosen = &c;
    if (!chosen) throw InternalError("vulkan: no usable Vulkan device (found: " + listing() + ")");
  }
  physical_ = chosen->device;
  properties_ = chosen->props;
  queue_family_ = chosen->family;
  api_version_ = std::min(api_version_, properties_.apiVersion);
}

void Context::createDevice() {
  bool core13 = api_version_ >= VK_API_VERSION_1_3;
  // Query what the device has, then enable only what we use and it supports.
  VkPhysicalDeviceVulkan13Features have13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features have12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceDynamicRenderingFeatures haveDr{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
  VkPhysicalDeviceFeatures2 have{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  have.pNext = &have12;
  have12.pNext = core13 ? static_cast<void*>(&have13) : static_cast<void*>(&haveDr);
  vkGetPhysicalDeviceFeatures2(physical_, &have);
  if (!(core13 ? have13.dynamicRendering : haveDr.dynamicRendering))
    throw InternalError("vulkan: device '" + deviceName() + "' lacks the dynamicRendering feature");
  // The render graph puts depth-only images in DEPTH_ATTACHMENT_OPTIMAL / DEPTH_READ_ONLY_OPTIMAL
  // (render/vk_backend.cpp, render/passes/rendering.cpp: the passes that test against the G-buffer's
  // depth without writing it, dnrt's box among them), which Vulkan 1.2 allows only with this feature
  // enabled. Every 1.2 desktop driver and lavapipe have it; without it we stop here rather than run
  // on layouts the driver may not honour.
  if (!have12.separateDepthStencilLayouts)
    throw InternalError("vulkan: device '" + deviceName() + "' lacks the separateDepthStencilLayouts feature");

  VkPhysicalDeviceFeatures& f = features_;
  const VkPhysicalDeviceFeatures& h = have.features;
  f.samplerAnisotropy = h.samplerAnisotropy;
  f.fillModeNonSolid = h.fillModeNonSolid;
  f.independentBlend = h.independentBlend;
  f.imageCubeArray = h.imageCubeArray;
  f.geometryShader = h.geometryShader;
  f.multiDrawIndirect = h.multiDrawIndirect;
  f.drawIndirectFirstInstance = h.drawIndirectFirstInstance;
  f.fragmentStoresAndAtomics = h.fragmentStoresAndAtomics;
  f.vertexPipelineStoresAndAtomics = h.vertexPipelineStoresAndAtomics;
  f.shaderStorageImageWriteWithoutFormat = h.shaderStorageImageWriteWithoutFormat;
  f.shaderStorageImageReadWithoutFormat = h.shaderStorageImageReadWithoutFormat;
  f.depthClamp = h.depthClamp;
  f.shaderFloat64 = h.shaderFloat64;

  VkPhysicalDeviceVulkan13Features en13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features en12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceDynamicRenderingFeatures enDr{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
  VkPhysicalDeviceFeatures2 en{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  en.features = features_;
  en.pNext = &en12;
  en12.scalarBlockLayout = have12.scalarBlockLayout;
  en12.hostQueryReset = have12.hostQueryReset;
  en12.timelineSemaphore = have12.timelineSemaphore;
  en12.storageBuffer8BitAccess = have12.storageBuffer8BitAccess;
  en12.shaderFloat16 = have12.shaderFloat16;
  en12.separateDepthStencilLayouts = VK_TRUE;  // checked above
  if (core13) {
    en12.pNext = &en13;
    en13.dynamicRendering = VK_TRUE;
    en13.synchronization2 = have13.synchronization2;
    // SPIR-V built for Vulkan 1.2 (shaders/CMakeLists.txt) on a 1.3 device: maintenance4 keeps
    // the validation layer from flagging LocalSizeId-era rules (DESIGN.md "Machine facts").
    en13.maintenance4 = have13.maintenance4;
  } else {
    en12.pNext = &enDr;
    enDr.dynamicRendering = VK_TRUE;
  }

  std::vector<const char*> extensions;
  if (!core13) extensions.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
  if (windowed_) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qi.queueFamilyIndex = queue_family_;
  qi.queueCount = 1;
  qi.pQueuePriorities = &priority;
  VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  ci.pNext = &en;
  ci.queueCreateInfoCount = 1;
  ci.pQueueCreateInfos = &qi;
  ci.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  check(vkCreateDevice(physical_, &ci, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

  const char* beginName = core13 ? "vkCmdBeginRendering" : "vkCmdBeginRenderingKHR";
  const char* endName = core13 ? "vkCmdEndRendering" : "vkCmdEndRenderingKHR";
  begin_rendering_ = reinterpret_cast<PFN_vkCmdBeginRendering>(vkGetDeviceProcAddr(device_, beginName));
  end_rendering_ = reinterpret_cast<PFN_vkCmdEndRendering>(vkGetDeviceProcAddr(device_, endName));
  if (!begin_rendering_ || !end_rendering_) throw InternalError("vulkan: dynamic rendering entry points missing");

  allocator_ = std::make_unique<MemoryAllocator>(*this);

  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pi.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pi.queueFamilyIndex = queue_family_;
  check(vkCreateCommandPool(device_, &pi, nullptr, &one_shot_pool_), "vkCreateCommandPool");
  setName(VK_OBJECT_TYPE_COMMAND_POOL, one_shot_pool_, "one-shot pool");
  log::debug("vulkan: using " + deviceName() + " (Vulkan " + versionString(api_version_) + ")" +
             (validation_ ? " with validation" : ""));
}

Context::~Context() { release(); }

void Context::release() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    pipelines_.reset();  // its pipelines, then their layouts: nothing the device still runs
    if (one_shot_pool_) vkDestroyCommandPool(device_, one_shot_pool_, nullptr);
    one_shot_pool_ = VK_NULL_HANDLE;
    allocator_.reset();
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
  instance_ = VK_NULL_HANDLE;
}

void Context::setName(VkObjectType type, std::uint64_t handle, const std::string& name) const {
  if (!set_name_ || !handle || name.empty()) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  set_name_(device_, &info);
}

void Context::beginLabel(VkCommandBuffer cmd, const std::string& name, const float color[4]) const {
  if (!begin_label_) return;
  VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  label.pLabelName = name.c_str();
  if (color) std::memcpy(label.color, color, sizeof(label.color));
  begin_label_(cmd, &label);
}

void Context::endLabel(VkCommandBuffer cmd) const {
  if (end_label_) end_label_(cmd);
}

void Context::submit(const VkSubmitInfo& info, VkFence fence) {
  std::lock_guard lock(queue_mutex_);
  check(vkQueueSubmit(queue_, 1, &info, fence), "vkQueueSubmit");
}

VkResult Context::present(const VkPresentInfoKHR& info) {
  std::lock_guard lock(queue_mutex_);
  return vkQueuePresentKHR(queue_, &info);
}

void Context::waitIdle() {
  std::lock_guard lock(queue_mutex_);
  check(vkDeviceWaitIdle(device_), "vkDeviceWaitIdle");
}

}  // namespace bounce::gpu
