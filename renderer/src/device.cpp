#include "vt/renderer/device.hpp"

#include <algorithm>
#include <cstring>

#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/renderer/vk_check.hpp"

namespace vt::renderer {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT types,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  const char* text = data && data->pMessage ? data->pMessage : "(no message)";
  // Loader chatter (general, info) is not a validation finding; warnings and errors are counted.
  const bool finding = (types & (VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                 VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT)) &&
                       severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
  if (finding) {
    static_cast<std::atomic<std::uint64_t>*>(user)->fetch_add(1);
    log::error("vulkan validation: ", text);
  } else if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    log::warn("vulkan: ", text);
  } else {
    log::debug("vulkan: ", text);
  }
  return VK_FALSE;
}

bool hasLayer(const char* name) {
  std::uint32_t count = 0;
  VT_VK(vkEnumerateInstanceLayerProperties(&count, nullptr));
  std::vector<VkLayerProperties> layers(count);
  VT_VK(vkEnumerateInstanceLayerProperties(&count, layers.data()));
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
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

int typeScore(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    default: return 1;
  }
}

int graphicsFamily(VkPhysicalDevice physical) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i) {
    if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) return int(i);
  }
  return -1;
}

bool supportsMultiview(VkPhysicalDevice physical) {
  VkPhysicalDeviceMultiviewFeatures multiview{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &multiview;
  vkGetPhysicalDeviceFeatures2(physical, &features);
  return multiview.multiview == VK_TRUE;
}

std::vector<const char*> cStrings(const std::vector<std::string>& strings) {
  std::vector<const char*> out;
  for (const auto& s : strings) out.push_back(s.c_str());
  return out;
}

}  // namespace

std::shared_ptr<Device> Device::create(const DeviceOptions& options) {
  std::shared_ptr<Device> dev(new Device);
  std::vector<std::string> instanceExtensions = options.instanceExtensions;
  std::vector<const char*> layers;
  if (options.validate) {
    if (!hasLayer(kValidationLayer)) {
      fail("vulkan: validation requested but ", kValidationLayer,
           " is not installed (apt-get install vulkan-validationlayers)");
    }
    layers.push_back(kValidationLayer);
    instanceExtensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "vtouching";
  app.pEngineName = "vt::renderer";
  app.apiVersion = VK_API_VERSION_1_1;
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                  VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT |
                                  VK_DEBUG_UTILS_MESSAGE_SEVERITY_INFO_BIT_EXT;
  messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messengerInfo.pfnUserCallback = &onDebugMessage;
  messengerInfo.pUserData = &dev->m_validationMessages;

  const auto extensionPtrs = cStrings(instanceExtensions);
  VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instanceInfo.pNext = options.validate ? &messengerInfo : nullptr;  // also covers create/destroy
  instanceInfo.pApplicationInfo = &app;
  instanceInfo.enabledLayerCount = std::uint32_t(layers.size());
  instanceInfo.ppEnabledLayerNames = layers.data();
  instanceInfo.enabledExtensionCount = std::uint32_t(extensionPtrs.size());
  instanceInfo.ppEnabledExtensionNames = extensionPtrs.data();
  if (options.hooks.createInstance) {
    dev->m_instance = options.hooks.createInstance(instanceInfo);
  } else {
    const VkResult result = vkCreateInstance(&instanceInfo, nullptr, &dev->m_instance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER) {
      fail("vulkan: no Vulkan driver found (install mesa-vulkan-drivers for the lavapipe software device)");
    }
    VT_VK(result);
  }
  if (options.validate) {
    auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(dev->m_instance, "vkCreateDebugUtilsMessengerEXT"));
    if (!createMessenger) fail("vulkan: vkCreateDebugUtilsMessengerEXT is missing");
    VT_VK(createMessenger(dev->m_instance, &messengerInfo, nullptr, &dev->m_messenger));
  }

  if (options.hooks.pickPhysicalDevice) {
    dev->m_physical = options.hooks.pickPhysicalDevice(dev->m_instance);
  } else {
    dev->selectPhysicalDevice(options.preferDiscrete);
  }
  const int family = graphicsFamily(dev->m_physical);
  if (family < 0) fail("vulkan: the chosen device has no graphics queue");
  if (!supportsMultiview(dev->m_physical)) fail("vulkan: the chosen device lacks multiview (Vulkan 1.1)");
  dev->m_queueFamily = std::uint32_t(family);

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = dev->m_queueFamily;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkPhysicalDeviceMultiviewFeatures multiview{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_FEATURES};
  multiview.multiview = VK_TRUE;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &multiview;
  const auto deviceExtensions = cStrings(options.deviceExtensions);
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &features;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.enabledExtensionCount = std::uint32_t(deviceExtensions.size());
  deviceInfo.ppEnabledExtensionNames = deviceExtensions.data();
  if (options.hooks.createDevice) {
    dev->m_device = options.hooks.createDevice(dev->m_physical, deviceInfo);
  } else {
    VT_VK(vkCreateDevice(dev->m_physical, &deviceInfo, nullptr, &dev->m_device));
  }
  vkGetDeviceQueue(dev->m_device, dev->m_queueFamily, 0, &dev->m_queue);
  dev->finishSetup();
  log::info("vulkan device: ", dev->m_description, options.validate ? " (validation on)" : "");
  return dev;
}

std::shared_ptr<Device> Device::adopt(const ExternalDevice& handles) {
  if (!handles.instance || !handles.physicalDevice || !handles.device) fail("vulkan: adopt() needs instance, physical device and device");
  std::shared_ptr<Device> dev(new Device);
  dev->m_owned = false;
  dev->m_instance = handles.instance;
  dev->m_physical = handles.physicalDevice;
  dev->m_device = handles.device;
  dev->m_queueFamily = handles.queueFamily;
  vkGetDeviceQueue(dev->m_device, handles.queueFamily, handles.queueIndex, &dev->m_queue);
  dev->finishSetup();
  log::info("vulkan device (external): ", dev->m_description);
  return dev;
}

void Device::selectPhysicalDevice(bool preferDiscrete) {
  std::uint32_t count = 0;
  VT_VK(vkEnumeratePhysicalDevices(m_instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  VT_VK(vkEnumeratePhysicalDevices(m_instance, &count, devices.data()));
  int bestScore = -1;
  for (VkPhysicalDevice candidate : devices) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(candidate, &props);
    const bool usable = props.apiVersion >= VK_API_VERSION_1_1 && graphicsFamily(candidate) >= 0 &&
                        supportsMultiview(candidate);
    log::debug("vulkan: found ", props.deviceName, " [", typeName(props.deviceType), "]",
               usable ? "" : " (unusable: needs Vulkan 1.1, graphics, multiview)");
    const int score = usable ? (preferDiscrete ? typeScore(props.deviceType) : 1) : -1;
    if (score > bestScore) {
      bestScore = score;
      m_physical = candidate;
    }
  }
  if (bestScore < 0) {
    fail("vulkan: no usable Vulkan device (", count,
         " found; install mesa-vulkan-drivers for lavapipe, check with vulkaninfo --summary)");
  }
}

void Device::finishSetup() {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(m_physical, &props);
  m_software = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  m_description = str(props.deviceName, " [", typeName(props.deviceType), "]");
  m_uniformAlignment = std::max<VkDeviceSize>(props.limits.minUniformBufferOffsetAlignment, 16);
  if (props.apiVersion >= VK_API_VERSION_1_2) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props2.pNext = &driver;
    vkGetPhysicalDeviceProperties2(m_physical, &props2);
    // Measured on Mesa 22.3 lavapipe: with multiview, triangles that need clipping vanish or land
    // wrongly in view 1 (tests/renderer: "multiview and per-view stereo agree").
    m_multiviewReliable = driver.driverID != VK_DRIVER_ID_MESA_LLVMPIPE;
    m_description += str(", ", driver.driverInfo);
  }
  vkGetPhysicalDeviceMemoryProperties(m_physical, &m_memory);
  for (VkFormat format : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D16_UNORM}) {
    VkFormatProperties fp;
    vkGetPhysicalDeviceFormatProperties(m_physical, format, &fp);
    if (fp.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) {
      m_depthFormat = format;
      break;
    }
  }
  if (m_depthFormat == VK_FORMAT_UNDEFINED) fail("vulkan: no depth attachment format on ", m_description);
}

Device::~Device() {
  if (!m_owned) return;
  if (m_device) {
    vkDeviceWaitIdle(m_device);
    vkDestroyDevice(m_device, nullptr);
  }
  if (m_messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(m_instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(m_instance, m_messenger, nullptr);
  }
  if (m_instance) vkDestroyInstance(m_instance, nullptr);
}

std::uint32_t Device::memoryType(std::uint32_t typeBits, VkMemoryPropertyFlags properties) const {
  for (std::uint32_t i = 0; i < m_memory.memoryTypeCount; ++i) {
    if ((typeBits & (1u << i)) && (m_memory.memoryTypes[i].propertyFlags & properties) == properties) return i;
  }
  fail("vulkan: no memory type with properties 0x", std::hex, properties, " on ", m_description);
}

void Device::waitIdle() const { VT_VK(vkDeviceWaitIdle(m_device)); }

}  // namespace vt::renderer
