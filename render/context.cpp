#include "render/context.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "render/vk_check.h"

namespace vegstream::render {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

const char* typeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

// Higher is preferred: a hardware GPU over a software rasteriser.
int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

std::string versionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

DeviceInfo describe(VkPhysicalDevice pd, int index) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
  vkGetPhysicalDeviceProperties2(pd, &props);
  const VkPhysicalDeviceProperties& p = props.properties;
  DeviceInfo info;
  info.index = index;
  info.name = p.deviceName;
  info.type = typeName(p.deviceType);
  info.driver = std::string(driver.driverName) + ": " + driver.driverInfo;
  info.apiVersion = versionString(p.apiVersion);
  info.software = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  const VkSampleCountFlags counts = p.limits.framebufferColorSampleCounts & p.limits.framebufferDepthSampleCounts;
  for (int s : {1, 2, 4, 8, 16})
    if (counts & static_cast<VkSampleCountFlags>(s)) info.msaaCounts.push_back(s);
  VkPhysicalDeviceFeatures features{};
  vkGetPhysicalDeviceFeatures(pd, &features);
  VkFormatProperties colour{};  // the colour target's storage view and the visibility target
  vkGetPhysicalDeviceFormatProperties(pd, VK_FORMAT_R8G8B8A8_UNORM, &colour);
  const bool storable = (colour.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) &&
                        (colour.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT);
  const VkSampleCountFlags storageCounts = features.shaderStorageImageMultisample
                                               ? (p.limits.storageImageSampleCounts & counts)
                                               : VkSampleCountFlags{VK_SAMPLE_COUNT_1_BIT};
  for (int s : {1, 2, 4, 8})  // the shade shader handles up to 8 samples
    if (storable && (storageCounts & static_cast<VkSampleCountFlags>(s))) info.storageMsaaCounts.push_back(s);
  info.sampleRateShading = features.sampleRateShading == VK_TRUE;
  info.multiDrawIndirect = features.multiDrawIndirect == VK_TRUE && features.drawIndirectFirstInstance == VK_TRUE;
  VkPhysicalDeviceMemoryProperties memory{};
  vkGetPhysicalDeviceMemoryProperties(pd, &memory);
  for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
    if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      info.deviceLocalBytes = std::max<uint64_t>(info.deviceLocalBytes, memory.memoryHeaps[h].size);
  return info;
}

bool hasQueueFamily(VkPhysicalDevice pd, uint32_t* family) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
  for (uint32_t i = 0; i < n; ++i) {
    if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) &&
        families[i].timestampValidBits > 0) {
      *family = i;
      return true;
    }
  }
  return false;
}

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* log = static_cast<ValidationLog*>(user);
  const bool isError = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  if (log && severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT)
    log->report(data->pMessage ? data->pMessage : "(no message)", isError);
  return VK_FALSE;
}

bool layerAvailable(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

// An instance just for enumeration, destroyed on scope exit.
struct ScratchInstance {
  VkInstance instance = VK_NULL_HANDLE;
  ~ScratchInstance() {
    if (instance) vkDestroyInstance(instance, nullptr);
  }
};

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t n = 0;
  vkCheck(vkEnumeratePhysicalDevices(instance, &n, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(n);
  vkCheck(vkEnumeratePhysicalDevices(instance, &n, devices.data()), "vkEnumeratePhysicalDevices");
  return devices;
}

}  // namespace

Result<std::vector<DeviceInfo>> listDevices() {
  return guardGpu([&]() -> Result<std::vector<DeviceInfo>> {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    ScratchInstance scratch;
    vkCheck(vkCreateInstance(&ci, nullptr, &scratch.instance), "vkCreateInstance");
    std::vector<DeviceInfo> out;
    int i = 0;
    for (VkPhysicalDevice pd : physicalDevices(scratch.instance)) out.push_back(describe(pd, i++));
    return out;
  });
}

Result<std::unique_ptr<Context>> Context::create(const ContextOptions& options) {
  std::unique_ptr<Context> ctx(new Context());
  try {
    ctx->init(options);
  } catch (const VulkanError& e) {
    return makeError(ErrorKind::Gpu, e.what());
  } catch (const std::invalid_argument& e) {
    return makeError(ErrorKind::NotFound, e.what());
  } catch (const std::domain_error& e) {
    return makeError(ErrorKind::Unsupported, e.what());
  } catch (const std::runtime_error& e) {  // no usable device: the system's, not the user's
    return makeError(ErrorKind::Gpu, e.what());
  }
  return ctx;
}

void Context::init(const ContextOptions& options) {
  logger_ = options.logger ? options.logger : makeNullLogger();
  validationLog_ = options.validationLog;
  createInstance(options);
  choosePhysicalDevice(options);
  createDevice(options);
}

// The instance, with the validation layer and its messenger when asked for.
void Context::createInstance(const ContextOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "vegstream";
  app.pEngineName = "vegstream";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> extensions;
  for (const auto& e : options.instanceExtensions) extensions.push_back(e.c_str());
  extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);  // object names, even without validation
  std::vector<const char*> layers;
  if (options.validate) {
    if (!layerAvailable(kValidationLayer))
      throw std::domain_error("--validate needs the Vulkan validation layers (Debian package vulkan-validationlayers)");
    layers.push_back(kValidationLayer);
  }

  VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  mci.pfnUserCallback = onDebugMessage;
  mci.pUserData = validationLog_.get();

  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  ici.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  ici.ppEnabledExtensionNames = extensions.data();
  ici.enabledLayerCount = static_cast<uint32_t>(layers.size());
  ici.ppEnabledLayerNames = layers.data();
  if (options.validate) ici.pNext = &mci;  // also catches messages from instance creation
  vkCheck(vkCreateInstance(&ici, nullptr, &instance_), "vkCreateInstance");

  if (options.validate) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    vkCheck(create(instance_, &mci, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }
  setObjectName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
      vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
}

// The physical device: the first usable one whose name contains --device, else the best by type.
void Context::choosePhysicalDevice(const ContextOptions& options) {
  const auto devices = physicalDevices(instance_);
  std::vector<DeviceInfo> infos;
  int best = -1, bestRank = -1;
  for (size_t i = 0; i < devices.size(); ++i) {
    infos.push_back(describe(devices[i], static_cast<int>(i)));
    uint32_t family = 0;
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(devices[i], &p);
    const bool usable = p.apiVersion >= VK_API_VERSION_1_3 && hasQueueFamily(devices[i], &family);
    if (!usable) continue;
    if (!options.deviceName.empty()) {
      if (lower(infos.back().name).find(lower(options.deviceName)) != std::string::npos && best < 0)
        best = static_cast<int>(i);
    } else if (typeRank(p.deviceType) > bestRank) {
      bestRank = typeRank(p.deviceType);
      best = static_cast<int>(i);
    }
  }
  if (best < 0) {
    std::string available;
    for (const auto& d : infos) available += (available.empty() ? "" : ", ") + ("\"" + d.name + "\"");
    if (available.empty()) available = "none";
    if (!options.deviceName.empty())
      throw std::invalid_argument("no Vulkan 1.3 device matches --device \"" + options.deviceName +
                                  "\"; available: " + available);
    throw std::runtime_error("no Vulkan 1.3 device with a graphics queue; devices found: " + available);
  }
  physical_ = devices[static_cast<size_t>(best)];
  info_ = infos[static_cast<size_t>(best)];
  hasQueueFamily(physical_, &queueFamily_);
  vkGetPhysicalDeviceProperties(physical_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
}

// The logical device: Vulkan 1.3 dynamic rendering and synchronization2, plus the optional
// features later passes use (tessellation, geometry, pipeline statistics) where offered.
void Context::createDevice(const ContextOptions& options) {
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(physical_, &supported);
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.dynamicRendering = VK_TRUE;
  f13.synchronization2 = VK_TRUE;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
  f12.hostQueryReset = VK_TRUE;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f12};
  features.features.pipelineStatisticsQuery = supported.pipelineStatisticsQuery;
  features.features.tessellationShader = supported.tessellationShader;
  features.features.geometryShader = supported.geometryShader;
  features.features.sampleRateShading = supported.sampleRateShading;
  features.features.fillModeNonSolid = supported.fillModeNonSolid;
  features.features.shaderStorageImageMultisample = supported.shaderStorageImageMultisample;
  features.features.multiDrawIndirect = supported.multiDrawIndirect;
  features.features.drawIndirectFirstInstance = supported.drawIndirectFirstInstance;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  std::vector<const char*> deviceExtensions;
  if (options.wantSwapchain) deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = static_cast<uint32_t>(deviceExtensions.size());
  dci.ppEnabledExtensionNames = deviceExtensions.data();
  vkCheck(vkCreateDevice(physical_, &dci, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
  setName(VK_OBJECT_TYPE_DEVICE, device_, "vegstream device");
  setName(VK_OBJECT_TYPE_QUEUE, queue_, "graphics queue");

  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pci.queueFamilyIndex = queueFamily_;
  VkCommandPool pool;
  vkCheck(vkCreateCommandPool(device_, &pci, nullptr, &pool), "vkCreateCommandPool");
  uploadPool_ = CommandPool(device_, pool);
  setName(VK_OBJECT_TYPE_COMMAND_POOL, pool, "one-off command pool");
  logger_->debug("GPU: {} ({}, {}, Vulkan {})", info_.name, info_.type, info_.driver, info_.apiVersion);
}

Context::~Context() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    uploadPool_.reset();
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

uint32_t Context::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & required) == required) return i;
  throw VulkanError(VK_ERROR_OUT_OF_DEVICE_MEMORY, "finding a memory type");
}

void Context::setName(VkObjectType type, uint64_t handle, const std::string& name) const {
  if (!setObjectName_ || handle == 0) return;
  VkDebugUtilsObjectNameInfoEXT ni{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  ni.objectType = type;
  ni.objectHandle = handle;
  ni.pObjectName = name.c_str();
  vkCheck(setObjectName_(device_, &ni), "vkSetDebugUtilsObjectNameEXT");
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = uploadPool_.get();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  vkCheck(vkAllocateCommandBuffers(device_, &ai, &cmd), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkCheck(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  record(cmd);
  vkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence rawFence;
  vkCheck(vkCreateFence(device_, &fci, nullptr, &rawFence), "vkCreateFence");
  Fence fence(device_, rawFence);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  vkCheck(vkQueueSubmit(queue_, 1, &si, rawFence), "vkQueueSubmit");
  vkCheck(vkWaitForFences(device_, 1, &rawFence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  vkFreeCommandBuffers(device_, uploadPool_.get(), 1, &cmd);
}

}  // namespace vegstream::render
