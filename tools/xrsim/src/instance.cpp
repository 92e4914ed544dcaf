// Instance lifetime, extensions, events, paths and enum-to-string entry points.
#include <openxr/openxr_reflection.h>

#include <cstdio>
#include <exception>

#include "api.hpp"

namespace xrsim {
namespace {

// The settings that decide which extensions are offered; a bad setting is reported once, by
// xrCreateInstance (defaults here).
Config offeredConfig() noexcept {
  try {
    return loadConfig();
  } catch (const std::exception&) {
    return Config{};
  }
}

std::vector<XrExtensionProperties> extensions(const Config& config) {
  auto make = [](const char* name, std::uint32_t version) {
    XrExtensionProperties p{XR_TYPE_EXTENSION_PROPERTIES};
    std::snprintf(p.extensionName, sizeof(p.extensionName), "%s", name);
    p.extensionVersion = version;
    return p;
  };
  std::vector<XrExtensionProperties> list = {make(XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME, XR_KHR_vulkan_enable2_SPEC_VERSION)};
  if (config.depthLayers)
    list.push_back(make(XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME, XR_KHR_composition_layer_depth_SPEC_VERSION));
  list.push_back(make(XR_EXT_HAND_TRACKING_EXTENSION_NAME, XR_EXT_hand_tracking_SPEC_VERSION));
  // Only in realtime mode is XrTime the wall clock (CLOCK_MONOTONIC); stepped mode's display
  // times advance one period per frame, however fast the app runs, and have no timespec.
  if (config.realtime)
    list.push_back(make(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME, XR_KHR_convert_timespec_time_SPEC_VERSION));
  list.push_back(make(XR_HTCX_VIVE_TRACKER_INTERACTION_EXTENSION_NAME, XR_HTCX_vive_tracker_interaction_SPEC_VERSION));
  if (config.hapticPcm) list.push_back(make(XR_FB_HAPTIC_PCM_EXTENSION_NAME, XR_FB_haptic_pcm_SPEC_VERSION));
  if (config.hapticEnvelope)
    list.push_back(make(XR_FB_HAPTIC_AMPLITUDE_ENVELOPE_EXTENSION_NAME, XR_FB_haptic_amplitude_envelope_SPEC_VERSION));
  if (config.hapticParametric) list.push_back(make(XR_EXT_HAPTIC_PARAMETRIC_EXTENSION_NAME, XR_EXT_haptic_parametric_SPEC_VERSION));
  return list;
}

bool validFixedString(const char* text, std::size_t capacity) {
  return std::memchr(text, 0, capacity) != nullptr && text[0] != 0;
}

}  // namespace

XrResult XRAPI_CALL enumerateInstanceExtensionProperties(const char* layerName, std::uint32_t capacity,
                                                         std::uint32_t* count, XrExtensionProperties* out) {
  return guarded("xrEnumerateInstanceExtensionProperties", [&]() -> XrResult {
    if (layerName != nullptr && layerName[0] != 0) return XR_ERROR_API_LAYER_NOT_PRESENT;
    const auto list = extensions(offeredConfig());
    if (out != nullptr)
      for (std::uint32_t i = 0; i < capacity && i < list.size(); ++i)
        if (out[i].type != XR_TYPE_EXTENSION_PROPERTIES) return XR_ERROR_VALIDATION_FAILURE;
    return twoCall(capacity, count, out, list);
  });
}

XrResult XRAPI_CALL enumerateApiLayerProperties(std::uint32_t capacity, std::uint32_t* count,
                                                XrApiLayerProperties* out) {
  return guarded("xrEnumerateApiLayerProperties",
                 [&] { return twoCall(capacity, count, out, std::vector<XrApiLayerProperties>{}); });
}

XrResult XRAPI_CALL createInstance(const XrInstanceCreateInfo* info, XrInstance* out) {
  return guarded("xrCreateInstance", [&]() -> XrResult {
    XRSIM_CHECK_STRUCT(info, XR_TYPE_INSTANCE_CREATE_INFO);
    if (out == nullptr || info->createFlags != 0) return XR_ERROR_VALIDATION_FAILURE;
    const auto& app = info->applicationInfo;
    if (!validFixedString(app.applicationName, sizeof(app.applicationName))) return XR_ERROR_NAME_INVALID;
    if (XR_VERSION_MAJOR(app.apiVersion) != 1 || XR_VERSION_MINOR(app.apiVersion) != 0)
      return XR_ERROR_API_VERSION_UNSUPPORTED;
    if (info->enabledApiLayerCount != 0) return XR_ERROR_API_LAYER_NOT_PRESENT;
    auto instance = std::make_unique<Instance>();
    for (std::uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
      const std::string name = info->enabledExtensionNames[i];
      if (name == XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) instance->vulkan2Enabled = true;
      else if (name == XR_KHR_COMPOSITION_LAYER_DEPTH_EXTENSION_NAME) instance->depthEnabled = true;
      else if (name == XR_EXT_HAND_TRACKING_EXTENSION_NAME) instance->handTrackingEnabled = true;
      else if (name == XR_HTCX_VIVE_TRACKER_INTERACTION_EXTENSION_NAME) instance->viveTrackerEnabled = true;
      else if (name == XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME) instance->timespecEnabled = true;
      else if (name == XR_FB_HAPTIC_PCM_EXTENSION_NAME) instance->hapticPcmEnabled = true;
      else if (name == XR_FB_HAPTIC_AMPLITUDE_ENVELOPE_EXTENSION_NAME) instance->hapticEnvelopeEnabled = true;
      else if (name == XR_EXT_HAPTIC_PARAMETRIC_EXTENSION_NAME) instance->hapticParametricEnabled = true;
      else return XR_ERROR_EXTENSION_NOT_PRESENT;
    }
    try {
      instance->config = loadConfig();
      if (!instance->config.scriptPath.empty()) instance->script = Script::load(instance->config.scriptPath);
      if (instance->depthEnabled && !instance->config.depthLayers) return XR_ERROR_EXTENSION_NOT_PRESENT;
      if (instance->hapticPcmEnabled && !instance->config.hapticPcm) return XR_ERROR_EXTENSION_NOT_PRESENT;
      if (instance->hapticEnvelopeEnabled && !instance->config.hapticEnvelope) return XR_ERROR_EXTENSION_NOT_PRESENT;
      if (instance->hapticParametricEnabled && !instance->config.hapticParametric) return XR_ERROR_EXTENSION_NOT_PRESENT;
    } catch (const vt::Error& e) {
      std::fprintf(stderr, "xrsim: %s\n", e.what());
      return XR_ERROR_INITIALIZATION_FAILED;
    }
    instance->applicationName = app.applicationName;
    *out = handleOf(instance.get());
    instanceList().push_back(std::move(instance));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL destroyInstance(XrInstance handle) {
  return guarded("xrDestroyInstance", [&]() -> XrResult {
    Instance* instance = lookup<Instance>(handle);
    if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
    auto& list = instanceList();
    for (auto it = list.begin(); it != list.end(); ++it)
      if (it->get() == instance) {
        list.erase(it);
        break;
      }
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL getInstanceProperties(XrInstance handle, XrInstanceProperties* props) {
  return guarded("xrGetInstanceProperties", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(props, XR_TYPE_INSTANCE_PROPERTIES);
    props->runtimeVersion = XR_MAKE_VERSION(0, 1, 0);
    std::snprintf(props->runtimeName, sizeof(props->runtimeName), "xrsim (V-Touching headless runtime)");
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL pollEvent(XrInstance handle, XrEventDataBuffer* event) {
  return guarded("xrPollEvent", [&]() -> XrResult {
    Instance* instance = lookup<Instance>(handle);
    if (instance == nullptr) return XR_ERROR_HANDLE_INVALID;
    XRSIM_CHECK_STRUCT(event, XR_TYPE_EVENT_DATA_BUFFER);
    // Events keep flowing after an instance loss so the app can see the loss-pending event.
    if (instance->events.empty()) return instance->lost ? XR_ERROR_INSTANCE_LOST : XR_EVENT_UNAVAILABLE;
    *event = instance->events.front();
    instance->events.pop_front();
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL resultToString(XrInstance handle, XrResult value, char* buffer) {
  return guarded("xrResultToString", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const char* name = nullptr;
    switch (value) {
#define XRSIM_RESULT_CASE(n, v) case n: name = #n; break;
      XR_LIST_ENUM_XrResult(XRSIM_RESULT_CASE)
#undef XRSIM_RESULT_CASE
      default: break;
    }
    if (name) std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "%s", name);
    else std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "XR_%s_%d", value < 0 ? "UNKNOWN_FAILURE" : "UNKNOWN_SUCCESS", int(value));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL structureTypeToString(XrInstance handle, XrStructureType value, char* buffer) {
  return guarded("xrStructureTypeToString", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const char* name = nullptr;
    switch (value) {
#define XRSIM_TYPE_CASE(n, v) case n: name = #n; break;
      XR_LIST_ENUM_XrStructureType(XRSIM_TYPE_CASE)
#undef XRSIM_TYPE_CASE
      default: break;
    }
    if (name) std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "%s", name);
    else std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "XR_UNKNOWN_STRUCTURE_TYPE_%d", int(value));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL stringToPath(XrInstance handle, const char* text, XrPath* out) {
  return guarded("xrStringToPath", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    if (text == nullptr || out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (!wellFormedPath(text)) return XR_ERROR_PATH_FORMAT_INVALID;
    *out = internPath(*instance, text);
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL pathToString(XrInstance handle, XrPath path, std::uint32_t capacity, std::uint32_t* count,
                                 char* buffer) {
  return guarded("xrPathToString", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    const std::string* text = pathString(*instance, path);
    if (text == nullptr) return XR_ERROR_PATH_INVALID;
    return twoCallString(capacity, count, buffer, *text);
  });
}

std::vector<std::unique_ptr<Instance>>& instanceList() {
  static std::vector<std::unique_ptr<Instance>> instances;
  return instances;
}

}  // namespace xrsim
