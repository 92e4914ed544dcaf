// Loader <-> runtime negotiation and xrGetInstanceProcAddr. Debian's loader 1.0.20 does not
// install loader_interfaces.h, so the negotiation structures are declared here as the
// OpenXR loader specification ("Runtime interface negotiation") defines them.
#include <algorithm>
#include <cstring>
#include <map>
#include <string>

#include "api.hpp"

extern "C" {

enum XrLoaderInterfaceStructs {
  XR_LOADER_INTERFACE_STRUCT_UNINTIALIZED = 0,
  XR_LOADER_INTERFACE_STRUCT_LOADER_INFO,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST,
  XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_CREATE_INFO,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_NEXT_INFO,
};

#define XR_LOADER_INFO_STRUCT_VERSION 1
#define XR_RUNTIME_INFO_STRUCT_VERSION 1
#define XR_CURRENT_LOADER_RUNTIME_VERSION 1

struct XrNegotiateLoaderInfo {
  XrLoaderInterfaceStructs structType;
  std::uint32_t structVersion;
  std::size_t structSize;
  std::uint32_t minInterfaceVersion;
  std::uint32_t maxInterfaceVersion;
  XrVersion minApiVersion;
  XrVersion maxApiVersion;
};

struct XrNegotiateRuntimeRequest {
  XrLoaderInterfaceStructs structType;
  std::uint32_t structVersion;
  std::size_t structSize;
  std::uint32_t runtimeInterfaceVersion;
  XrVersion runtimeApiVersion;
  PFN_xrGetInstanceProcAddr getInstanceProcAddr;
};

__attribute__((visibility("default"))) XrResult XRAPI_CALL xrNegotiateLoaderRuntimeInterface(
    const XrNegotiateLoaderInfo* loaderInfo, XrNegotiateRuntimeRequest* runtimeRequest);

}  // extern "C"

namespace xrsim {
namespace {

enum class Needs { Instance, NoInstance, HandTracking, ViveTracker, Vulkan2, Timespec, HapticPcm, HapticParametric };

struct Entry {
  PFN_xrVoidFunction function;
  Needs needs;
};

XrResult XRAPI_CALL getInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function);

#define XRSIM_FN(name, impl, needs) {name, {reinterpret_cast<PFN_xrVoidFunction>(&impl), Needs::needs}}

const std::map<std::string, Entry>& table() {
  static const std::map<std::string, Entry> entries = {
      XRSIM_FN("xrGetInstanceProcAddr", getInstanceProcAddr, Instance),
      XRSIM_FN("xrEnumerateInstanceExtensionProperties", enumerateInstanceExtensionProperties, NoInstance),
      XRSIM_FN("xrEnumerateApiLayerProperties", enumerateApiLayerProperties, NoInstance),
      XRSIM_FN("xrCreateInstance", createInstance, NoInstance),
      XRSIM_FN("xrDestroyInstance", destroyInstance, Instance),
      XRSIM_FN("xrGetInstanceProperties", getInstanceProperties, Instance),
      XRSIM_FN("xrPollEvent", pollEvent, Instance),
      XRSIM_FN("xrResultToString", resultToString, Instance),
      XRSIM_FN("xrStructureTypeToString", structureTypeToString, Instance),
      XRSIM_FN("xrStringToPath", stringToPath, Instance),
      XRSIM_FN("xrPathToString", pathToString, Instance),
      XRSIM_FN("xrGetSystem", getSystem, Instance),
      XRSIM_FN("xrGetSystemProperties", getSystemProperties, Instance),
      XRSIM_FN("xrEnumerateEnvironmentBlendModes", enumerateEnvironmentBlendModes, Instance),
      XRSIM_FN("xrEnumerateViewConfigurations", enumerateViewConfigurations, Instance),
      XRSIM_FN("xrGetViewConfigurationProperties", getViewConfigurationProperties, Instance),
      XRSIM_FN("xrEnumerateViewConfigurationViews", enumerateViewConfigurationViews, Instance),
      XRSIM_FN("xrCreateSession", createSession, Instance),
      XRSIM_FN("xrDestroySession", destroySession, Instance),
      XRSIM_FN("xrBeginSession", beginSession, Instance),
      XRSIM_FN("xrEndSession", endSession, Instance),
      XRSIM_FN("xrRequestExitSession", requestExitSession, Instance),
      XRSIM_FN("xrWaitFrame", waitFrame, Instance),
      XRSIM_FN("xrBeginFrame", beginFrame, Instance),
      XRSIM_FN("xrEndFrame", endFrame, Instance),
      XRSIM_FN("xrLocateViews", locateViews, Instance),
      XRSIM_FN("xrEnumerateReferenceSpaces", enumerateReferenceSpaces, Instance),
      XRSIM_FN("xrCreateReferenceSpace", createReferenceSpace, Instance),
      XRSIM_FN("xrGetReferenceSpaceBoundsRect", getReferenceSpaceBoundsRect, Instance),
      XRSIM_FN("xrCreateActionSpace", createActionSpace, Instance),
      XRSIM_FN("xrLocateSpace", locateSpace, Instance),
      XRSIM_FN("xrDestroySpace", destroySpace, Instance),
      XRSIM_FN("xrEnumerateSwapchainFormats", enumerateSwapchainFormats, Instance),
      XRSIM_FN("xrCreateSwapchain", createSwapchain, Instance),
      XRSIM_FN("xrDestroySwapchain", destroySwapchain, Instance),
      XRSIM_FN("xrEnumerateSwapchainImages", enumerateSwapchainImages, Instance),
      XRSIM_FN("xrAcquireSwapchainImage", acquireSwapchainImage, Instance),
      XRSIM_FN("xrWaitSwapchainImage", waitSwapchainImage, Instance),
      XRSIM_FN("xrReleaseSwapchainImage", releaseSwapchainImage, Instance),
      XRSIM_FN("xrCreateActionSet", createActionSet, Instance),
      XRSIM_FN("xrDestroyActionSet", destroyActionSet, Instance),
      XRSIM_FN("xrCreateAction", createAction, Instance),
      XRSIM_FN("xrDestroyAction", destroyAction, Instance),
      XRSIM_FN("xrSuggestInteractionProfileBindings", suggestInteractionProfileBindings, Instance),
      XRSIM_FN("xrAttachSessionActionSets", attachSessionActionSets, Instance),
      XRSIM_FN("xrGetCurrentInteractionProfile", getCurrentInteractionProfile, Instance),
      XRSIM_FN("xrEnumerateBoundSourcesForAction", enumerateBoundSourcesForAction, Instance),
      XRSIM_FN("xrGetInputSourceLocalizedName", getInputSourceLocalizedName, Instance),
      XRSIM_FN("xrSyncActions", syncActions, Instance),
      XRSIM_FN("xrGetActionStateBoolean", getActionStateBoolean, Instance),
      XRSIM_FN("xrGetActionStateFloat", getActionStateFloat, Instance),
      XRSIM_FN("xrGetActionStateVector2f", getActionStateVector2f, Instance),
      XRSIM_FN("xrGetActionStatePose", getActionStatePose, Instance),
      XRSIM_FN("xrApplyHapticFeedback", applyHapticFeedback, Instance),
      XRSIM_FN("xrStopHapticFeedback", stopHapticFeedback, Instance),
      XRSIM_FN("xrGetDeviceSampleRateFB", getDeviceSampleRate, HapticPcm),
      XRSIM_FN("xrHapticParametricGetPropertiesEXT", hapticParametricGetProperties, HapticParametric),
      XRSIM_FN("xrCreateHandTrackerEXT", createHandTracker, HandTracking),
      XRSIM_FN("xrDestroyHandTrackerEXT", destroyHandTracker, HandTracking),
      XRSIM_FN("xrLocateHandJointsEXT", locateHandJoints, HandTracking),
      XRSIM_FN("xrEnumerateViveTrackerPathsHTCX", enumerateViveTrackerPaths, ViveTracker),
      XRSIM_FN("xrConvertTimespecTimeToTimeKHR", convertTimespecTimeToTime, Timespec),
      XRSIM_FN("xrConvertTimeToTimespecTimeKHR", convertTimeToTimespecTime, Timespec),
      XRSIM_FN("xrGetVulkanGraphicsRequirements2KHR", getVulkanGraphicsRequirements2, Vulkan2),
      XRSIM_FN("xrCreateVulkanInstanceKHR", createVulkanInstance, Vulkan2),
      XRSIM_FN("xrGetVulkanGraphicsDevice2KHR", getVulkanGraphicsDevice2, Vulkan2),
      XRSIM_FN("xrCreateVulkanDeviceKHR", createVulkanDevice, Vulkan2),
  };
  return entries;
}

#undef XRSIM_FN

XrResult XRAPI_CALL getInstanceProcAddr(XrInstance instance, const char* name, PFN_xrVoidFunction* function) {
  return guarded("xrGetInstanceProcAddr", [&]() -> XrResult {
    if (name == nullptr || function == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    *function = nullptr;
    const auto it = table().find(name);
    if (instance == XR_NULL_HANDLE) {
      if (it == table().end() || it->second.needs != Needs::NoInstance) return XR_ERROR_HANDLE_INVALID;
      *function = it->second.function;
      return XR_SUCCESS;
    }
    Instance* inst = lookup<Instance>(instance);
    if (inst == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (it == table().end()) return XR_ERROR_FUNCTION_UNSUPPORTED;
    // Extension functions exist only when their extension was enabled (spec 4.1 / 2.7).
    if (it->second.needs == Needs::HandTracking && !inst->handTrackingEnabled) return XR_ERROR_FUNCTION_UNSUPPORTED;
    if (it->second.needs == Needs::Vulkan2 && !inst->vulkan2Enabled) return XR_ERROR_FUNCTION_UNSUPPORTED;
    if (it->second.needs == Needs::ViveTracker && !inst->viveTrackerEnabled) return XR_ERROR_FUNCTION_UNSUPPORTED;
    if (it->second.needs == Needs::Timespec && !inst->timespecEnabled) return XR_ERROR_FUNCTION_UNSUPPORTED;
    if (it->second.needs == Needs::HapticPcm && !inst->hapticPcmEnabled) return XR_ERROR_FUNCTION_UNSUPPORTED;
    if (it->second.needs == Needs::HapticParametric && !inst->hapticParametricEnabled) return XR_ERROR_FUNCTION_UNSUPPORTED;
    *function = it->second.function;
    return XR_SUCCESS;
  });
}

}  // namespace
}  // namespace xrsim

extern "C" XrResult XRAPI_CALL xrNegotiateLoaderRuntimeInterface(const XrNegotiateLoaderInfo* loaderInfo,
                                                               XrNegotiateRuntimeRequest* runtimeRequest) {
  if (loaderInfo == nullptr || runtimeRequest == nullptr ||
      loaderInfo->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
      loaderInfo->structVersion != XR_LOADER_INFO_STRUCT_VERSION ||
      loaderInfo->structSize != sizeof(XrNegotiateLoaderInfo) ||
      runtimeRequest->structType != XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST ||
      runtimeRequest->structVersion != XR_RUNTIME_INFO_STRUCT_VERSION ||
      runtimeRequest->structSize != sizeof(XrNegotiateRuntimeRequest))
    return XR_ERROR_INITIALIZATION_FAILED;
  if (loaderInfo->minInterfaceVersion > XR_CURRENT_LOADER_RUNTIME_VERSION ||
      loaderInfo->maxInterfaceVersion < XR_CURRENT_LOADER_RUNTIME_VERSION)
    return XR_ERROR_INITIALIZATION_FAILED;
  const XrVersion ours = XR_MAKE_VERSION(1, 0, 0);
  if (XR_VERSION_MAJOR(loaderInfo->minApiVersion) > 1 || XR_VERSION_MAJOR(loaderInfo->maxApiVersion) < 1)
    return XR_ERROR_INITIALIZATION_FAILED;
  runtimeRequest->runtimeInterfaceVersion = XR_CURRENT_LOADER_RUNTIME_VERSION;
  runtimeRequest->runtimeApiVersion = std::max<XrVersion>(ours, std::min<XrVersion>(loaderInfo->maxApiVersion, XR_CURRENT_API_VERSION));
  runtimeRequest->getInstanceProcAddr = &xrsim::getInstanceProcAddr;
  return XR_SUCCESS;
}
