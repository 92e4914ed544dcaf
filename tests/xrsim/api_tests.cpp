// xrsim's API behaviour through the unmodified Khronos loader: negotiation, extension gating,
// handle and structure validation, call order and the session state machine's error codes.
// Also XR_HTCX_vive_tracker_interaction inside a session (its instance-level checks: vive_tracker_tests.cpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <vulkan/vulkan.h>
#define XR_USE_GRAPHICS_API_VULKAN
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include "test_support.hpp"
#include "tracker_binding.hpp"

namespace {

template <class Fn>
Fn function(XrInstance instance, const char* name) {
  PFN_xrVoidFunction fn = nullptr;
  REQUIRE(xrGetInstanceProcAddr(instance, name, &fn) == XR_SUCCESS);
  return reinterpret_cast<Fn>(fn);
}

// An instance of xrsim with XR_KHR_vulkan_enable2, plus the Vulkan objects a session needs.
struct Fixture {
  XrInstance instance = XR_NULL_HANDLE;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  VkInstance vkInstance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t family = 0;

  explicit Fixture(bool queryRequirements = true, const char* extraExtension = nullptr) {
    setenv("XR_RUNTIME_JSON", VT_XRSIM_MANIFEST, 1);
    const char* extensions[] = {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME, extraExtension};
    XrInstanceCreateInfo info{XR_TYPE_INSTANCE_CREATE_INFO};
    std::snprintf(info.applicationInfo.applicationName, sizeof(info.applicationInfo.applicationName), "xrsim-test");
    info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
    info.enabledExtensionCount = extraExtension ? 2 : 1;
    info.enabledExtensionNames = extensions;
    REQUIRE(xrCreateInstance(&info, &instance) == XR_SUCCESS);
    XrSystemGetInfo systemInfo{XR_TYPE_SYSTEM_GET_INFO};
    systemInfo.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    REQUIRE(xrGetSystem(instance, &systemInfo, &system) == XR_SUCCESS);
    if (queryRequirements) {
      XrGraphicsRequirementsVulkan2KHR req{XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR};
      REQUIRE(function<PFN_xrGetVulkanGraphicsRequirements2KHR>(instance, "xrGetVulkanGraphicsRequirements2KHR")(
                  instance, system, &req) == XR_SUCCESS);
    }
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_1;
    VkInstanceCreateInfo vkInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    vkInfo.pApplicationInfo = &app;
    XrVulkanInstanceCreateInfoKHR createVk{XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR};
    createVk.systemId = system;
    createVk.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    createVk.vulkanCreateInfo = &vkInfo;
    VkResult vr = VK_ERROR_UNKNOWN;
    REQUIRE(function<PFN_xrCreateVulkanInstanceKHR>(instance, "xrCreateVulkanInstanceKHR")(instance, &createVk, &vkInstance, &vr) == XR_SUCCESS);
    REQUIRE(vr == VK_SUCCESS);
    XrVulkanGraphicsDeviceGetInfoKHR get{XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR};
    get.systemId = system;
    get.vulkanInstance = vkInstance;
    REQUIRE(function<PFN_xrGetVulkanGraphicsDevice2KHR>(instance, "xrGetVulkanGraphicsDevice2KHR")(instance, &get, &physical) == XR_SUCCESS);
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = family;  // lavapipe: family 0 does graphics
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queue;
    XrVulkanDeviceCreateInfoKHR createDevice{XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR};
    createDevice.systemId = system;
    createDevice.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    createDevice.vulkanPhysicalDevice = physical;
    createDevice.vulkanCreateInfo = &deviceInfo;
    REQUIRE(function<PFN_xrCreateVulkanDeviceKHR>(instance, "xrCreateVulkanDeviceKHR")(instance, &createDevice, &device, &vr) == XR_SUCCESS);
    REQUIRE(vr == VK_SUCCESS);
  }
  ~Fixture() {
    if (instance != XR_NULL_HANDLE) xrDestroyInstance(instance);
    if (device != VK_NULL_HANDLE) vkDestroyDevice(device, nullptr);
    if (vkInstance != VK_NULL_HANDLE) vkDestroyInstance(vkInstance, nullptr);
  }

  XrResult createSession(XrSession& session) {
    XrGraphicsBindingVulkan2KHR binding{XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR};
    binding.instance = vkInstance;
    binding.physicalDevice = physical;
    binding.device = device;
    binding.queueFamilyIndex = family;
    XrSessionCreateInfo info{XR_TYPE_SESSION_CREATE_INFO};
    info.next = &binding;
    info.systemId = system;
    return xrCreateSession(instance, &info, &session);
  }

  // Next session state from the event queue, or UNKNOWN when there is none.
  XrSessionState nextState() {
    XrEventDataBuffer event{XR_TYPE_EVENT_DATA_BUFFER};
    while (xrPollEvent(instance, &event) == XR_SUCCESS) {
      if (event.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED)
        return reinterpret_cast<XrEventDataSessionStateChanged&>(event).state;
      event = {XR_TYPE_EVENT_DATA_BUFFER};
    }
    return XR_SESSION_STATE_UNKNOWN;
  }
};

}  // namespace

TEST_CASE("xrsim gates extension functions and validates structure types and handles") {
  Fixture fx;
  PFN_xrVoidFunction fn = nullptr;
  // XR_EXT_hand_tracking is offered but was not enabled: its functions do not exist.
  CHECK(xrGetInstanceProcAddr(fx.instance, "xrCreateHandTrackerEXT", &fn) == XR_ERROR_FUNCTION_UNSUPPORTED);
  CHECK(xrGetInstanceProcAddr(fx.instance, "xrNoSuchFunction", &fn) == XR_ERROR_FUNCTION_UNSUPPORTED);

  XrInstanceProperties props{XR_TYPE_SYSTEM_PROPERTIES};  // wrong type on purpose
  CHECK(xrGetInstanceProperties(fx.instance, &props) == XR_ERROR_VALIDATION_FAILURE);
  props.type = XR_TYPE_INSTANCE_PROPERTIES;
  REQUIRE(xrGetInstanceProperties(fx.instance, &props) == XR_SUCCESS);
  CHECK(std::strstr(props.runtimeName, "xrsim") != nullptr);

  XrPath path = XR_NULL_PATH;
  CHECK(xrStringToPath(fx.instance, "/user/hand/left", &path) == XR_SUCCESS);
  CHECK(xrStringToPath(fx.instance, "/user//hand", &path) == XR_ERROR_PATH_FORMAT_INVALID);
  CHECK(xrStringToPath(fx.instance, "/User/hand", &path) == XR_ERROR_PATH_FORMAT_INVALID);
  CHECK(xrStringToPath(fx.instance, "/user/hand/", &path) == XR_ERROR_PATH_FORMAT_INVALID);

  XrSystemGetInfo handheld{XR_TYPE_SYSTEM_GET_INFO};
  handheld.formFactor = XR_FORM_FACTOR_HANDHELD_DISPLAY;
  XrSystemId system = 0;
  CHECK(xrGetSystem(fx.instance, &handheld, &system) == XR_ERROR_FORM_FACTOR_UNSUPPORTED);

  // Two-call idiom.
  std::uint32_t count = 0;
  REQUIRE(xrEnumerateViewConfigurations(fx.instance, fx.system, 0, &count, nullptr) == XR_SUCCESS);
  CHECK(count == 1);
  std::vector<XrViewConfigurationView> views(1, {XR_TYPE_VIEW_CONFIGURATION_VIEW});
  CHECK(xrEnumerateViewConfigurationViews(fx.instance, fx.system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO, 1, &count,
                                          views.data()) == XR_ERROR_SIZE_INSUFFICIENT);
  CHECK(count == 2);
}

TEST_CASE("xrsim session needs the graphics requirements call and follows the state machine") {
  {
    Fixture noRequirements(false);
    XrSession session = XR_NULL_HANDLE;
    CHECK(noRequirements.createSession(session) == XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING);
  }
  Fixture fx;
  XrSession session = XR_NULL_HANDLE;
  REQUIRE(fx.createSession(session) == XR_SUCCESS);
  CHECK(fx.nextState() == XR_SESSION_STATE_IDLE);
  CHECK(fx.nextState() == XR_SESSION_STATE_READY);
  XrFrameState frameState{XR_TYPE_FRAME_STATE};
  CHECK(xrWaitFrame(session, nullptr, &frameState) == XR_ERROR_SESSION_NOT_RUNNING);
  CHECK(xrEndSession(session) == XR_ERROR_SESSION_NOT_RUNNING);

  XrSessionBeginInfo begin{XR_TYPE_SESSION_BEGIN_INFO};
  begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO;
  CHECK(xrBeginSession(session, &begin) == XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED);
  begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  REQUIRE(xrBeginSession(session, &begin) == XR_SUCCESS);
  CHECK(xrBeginSession(session, &begin) == XR_ERROR_SESSION_RUNNING);

  // Frame call order.
  CHECK(xrBeginFrame(session, nullptr) == XR_ERROR_CALL_ORDER_INVALID);
  XrFrameEndInfo end{XR_TYPE_FRAME_END_INFO};
  end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  REQUIRE(xrWaitFrame(session, nullptr, &frameState) == XR_SUCCESS);
  CHECK(fx.nextState() == XR_SESSION_STATE_SYNCHRONIZED);
  CHECK(frameState.shouldRender == XR_FALSE);
  CHECK(frameState.predictedDisplayPeriod > 0);
  end.displayTime = frameState.predictedDisplayTime;
  CHECK(xrEndFrame(session, &end) == XR_ERROR_CALL_ORDER_INVALID);
  REQUIRE(xrBeginFrame(session, nullptr) == XR_SUCCESS);
  XrFrameEndInfo wrong = end;
  wrong.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_ADDITIVE;
  CHECK(xrEndFrame(session, &wrong) == XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED);
  REQUIRE(xrEndFrame(session, &end) == XR_SUCCESS);
  CHECK(fx.nextState() == XR_SESSION_STATE_VISIBLE);
  CHECK(fx.nextState() == XR_SESSION_STATE_FOCUSED);
  const XrTime firstTime = frameState.predictedDisplayTime;
  REQUIRE(xrWaitFrame(session, nullptr, &frameState) == XR_SUCCESS);
  CHECK(frameState.shouldRender == XR_TRUE);
  CHECK(frameState.predictedDisplayTime > firstTime);
  REQUIRE(xrBeginFrame(session, nullptr) == XR_SUCCESS);
  end.displayTime = frameState.predictedDisplayTime;
  REQUIRE(xrEndFrame(session, &end) == XR_SUCCESS);

  // Ending needs STOPPING first; an exit request walks down to it, then IDLE and EXITING.
  CHECK(xrEndSession(session) == XR_ERROR_SESSION_NOT_STOPPING);
  REQUIRE(xrRequestExitSession(session) == XR_SUCCESS);
  CHECK(fx.nextState() == XR_SESSION_STATE_VISIBLE);
  CHECK(fx.nextState() == XR_SESSION_STATE_SYNCHRONIZED);
  CHECK(fx.nextState() == XR_SESSION_STATE_STOPPING);
  REQUIRE(xrEndSession(session) == XR_SUCCESS);
  CHECK(fx.nextState() == XR_SESSION_STATE_IDLE);
  CHECK(fx.nextState() == XR_SESSION_STATE_EXITING);
  CHECK(xrDestroySession(session) == XR_SUCCESS);
}

TEST_CASE("xrsim swapchains enforce acquire wait release order and reject unknown formats") {
  Fixture fx;
  XrSession session = XR_NULL_HANDLE;
  REQUIRE(fx.createSession(session) == XR_SUCCESS);
  std::uint32_t count = 0;
  REQUIRE(xrEnumerateSwapchainFormats(session, 0, &count, nullptr) == XR_SUCCESS);
  std::vector<std::int64_t> formats(count);
  REQUIRE(xrEnumerateSwapchainFormats(session, count, &count, formats.data()) == XR_SUCCESS);
  REQUIRE(!formats.empty());
  CHECK(formats[0] == VK_FORMAT_R8G8B8A8_SRGB);  // sRGB first, as a compositor prefers
  CHECK(std::find(formats.begin(), formats.end(), VK_FORMAT_D32_SFLOAT) != formats.end());

  XrSwapchainCreateInfo info{XR_TYPE_SWAPCHAIN_CREATE_INFO};
  info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT;
  info.format = VK_FORMAT_R5G6B5_UNORM_PACK16;
  info.sampleCount = info.faceCount = info.arraySize = info.mipCount = 1;
  info.width = info.height = 64;
  XrSwapchain swapchain = XR_NULL_HANDLE;
  CHECK(xrCreateSwapchain(session, &info, &swapchain) == XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED);
  info.format = formats[0];
  REQUIRE(xrCreateSwapchain(session, &info, &swapchain) == XR_SUCCESS);
  REQUIRE(xrEnumerateSwapchainImages(swapchain, 0, &count, nullptr) == XR_SUCCESS);
  std::vector<XrSwapchainImageVulkan2KHR> images(count, {XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR});
  REQUIRE(xrEnumerateSwapchainImages(swapchain, count, &count, reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())) == XR_SUCCESS);
  for (const auto& image : images) CHECK(image.image != VK_NULL_HANDLE);

  XrSwapchainImageWaitInfo wait{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO};
  wait.timeout = XR_INFINITE_DURATION;
  CHECK(xrWaitSwapchainImage(swapchain, &wait) == XR_ERROR_CALL_ORDER_INVALID);
  CHECK(xrReleaseSwapchainImage(swapchain, nullptr) == XR_ERROR_CALL_ORDER_INVALID);
  std::uint32_t index = 99;
  REQUIRE(xrAcquireSwapchainImage(swapchain, nullptr, &index) == XR_SUCCESS);
  CHECK(index < count);
  CHECK(xrReleaseSwapchainImage(swapchain, nullptr) == XR_ERROR_CALL_ORDER_INVALID);  // not waited yet
  REQUIRE(xrWaitSwapchainImage(swapchain, &wait) == XR_SUCCESS);
  REQUIRE(xrReleaseSwapchainImage(swapchain, nullptr) == XR_SUCCESS);
  CHECK(xrDestroySwapchain(swapchain) == XR_SUCCESS);
  CHECK(xrDestroySession(session) == XR_SUCCESS);
}

TEST_CASE("xrsim refuses a bad setting or script at xrCreateInstance and names it") {
  const auto dir = vt::test::outputDir("xrsim_bad_config");
  setenv("XR_RUNTIME_JSON", VT_XRSIM_MANIFEST, 1);
  const char* extensions[] = {XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME};
  XrInstanceCreateInfo info{XR_TYPE_INSTANCE_CREATE_INFO};
  std::snprintf(info.applicationInfo.applicationName, sizeof(info.applicationInfo.applicationName), "xrsim-test");
  info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  info.enabledExtensionCount = 1;
  info.enabledExtensionNames = extensions;
  XrInstance instance = XR_NULL_HANDLE;

  setenv("XRSIM_FRAMES", "many", 1);
  CHECK(xrCreateInstance(&info, &instance) == XR_ERROR_INITIALIZATION_FAILED);
  unsetenv("XRSIM_FRAMES");

  {
    std::FILE* script = std::fopen((dir / "script.json").c_str(), "w");
    REQUIRE(script);
    std::fputs(R"({"keyframes": [{"t": 0, "right": {"joints": [{"position": [0, 0, 0]}]}}]})", script);
    std::fclose(script);
  }
  setenv("XRSIM_SCRIPT", (dir / "script.json").c_str(), 1);
  CHECK(xrCreateInstance(&info, &instance) == XR_ERROR_INITIALIZATION_FAILED);  // 1 joint, not 26
  unsetenv("XRSIM_SCRIPT");

  const char* unknown[] = {"XR_KHR_no_such_extension"};
  info.enabledExtensionNames = unknown;
  CHECK(xrCreateInstance(&info, &instance) == XR_ERROR_EXTENSION_NOT_PRESENT);
  info.enabledExtensionNames = extensions;
  REQUIRE(xrCreateInstance(&info, &instance) == XR_SUCCESS);
  CHECK(xrDestroyInstance(instance) == XR_SUCCESS);
}

TEST_CASE("xrsim vive tracker is announced at xrBeginSession and its action space follows the script") {
  const auto dir = vt::test::outputDir("xrsim_vive_tracker_session");
  {
    std::FILE* script = std::fopen((dir / "script.json").c_str(), "w");
    REQUIRE(script);
    std::fputs(R"({"keyframes": [{"t": 0, "tracker": {"position": [0.1, 1, -0.4]}},
                                 {"t": 1, "tracker": {"position": [0.3, 1, -0.4]}}]})", script);
    std::fclose(script);
  }
  setenv("XRSIM_SCRIPT", (dir / "script.json").c_str(), 1);
  Fixture fx(true, XR_HTCX_VIVE_TRACKER_INTERACTION_EXTENSION_NAME);
  unsetenv("XRSIM_SCRIPT");
  XrSession session = XR_NULL_HANDLE;
  REQUIRE(fx.createSession(session) == XR_SUCCESS);

  const vt::test::TrackerPoseAction tracker =
      vt::test::suggestTrackerPose(fx.instance, "/user/vive_tracker_htcx/role/handheld_object/input/grip/pose");
  REQUIRE(tracker.suggested == XR_SUCCESS);
  XrActionSet set = tracker.set;
  const XrAction action = tracker.action;
  XrSessionActionSetsAttachInfo attach{XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO};
  attach.countActionSets = 1;
  attach.actionSets = &set;
  REQUIRE(xrAttachSessionActionSets(session, &attach) == XR_SUCCESS);
  XrActionSpaceCreateInfo spaceInfo{XR_TYPE_ACTION_SPACE_CREATE_INFO};
  spaceInfo.action = action;
  spaceInfo.poseInActionSpace.orientation.w = 1.0f;
  XrSpace trackerSpace = XR_NULL_HANDLE, stage = XR_NULL_HANDLE;
  REQUIRE(xrCreateActionSpace(session, &spaceInfo, &trackerSpace) == XR_SUCCESS);
  XrReferenceSpaceCreateInfo stageInfo{XR_TYPE_REFERENCE_SPACE_CREATE_INFO};
  stageInfo.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_STAGE;
  stageInfo.poseInReferenceSpace.orientation.w = 1.0f;
  REQUIRE(xrCreateReferenceSpace(session, &stageInfo, &stage) == XR_SUCCESS);

  XrSessionBeginInfo begin{XR_TYPE_SESSION_BEGIN_INFO};
  begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  REQUIRE(xrBeginSession(session, &begin) == XR_SUCCESS);
  int connected = 0;
  XrEventDataBuffer event{XR_TYPE_EVENT_DATA_BUFFER};
  while (xrPollEvent(fx.instance, &event) == XR_SUCCESS) {
    if (event.type == XR_TYPE_EVENT_DATA_VIVE_TRACKER_CONNECTED_HTCX) {
      ++connected;
      const XrViveTrackerPathsHTCX* paths = reinterpret_cast<XrEventDataViveTrackerConnectedHTCX&>(event).paths;
      REQUIRE(paths != nullptr);
      char text[XR_MAX_PATH_LENGTH] = {};
      std::uint32_t count = 0;
      REQUIRE(xrPathToString(fx.instance, paths->rolePath, sizeof(text), &count, text) == XR_SUCCESS);
      CHECK(std::strcmp(text, "/user/vive_tracker_htcx/role/handheld_object") == 0);
    }
    event = {XR_TYPE_EVENT_DATA_BUFFER};
  }
  CHECK(connected == 1);

  // One frame to reach FOCUSED, then the tracker's pose action is active and its space located.
  XrFrameState frameState{XR_TYPE_FRAME_STATE};
  REQUIRE(xrWaitFrame(session, nullptr, &frameState) == XR_SUCCESS);
  REQUIRE(xrBeginFrame(session, nullptr) == XR_SUCCESS);
  XrFrameEndInfo end{XR_TYPE_FRAME_END_INFO};
  end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  end.displayTime = frameState.predictedDisplayTime;
  REQUIRE(xrEndFrame(session, &end) == XR_SUCCESS);
  XrActiveActionSet active{set, XR_NULL_PATH};
  XrActionsSyncInfo sync{XR_TYPE_ACTIONS_SYNC_INFO};
  sync.countActiveActionSets = 1;
  sync.activeActionSets = &active;
  REQUIRE(xrSyncActions(session, &sync) == XR_SUCCESS);
  XrActionStateGetInfo get{XR_TYPE_ACTION_STATE_GET_INFO};
  get.action = action;
  XrActionStatePose state{XR_TYPE_ACTION_STATE_POSE};
  REQUIRE(xrGetActionStatePose(session, &get, &state) == XR_SUCCESS);
  CHECK(state.isActive == XR_TRUE);

  // Half a second apart the tracker moved 0.1 m along +X (linear between the keyframes).
  XrSpaceLocation first{XR_TYPE_SPACE_LOCATION}, later{XR_TYPE_SPACE_LOCATION};
  const XrTime t = frameState.predictedDisplayTime;
  REQUIRE(xrLocateSpace(trackerSpace, stage, t, &first) == XR_SUCCESS);
  REQUIRE(xrLocateSpace(trackerSpace, stage, t + 500'000'000, &later) == XR_SUCCESS);
  CHECK((first.locationFlags & XR_SPACE_LOCATION_POSITION_VALID_BIT) != 0);
  CHECK(first.pose.position.x >= 0.1f);
  CHECK(first.pose.position.x < 0.12f);
  CHECK(later.pose.position.x - first.pose.position.x == Approx(0.1f).margin(1e-4));
  CHECK(later.pose.position.y == Approx(1.0f).margin(1e-5));
  CHECK(later.pose.position.z == Approx(-0.4f).margin(1e-5));
  CHECK(xrDestroySession(session) == XR_SUCCESS);
}
