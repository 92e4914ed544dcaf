// Headset creation: instance, system, the runtime-created Vulkan device, session, swapchains,
// input; and the fallback classification when any of it is absent.
#include <algorithm>
#include <cstdlib>
#include <cstdio>
#include <cstring>

#include "headset_impl.hpp"
#include "vt/core/log.hpp"

namespace vt::xr {
namespace {

template <class Fn>
Fn instanceFunction(XrInstance instance, const char* name) {
  PFN_xrVoidFunction fn = nullptr;
  xrCheck(xrGetInstanceProcAddr(instance, name, &fn), name);
  return reinterpret_cast<Fn>(fn);
}

bool hasExtension(const char* name) {
  std::uint32_t count = 0;
  if (XR_FAILED(xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr))) return false;
  std::vector<XrExtensionProperties> props(count, {XR_TYPE_EXTENSION_PROPERTIES});
  if (XR_FAILED(xrEnumerateInstanceExtensionProperties(nullptr, count, &count, props.data()))) return false;
  return std::any_of(props.begin(), props.end(), [&](const auto& p) { return std::strcmp(p.extensionName, name) == 0; });
}

// The renderer fills the Vulkan create infos; the runtime performs the calls (enable2).
renderer::DeviceCreationHooks vulkanHooks(XrInstance instance, XrSystemId system) {
  auto createInstance = instanceFunction<PFN_xrCreateVulkanInstanceKHR>(instance, "xrCreateVulkanInstanceKHR");
  auto getDevice = instanceFunction<PFN_xrGetVulkanGraphicsDevice2KHR>(instance, "xrGetVulkanGraphicsDevice2KHR");
  auto createDevice = instanceFunction<PFN_xrCreateVulkanDeviceKHR>(instance, "xrCreateVulkanDeviceKHR");
  renderer::DeviceCreationHooks hooks;
  hooks.createInstance = [=](const VkInstanceCreateInfo& info) {
    XrVulkanInstanceCreateInfoKHR create{XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR};
    create.systemId = system;
    create.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    create.vulkanCreateInfo = &info;
    VkInstance vkInstance = VK_NULL_HANDLE;
    VkResult vkResult = VK_SUCCESS;
    VT_XR_CHECK(createInstance(instance, &create, &vkInstance, &vkResult));
    if (vkResult != VK_SUCCESS) fail("OpenXR: xrCreateVulkanInstanceKHR: vkCreateInstance returned ", int(vkResult));
    return vkInstance;
  };
  hooks.pickPhysicalDevice = [=](VkInstance vkInstance) {
    XrVulkanGraphicsDeviceGetInfoKHR get{XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR};
    get.systemId = system;
    get.vulkanInstance = vkInstance;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VT_XR_CHECK(getDevice(instance, &get, &physical));
    return physical;
  };
  hooks.createDevice = [=](VkPhysicalDevice physical, const VkDeviceCreateInfo& info) {
    XrVulkanDeviceCreateInfoKHR create{XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR};
    create.systemId = system;
    create.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    create.vulkanPhysicalDevice = physical;
    create.vulkanCreateInfo = &info;
    VkDevice device = VK_NULL_HANDLE;
    VkResult vkResult = VK_SUCCESS;
    VT_XR_CHECK(createDevice(instance, &create, &device, &vkResult));
    if (vkResult != VK_SUCCESS) fail("OpenXR: xrCreateVulkanDeviceKHR: vkCreateDevice returned ", int(vkResult));
    return device;
  };
  return hooks;
}

// The runtime's swapchain formats, in its order of preference.
std::vector<std::int64_t> swapchainFormats(XrSession session) {
  std::uint32_t count = 0;
  VT_XR_CHECK(xrEnumerateSwapchainFormats(session, 0, &count, nullptr));
  std::vector<std::int64_t> formats(count);
  VT_XR_CHECK(xrEnumerateSwapchainFormats(session, count, &count, formats.data()));
  return formats;
}

// First format of the runtime's (preference-ordered) list that is sRGB; else the first 8-bit one.
VkFormat chooseColorFormat(const std::vector<std::int64_t>& formats) {
  for (std::int64_t f : formats)
    if (f == VK_FORMAT_R8G8B8A8_SRGB || f == VK_FORMAT_B8G8R8A8_SRGB) return VkFormat(f);
  for (std::int64_t f : formats)
    if (f == VK_FORMAT_R8G8B8A8_UNORM || f == VK_FORMAT_B8G8R8A8_UNORM) return VkFormat(f);
  fail("OpenXR: the runtime offers no 8-bit RGBA/BGRA swapchain format");
}

// First format of the runtime's list that the renderer can draw depth into; UNDEFINED = none.
VkFormat chooseDepthFormat(const std::vector<std::int64_t>& formats, const renderer::Device& device) {
  for (std::int64_t f : formats)
    if (renderer::supportsExternalDepth(device, VkFormat(f))) return VkFormat(f);
  return VK_FORMAT_UNDEFINED;
}

// A swapchain of one eye's size and its Vulkan images.
XrSwapchain createSwapchain(XrSession session, XrSwapchainCreateInfo info, std::vector<VkImage>& images) {
  XrSwapchain handle = XR_NULL_HANDLE;
  VT_XR_CHECK(xrCreateSwapchain(session, &info, &handle));
  std::uint32_t imageCount = 0;
  VT_XR_CHECK(xrEnumerateSwapchainImages(handle, 0, &imageCount, nullptr));
  std::vector<XrSwapchainImageVulkan2KHR> xrImages(imageCount, {XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR});
  VT_XR_CHECK(xrEnumerateSwapchainImages(handle, imageCount, &imageCount,
                                         reinterpret_cast<XrSwapchainImageBaseHeader*>(xrImages.data())));
  for (const auto& image : xrImages) images.push_back(image.image);
  return handle;
}

void createEyes(Headset::Impl& h) {
  std::uint32_t count = 0;
  VT_XR_CHECK(xrEnumerateViewConfigurationViews(h.instance, h.system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 0, &count, nullptr));
  std::vector<XrViewConfigurationView> views(count, {XR_TYPE_VIEW_CONFIGURATION_VIEW});
  VT_XR_CHECK(xrEnumerateViewConfigurationViews(h.instance, h.system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, count, &count, views.data()));
  if (count != 2) fail("OpenXR: stereo view configuration has ", count, " views (expected 2)");
  const std::vector<std::int64_t> formats = swapchainFormats(h.session);
  const VkFormat format = chooseColorFormat(formats);
  if (h.depthOffered) {
    h.depthFormat = chooseDepthFormat(formats, *h.device);
    if (h.depthFormat == VK_FORMAT_UNDEFINED)
      vt::log::warn("OpenXR: ", h.runtimeName, " offers no depth swapchain format the renderer can use; no depth layers");
  }
  for (std::size_t eye = 0; eye < 2; ++eye) {
    XrSwapchainCreateInfo info{XR_TYPE_SWAPCHAIN_CREATE_INFO};
    info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT | XR_SWAPCHAIN_USAGE_SAMPLED_BIT | XR_SWAPCHAIN_USAGE_TRANSFER_SRC_BIT;
    info.format = format;
    info.sampleCount = 1;
    info.width = views[eye].recommendedImageRectWidth;
    info.height = views[eye].recommendedImageRectHeight;
    info.faceCount = 1;
    info.arraySize = 1;
    info.mipCount = 1;
    EyeSwapchain& out = h.eyes[eye];
    renderer::ExternalImages desc;
    out.handle = createSwapchain(h.session, info, desc.images);
    if (h.depthFormat != VK_FORMAT_UNDEFINED) {
      // The compositor reprojects with it; the renderer draws and stores it (ExternalImages).
      XrSwapchainCreateInfo depthInfo = info;
      depthInfo.usageFlags = XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
      depthInfo.format = h.depthFormat;
      out.depthHandle = createSwapchain(h.session, depthInfo, desc.depthImages);
      desc.depthFormat = h.depthFormat;
    }
    desc.format = format;
    desc.extent = {info.width, info.height};
    desc.layers = 1;
    desc.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;  // what OpenXR expects at release
    out.target = std::make_unique<renderer::ExternalTarget>(h.device, desc);
    out.extent = {std::int32_t(info.width), std::int32_t(info.height)};
  }
}

XrSpace createAppSpace(Headset::Impl& h) {
  std::uint32_t count = 0;
  VT_XR_CHECK(xrEnumerateReferenceSpaces(h.session, 0, &count, nullptr));
  std::vector<XrReferenceSpaceType> types(count);
  VT_XR_CHECK(xrEnumerateReferenceSpaces(h.session, count, &count, types.data()));
  const bool stage = std::find(types.begin(), types.end(), XR_REFERENCE_SPACE_TYPE_STAGE) != types.end();
  XrReferenceSpaceCreateInfo info{XR_TYPE_REFERENCE_SPACE_CREATE_INFO};
  info.referenceSpaceType = stage ? XR_REFERENCE_SPACE_TYPE_STAGE : XR_REFERENCE_SPACE_TYPE_LOCAL;
  info.poseInReferenceSpace.orientation.w = 1.0f;
  XrSpace space = XR_NULL_HANDLE;
  VT_XR_CHECK(xrCreateReferenceSpace(h.session, &info, &space));
  info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_VIEW;
  VT_XR_CHECK(xrCreateReferenceSpace(h.session, &info, &h.viewSpace));
  h.stage = stage;
  // Until the head is located (or always without placeAtHead). LOCAL's origin is at head
  // height: lower the scene so the table stays at table height.
  h.T_world_app = glm::inverse(h.options.T_stage_world);
  if (!stage) h.T_world_app[3].y += 1.6f;  // approximate eye height above the floor
  return space;
}

}  // namespace

const char* describe(Unavailable reason) noexcept {
  switch (reason) {
    case Unavailable::None: return "headset available";
    case Unavailable::NoRuntime: return "no OpenXR runtime";
    case Unavailable::NoHmd: return "no headset (HMD) connected";
    case Unavailable::SessionRefused: return "the OpenXR runtime refused the session";
  }
  return "unknown";
}

Headset::Headset(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
Headset::~Headset() = default;

void Headset::Impl::destroySession() noexcept {
  if (device) device->waitIdle();
  input.reset();
  for (auto& eye : eyes) {
    eye.target.reset();
    if (eye.handle != XR_NULL_HANDLE) xrDestroySwapchain(eye.handle);
    if (eye.depthHandle != XR_NULL_HANDLE) xrDestroySwapchain(eye.depthHandle);
    eye.handle = XR_NULL_HANDLE;
    eye.depthHandle = XR_NULL_HANDLE;
  }
  if (appSpace != XR_NULL_HANDLE) xrDestroySpace(appSpace);
  if (viewSpace != XR_NULL_HANDLE) xrDestroySpace(viewSpace);
  appSpace = viewSpace = XR_NULL_HANDLE;
  if (session != XR_NULL_HANDLE) xrDestroySession(session);
  session = XR_NULL_HANDLE;
}

Headset::Impl::~Impl() {
  destroySession();
  // The Vulkan device goes when its last user (the app's renderer) lets go; the XR instance
  // may go first: enable2 makes the application the owner of the Vulkan objects.
  if (instance != XR_NULL_HANDLE) xrDestroyInstance(instance);
}

Headset::OpenResult Headset::open(const HeadsetOptions& options) {
  OpenResult result;
  auto h = std::make_unique<Impl>();
  h->options = options;
  auto unavailable = [&](Unavailable reason, const std::string& detail) {
    result.reason = reason;
    result.message = str("headset mode unavailable: ", describe(reason), " (", detail, ")");
    return std::move(result);
  };

  // The loader prints its own error lines for a missing runtime; the fallback line below says
  // it once. XR_LOADER_DEBUG set by the user (e.g. "error") keeps the loader's diagnostics.
  setenv("XR_LOADER_DEBUG", "none", 0);

  // 1. Instance: no runtime installed, an unreadable manifest or a broken runtime all land here.
  const bool handTrackingOffered = hasExtension(XR_EXT_HAND_TRACKING_EXTENSION_NAME);
  h->depthOffered = hasExtension(XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME);
  std::vector<const char*> extensions = {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME};
  if (options.preferHandTracking && handTrackingOffered) extensions.push_back(XR_EXT_HAND_TRACKING_EXTENSION_NAME);
  if (h->depthOffered) extensions.push_back(XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME);
  const bool viveTracker = options.useTracker && hasExtension(XR_HTCX_VIVE_TRACKER_INTERACTION_EXTENSION_NAME);
  if (viveTracker) extensions.push_back(XR_HTCX_VIVE_TRACKER_INTERACTION_EXTENSION_NAME);
  // Hand poses are stamped with the time they describe on the app's monotonic clock.
  const bool timespec = hasExtension(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
  if (timespec) extensions.push_back(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);
  // Every richer controller haptics the runtime offers is enabled; each controller then plays
  // the richest it supports (chooseControllerHaptics): the texture waveform itself (Quest:
  // XR_FB_haptic_pcm), else amplitude and frequency curves (XR_EXT_haptic_parametric), else an
  // envelope, else the rumble.
  for (const auto& [name, flag] : {std::pair{XR_FB_HAPTIC_AMPLITUDE_ENVELOPE_EXTENSION_NAME, &h->envelopeEnabled},
                                   std::pair{XR_EXT_HAPTIC_PARAMETRIC_EXTENSION_NAME, &h->parametricEnabled},
                                   std::pair{XR_FB_HAPTIC_PCM_EXTENSION_NAME, &h->pcmEnabled}}) {
    *flag = hasExtension(name);
    if (*flag) extensions.push_back(name);
  }
  h->controllerHaptics = h->pcmEnabled         ? ControllerHaptics::Pcm
                         : h->parametricEnabled ? ControllerHaptics::Parametric
                         : h->envelopeEnabled   ? ControllerHaptics::AmplitudeEnvelope
                                                : ControllerHaptics::Rumble;
  XrInstanceCreateInfo createInfo{XR_TYPE_INSTANCE_CREATE_INFO};
  std::snprintf(createInfo.applicationInfo.applicationName, sizeof(createInfo.applicationInfo.applicationName), "%s",
                options.applicationName.c_str());
  std::snprintf(createInfo.applicationInfo.engineName, sizeof(createInfo.applicationInfo.engineName), "vt");
  createInfo.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  createInfo.enabledExtensionCount = std::uint32_t(extensions.size());
  createInfo.enabledExtensionNames = extensions.data();
  if (XrResult r = xrCreateInstance(&createInfo, &h->instance); XR_FAILED(r)) {
    h->instance = XR_NULL_HANDLE;
    if (r == XR_ERROR_EXTENSION_NOT_PRESENT) return unavailable(Unavailable::NoRuntime, "the runtime lacks XR_KHR_vulkan_enable2");
    return unavailable(Unavailable::NoRuntime, str("xrCreateInstance: ", resultName(r)));
  }
  XrInstanceProperties props{XR_TYPE_INSTANCE_PROPERTIES};
  VT_XR_CHECK(xrGetInstanceProperties(h->instance, &props));
  h->runtimeName = props.runtimeName;

  // 2. System: the runtime is there but no headset is.
  XrSystemGetInfo systemInfo{XR_TYPE_SYSTEM_GET_INFO};
  systemInfo.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  if (XrResult r = xrGetSystem(h->instance, &systemInfo, &h->system); XR_FAILED(r))
    return unavailable(Unavailable::NoHmd, str(h->runtimeName, ": xrGetSystem: ", resultName(r)));
  XrSystemHandTrackingPropertiesEXT handProps{XR_TYPE_SYSTEM_HAND_TRACKING_PROPERTIES_EXT};
  XrSystemProperties systemProps{XR_TYPE_SYSTEM_PROPERTIES};
  if (options.preferHandTracking && handTrackingOffered) systemProps.next = &handProps;
  VT_XR_CHECK(xrGetSystemProperties(h->instance, h->system, &systemProps));
  h->handTracking = handProps.supportsHandTracking == XR_TRUE;

  // 3. Vulkan through the runtime, then the session.
  auto getRequirements = instanceFunction<PFN_xrGetVulkanGraphicsRequirements2KHR>(h->instance, "xrGetVulkanGraphicsRequirements2KHR");
  XrGraphicsRequirementsVulkan2KHR requirements{XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR};
  VT_XR_CHECK(getRequirements(h->instance, h->system, &requirements));
  if (XR_VERSION_MAJOR(requirements.minApiVersionSupported) > 1 ||
      (XR_VERSION_MAJOR(requirements.minApiVersionSupported) == 1 && XR_VERSION_MINOR(requirements.minApiVersionSupported) > 3))
    fail("OpenXR: the runtime needs Vulkan newer than 1.3");
  renderer::DeviceOptions deviceOptions;
  deviceOptions.validate = options.validate;
  deviceOptions.hooks = vulkanHooks(h->instance, h->system);
  deviceOptions.instanceExtensions = options.vulkanInstanceExtensions;
  deviceOptions.deviceExtensions = options.vulkanDeviceExtensions;
  h->extraVulkanExtensions = !options.vulkanInstanceExtensions.empty() || !options.vulkanDeviceExtensions.empty();
  try {
    h->device = renderer::Device::create(deviceOptions);
  } catch (const Error& e) {
    if (!h->extraVulkanExtensions) throw;
    // The extras are optional (a mirror window): without them the headset still works.
    vt::log::debug("OpenXR: Vulkan without the extra extensions (", e.what(), ")");
    h->extraVulkanExtensions = false;
    deviceOptions.instanceExtensions.clear();
    deviceOptions.deviceExtensions.clear();
    h->device = renderer::Device::create(deviceOptions);
  }

  XrGraphicsBindingVulkan2KHR binding{XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR};
  binding.instance = h->device->instance();
  binding.physicalDevice = h->device->physicalDevice();
  binding.device = h->device->device();
  binding.queueFamilyIndex = h->device->queueFamily();
  binding.queueIndex = 0;  // the renderer uses queue 0 of its family
  XrSessionCreateInfo sessionInfo{XR_TYPE_SESSION_CREATE_INFO};
  sessionInfo.next = &binding;
  sessionInfo.systemId = h->system;
  if (XrResult r = xrCreateSession(h->instance, &sessionInfo, &h->session); XR_FAILED(r)) {
    h->session = XR_NULL_HANDLE;
    return unavailable(Unavailable::SessionRefused, str(h->runtimeName, ": xrCreateSession: ", resultName(r)));
  }
  h->appSpace = createAppSpace(*h);
  createEyes(*h);
  h->input = std::make_unique<HandInput>(h->instance, h->session, h->handTracking, viveTracker, timespec, options);
  h->chooseControllerHaptics();
  vt::log::info("OpenXR: ", h->runtimeName, ", ", h->device->description(), ", input ",
                h->handTracking ? "hand tracking" : "controllers", viveTracker ? " + vive tracker" : "",
                h->depthFormat != VK_FORMAT_UNDEFINED ? ", depth layers" : "",
                ", controller haptics ", controllerHapticsName(h->handHaptics[0]), " (left), ",
                controllerHapticsName(h->handHaptics[1]), " (right)");
  result.headset.reset(new Headset(std::move(h)));
  return result;
}

const std::shared_ptr<renderer::Device>& Headset::device() const { return m_impl->device; }
int Headset::sessionState() const { return int(m_impl->state); }
std::string Headset::runtimeName() const { return m_impl->runtimeName; }
bool Headset::handTracking() const { return m_impl->handTracking; }
ControllerHaptics Headset::controllerHaptics() const { return m_impl->controllerHaptics; }
ControllerHaptics Headset::controllerHaptics(int hand) const { return m_impl->handHaptics[std::size_t(hand & 1)]; }
ParametricProperties Headset::parametricProperties(int hand) const { return m_impl->parametric[std::size_t(hand & 1)]; }
bool Headset::depthLayers() const { return m_impl->depthFormat != VK_FORMAT_UNDEFINED; }
VkFormat Headset::depthFormat() const { return m_impl->depthFormat; }
bool Headset::extraVulkanExtensions() const { return m_impl->extraVulkanExtensions; }
std::uint64_t Headset::framesRendered() const { return m_impl->framesRendered; }
std::uint64_t Headset::placements() const { return m_impl->placements; }
std::int64_t Headset::displayPeriod_ns() const { return m_impl->displayPeriod; }
HandPose Headset::displayHand(int hand) const { return m_impl->input ? m_impl->input->displayHand(hand) : HandPose{}; }
void Headset::setHandLookahead(std::int64_t lookahead_ns) {
  if (m_impl->input) m_impl->input->setLookahead(lookahead_ns);
}
bool Headset::viveTracker() const { return m_impl->input && m_impl->input->viveTracker(); }
std::string Headset::inputSource() const {
  if (m_impl->input && m_impl->input->trackerPosedHand()) return str("vive tracker (", m_impl->options.trackerRole, ")");
  if (m_impl->handTracking) return "hand tracking";
  const std::string profile = m_impl->input ? m_impl->input->profile() : "";
  return profile.empty() ? "no input yet" : profile;
}

}  // namespace vt::xr
