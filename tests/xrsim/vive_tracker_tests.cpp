// xrsim's XR_HTCX_vive_tracker_interaction through the unmodified Khronos loader: the extension
// is offered, its function exists only when enabled, the scripted tracker's paths, and tracker
// bindings. (The tracker's pose through an action space is checked end to end in tests/xr.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <openxr/openxr.h>

#include "test_support.hpp"
#include "tracker_binding.hpp"

namespace {

// An xrsim instance with the given extensions and script (empty = none); XR_NULL_HANDLE and
// `result` set when creation fails.
XrInstance createInstance(const std::vector<const char*>& extensions, const std::string& script, XrResult& result) {
  setenv("XR_RUNTIME_JSON", VT_XRSIM_MANIFEST, 1);
  if (script.empty()) unsetenv("XRSIM_SCRIPT");
  else setenv("XRSIM_SCRIPT", script.c_str(), 1);
  XrInstanceCreateInfo info{XR_TYPE_INSTANCE_CREATE_INFO};
  std::snprintf(info.applicationInfo.applicationName, sizeof(info.applicationInfo.applicationName), "xrsim-test");
  info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  info.enabledExtensionCount = std::uint32_t(extensions.size());
  info.enabledExtensionNames = extensions.data();
  XrInstance instance = XR_NULL_HANDLE;
  result = xrCreateInstance(&info, &instance);
  unsetenv("XRSIM_SCRIPT");
  return result == XR_SUCCESS ? instance : XR_NULL_HANDLE;
}

std::string writeScript(const std::string& name, const std::string& text) {
  const auto path = vt::test::outputDir("xrsim_vive_tracker") / name;
  std::FILE* file = std::fopen(path.c_str(), "w");
  REQUIRE(file);
  std::fputs(text.c_str(), file);
  std::fclose(file);
  return path.string();
}

std::string pathText(XrInstance instance, XrPath path) {
  char buffer[XR_MAX_PATH_LENGTH] = {};
  std::uint32_t count = 0;
  REQUIRE(xrPathToString(instance, path, sizeof(buffer), &count, buffer) == XR_SUCCESS);
  return buffer;
}

XrResult suggestTrackerBinding(XrInstance instance, const char* binding) {
  const vt::test::TrackerPoseAction tracker = vt::test::suggestTrackerPose(instance, binding);
  REQUIRE(xrDestroyActionSet(tracker.set) == XR_SUCCESS);
  return tracker.suggested;
}

constexpr const char* kTracker = XR_HTCX_VIVE_TRACKER_INTERACTION_EXTENSION_NAME;

PFN_xrEnumerateViveTrackerPathsHTCX enumerateFunction(XrInstance instance) {
  PFN_xrVoidFunction fn = nullptr;
  REQUIRE(xrGetInstanceProcAddr(instance, "xrEnumerateViveTrackerPathsHTCX", &fn) == XR_SUCCESS);
  REQUIRE(fn != nullptr);
  return reinterpret_cast<PFN_xrEnumerateViveTrackerPathsHTCX>(fn);
}

}  // namespace

TEST_CASE("xrsim offers the vive tracker extension and gates its function and device bindings") {
  setenv("XR_RUNTIME_JSON", VT_XRSIM_MANIFEST, 1);
  std::uint32_t count = 0;
  REQUIRE(xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr) == XR_SUCCESS);
  std::vector<XrExtensionProperties> props(count, {XR_TYPE_EXTENSION_PROPERTIES});
  REQUIRE(xrEnumerateInstanceExtensionProperties(nullptr, count, &count, props.data()) == XR_SUCCESS);
  CHECK(std::any_of(props.begin(), props.end(), [](const auto& p) { return std::string(p.extensionName) == kTracker; }));

  const std::string script = writeScript("tracked.json", R"({"keyframes": [{"t": 0, "tracker": {"position": [0, 1, 0]}}]})");
  XrResult result = XR_SUCCESS;
  XrInstance plain = createInstance({}, script, result);
  REQUIRE(plain != XR_NULL_HANDLE);
  PFN_xrVoidFunction fn = nullptr;
  CHECK(xrGetInstanceProcAddr(plain, "xrEnumerateViveTrackerPathsHTCX", &fn) == XR_ERROR_FUNCTION_UNSUPPORTED);
  // A tracker's persistent /devices/ path is no binding without the extension.
  CHECK(suggestTrackerBinding(plain, "/devices/htc/vive_tracker_xrsim/input/grip/pose") == XR_ERROR_PATH_UNSUPPORTED);
  CHECK(xrDestroyInstance(plain) == XR_SUCCESS);

  XrInstance enabled = createInstance({kTracker}, script, result);
  REQUIRE(enabled != XR_NULL_HANDLE);
  CHECK(xrGetInstanceProcAddr(enabled, "xrEnumerateViveTrackerPathsHTCX", &fn) == XR_SUCCESS);
  CHECK(fn != nullptr);
  CHECK(suggestTrackerBinding(enabled, "/devices/htc/vive_tracker_xrsim/input/grip/pose") == XR_SUCCESS);
  CHECK(suggestTrackerBinding(enabled, "/user/vive_tracker_htcx/role/handheld_object/input/grip/pose") == XR_SUCCESS);
  CHECK(xrDestroyInstance(enabled) == XR_SUCCESS);
}

TEST_CASE("xrsim enumerates the scripted vive tracker with its role") {
  XrResult result = XR_SUCCESS;
  const std::string script = writeScript(
      "role.json", R"({"keyframes": [{"t": 0, "tracker": {"position": [0, 1, 0], "role": "left_foot"}}]})");
  XrInstance instance = createInstance({kTracker}, script, result);
  REQUIRE(instance != XR_NULL_HANDLE);
  std::uint32_t count = 0;
  REQUIRE(enumerateFunction(instance)(instance, 0, &count, nullptr) == XR_SUCCESS);
  REQUIRE(count == 1);
  XrViveTrackerPathsHTCX paths{XR_TYPE_VIEW_CONFIGURATION_VIEW};  // wrong type on purpose
  CHECK(enumerateFunction(instance)(instance, 1, &count, &paths) == XR_ERROR_VALIDATION_FAILURE);
  paths = {XR_TYPE_VIVE_TRACKER_PATHS_HTCX};
  REQUIRE(enumerateFunction(instance)(instance, 1, &count, &paths) == XR_SUCCESS);
  CHECK(pathText(instance, paths.persistentPath) == "/devices/htc/vive_tracker_xrsim");
  CHECK(pathText(instance, paths.rolePath) == "/user/vive_tracker_htcx/role/left_foot");
  CHECK(xrDestroyInstance(instance) == XR_SUCCESS);

  // The default role, and no tracker when the script has none.
  const std::string unnamed = writeScript("unnamed.json", R"({"keyframes": [{"t": 0, "tracker": {}}]})");
  instance = createInstance({kTracker}, unnamed, result);
  REQUIRE(instance != XR_NULL_HANDLE);
  REQUIRE(enumerateFunction(instance)(instance, 1, &count, &paths) == XR_SUCCESS);
  CHECK(count == 1);
  CHECK(pathText(instance, paths.rolePath) == "/user/vive_tracker_htcx/role/handheld_object");
  CHECK(xrDestroyInstance(instance) == XR_SUCCESS);
  instance = createInstance({kTracker}, "", result);
  REQUIRE(instance != XR_NULL_HANDLE);
  REQUIRE(enumerateFunction(instance)(instance, 0, &count, nullptr) == XR_SUCCESS);
  CHECK(count == 0);
  CHECK(xrDestroyInstance(instance) == XR_SUCCESS);

  // A malformed role is refused at xrCreateInstance.
  const std::string bad = writeScript("bad.json", R"({"keyframes": [{"t": 0, "tracker": {"role": "Left Foot"}}]})");
  CHECK(createInstance({kTracker}, bad, result) == XR_NULL_HANDLE);
  CHECK(result == XR_ERROR_INITIALIZATION_FAILED);
}
