// The one simulated headset: system properties, view configurations, blend modes.
#include <cstdio>

#include "api.hpp"

namespace xrsim {

XrResult checkSystem(const Instance& instance, XrSystemId system) noexcept {
  if (system != kSystemId || instance.config.failure == Failure::NoHmd) return XR_ERROR_SYSTEM_INVALID;
  return XR_SUCCESS;
}

XrResult XRAPI_CALL getSystem(XrInstance handle, const XrSystemGetInfo* info, XrSystemId* out) {
  return guarded("xrGetSystem", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_SYSTEM_GET_INFO);
    if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (info->formFactor == XR_FORM_FACTOR_HANDHELD_DISPLAY) return XR_ERROR_FORM_FACTOR_UNSUPPORTED;
    if (info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY) return XR_ERROR_VALIDATION_FAILURE;
    if (instance->config.failure == Failure::NoHmd) return XR_ERROR_FORM_FACTOR_UNAVAILABLE;
    *out = kSystemId;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL getSystemProperties(XrInstance handle, XrSystemId system, XrSystemProperties* props) {
  return guarded("xrGetSystemProperties", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    if (XrResult r = checkSystem(*instance, system); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(props, XR_TYPE_SYSTEM_PROPERTIES);
    props->systemId = kSystemId;
    props->vendorId = 0x5654;  // "VT"
    std::snprintf(props->systemName, sizeof(props->systemName), "xrsim simulated headset");
    props->graphicsProperties = {4096, 4096, 16};
    props->trackingProperties = {XR_TRUE, XR_TRUE};
    for (auto* next = static_cast<XrBaseOutStructure*>(props->next); next != nullptr; next = next->next)
      if (next->type == XR_TYPE_SYSTEM_HAND_TRACKING_PROPERTIES_EXT && instance->handTrackingEnabled)
        reinterpret_cast<XrSystemHandTrackingPropertiesEXT*>(next)->supportsHandTracking =
            instance->config.handTracking ? XR_TRUE : XR_FALSE;
      else if (next->type == XR_TYPE_SYSTEM_HAPTIC_PARAMETRIC_PROPERTIES_EXT && instance->hapticParametricEnabled)
        reinterpret_cast<XrSystemHapticParametricPropertiesEXT*>(next)->supportsParametricHaptics = XR_TRUE;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL enumerateEnvironmentBlendModes(XrInstance handle, XrSystemId system, XrViewConfigurationType type,
                                                   std::uint32_t capacity, std::uint32_t* count,
                                                   XrEnvironmentBlendMode* out) {
  return guarded("xrEnumerateEnvironmentBlendModes", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    if (XrResult r = checkSystem(*instance, system); r != XR_SUCCESS) return r;
    if (type != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
    return twoCall(capacity, count, out, std::vector<XrEnvironmentBlendMode>{XR_ENVIRONMENT_BLEND_MODE_OPAQUE});
  });
}

XrResult XRAPI_CALL enumerateViewConfigurations(XrInstance handle, XrSystemId system, std::uint32_t capacity,
                                                std::uint32_t* count, XrViewConfigurationType* out) {
  return guarded("xrEnumerateViewConfigurations", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    if (XrResult r = checkSystem(*instance, system); r != XR_SUCCESS) return r;
    return twoCall(capacity, count, out, std::vector<XrViewConfigurationType>{XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO});
  });
}

XrResult XRAPI_CALL getViewConfigurationProperties(XrInstance handle, XrSystemId system, XrViewConfigurationType type,
                                                   XrViewConfigurationProperties* props) {
  return guarded("xrGetViewConfigurationProperties", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    if (XrResult r = checkSystem(*instance, system); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(props, XR_TYPE_VIEW_CONFIGURATION_PROPERTIES);
    if (type != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
    props->viewConfigurationType = type;
    props->fovMutable = XR_FALSE;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL enumerateViewConfigurationViews(XrInstance handle, XrSystemId system, XrViewConfigurationType type,
                                                    std::uint32_t capacity, std::uint32_t* count,
                                                    XrViewConfigurationView* out) {
  return guarded("xrEnumerateViewConfigurationViews", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    if (XrResult r = checkSystem(*instance, system); r != XR_SUCCESS) return r;
    if (type != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
    XrViewConfigurationView view{XR_TYPE_VIEW_CONFIGURATION_VIEW};
    view.recommendedImageRectWidth = std::uint32_t(instance->config.width);
    view.recommendedImageRectHeight = std::uint32_t(instance->config.height);
    view.maxImageRectWidth = view.maxImageRectHeight = 4096;
    view.recommendedSwapchainSampleCount = 1;
    view.maxSwapchainSampleCount = 1;
    if (out != nullptr)
      for (std::uint32_t i = 0; i < capacity && i < 2; ++i)
        if (out[i].type != XR_TYPE_VIEW_CONFIGURATION_VIEW) return XR_ERROR_VALIDATION_FAILURE;
    return twoCall(capacity, count, out, std::vector<XrViewConfigurationView>{view, view});
  });
}

}  // namespace xrsim
