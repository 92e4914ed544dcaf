// xrsim's XR_FB_haptic_pcm / XR_FB_haptic_amplitude_envelope: offered only when configured, and
// their function gated on the extension (the waveform path itself: tests/xr/hand_haptics_tests.cpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <openxr/openxr.h>

namespace {

constexpr const char* kPcm = "XR_FB_haptic_pcm";
constexpr const char* kEnvelope = "XR_FB_haptic_amplitude_envelope";

std::vector<std::string> offeredExtensions() {
  std::uint32_t count = 0;
  REQUIRE(xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr) == XR_SUCCESS);
  std::vector<XrExtensionProperties> props(count, {XR_TYPE_EXTENSION_PROPERTIES});
  REQUIRE(xrEnumerateInstanceExtensionProperties(nullptr, count, &count, props.data()) == XR_SUCCESS);
  std::vector<std::string> names;
  for (const auto& p : props) names.emplace_back(p.extensionName);
  return names;
}

bool offered(const char* name) {
  const auto names = offeredExtensions();
  return std::find(names.begin(), names.end(), name) != names.end();
}

XrResult createWith(const char* extension, XrInstance& instance) {
  XrInstanceCreateInfo info{XR_TYPE_INSTANCE_CREATE_INFO};
  std::snprintf(info.applicationInfo.applicationName, sizeof(info.applicationInfo.applicationName), "xrsim-fb-haptics");
  info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  info.enabledExtensionCount = extension ? 1 : 0;
  info.enabledExtensionNames = &extension;
  return xrCreateInstance(&info, &instance);
}

}  // namespace

TEST_CASE("xrsim offers the FB haptics extensions only when configured and gates xrGetDeviceSampleRateFB") {
  setenv("XR_RUNTIME_JSON", VT_XRSIM_MANIFEST, 1);
  unsetenv("XRSIM_HAPTIC_PCM");
  unsetenv("XRSIM_HAPTIC_ENVELOPE");
  CHECK_FALSE(offered(kPcm));
  CHECK_FALSE(offered(kEnvelope));
  XrInstance instance = XR_NULL_HANDLE;
  CHECK(createWith(kPcm, instance) == XR_ERROR_EXTENSION_NOT_PRESENT);  // not offered: refused

  setenv("XRSIM_HAPTIC_PCM", "1", 1);
  setenv("XRSIM_HAPTIC_ENVELOPE", "1", 1);
  CHECK(offered(kPcm));
  CHECK(offered(kEnvelope));
  PFN_xrVoidFunction fn = nullptr;
  REQUIRE(createWith(nullptr, instance) == XR_SUCCESS);
  CHECK(xrGetInstanceProcAddr(instance, "xrGetDeviceSampleRateFB", &fn) == XR_ERROR_FUNCTION_UNSUPPORTED);
  CHECK(xrDestroyInstance(instance) == XR_SUCCESS);
  REQUIRE(createWith(kPcm, instance) == XR_SUCCESS);
  CHECK(xrGetInstanceProcAddr(instance, "xrGetDeviceSampleRateFB", &fn) == XR_SUCCESS);
  CHECK(fn != nullptr);
  CHECK(xrDestroyInstance(instance) == XR_SUCCESS);
  unsetenv("XRSIM_HAPTIC_PCM");
  unsetenv("XRSIM_HAPTIC_ENVELOPE");
}
