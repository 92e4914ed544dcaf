#pragma once
// Shared helpers of the entry points: locking, error mapping, handle/struct checks, the
// two-call idiom, paths, events and pose maths. Entry points are declared per source file.
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "objects.hpp"
#include "vt/xr/openxr_ext_haptic_parametric.hpp"
#include "vt/xr/openxr_fb_haptics.hpp"
#include "vt/core/log.hpp"

namespace xrsim {

/// The one lock every entry point holds (apps may call from several threads).
std::recursive_mutex& apiMutex() noexcept;

/// Runs an entry point's body under the lock; exceptions become XR_ERROR_RUNTIME_FAILURE with
/// one line on stderr naming the call.
template <class Body>
XrResult guarded(const char* call, Body&& body) noexcept {
  try {
    std::lock_guard<std::recursive_mutex> lock(apiMutex());
    return body();
  } catch (const std::exception& e) {
    vt::log::error("xrsim: ", call, ": ", e.what());
    return XR_ERROR_RUNTIME_FAILURE;
  } catch (...) {
    return XR_ERROR_RUNTIME_FAILURE;
  }
}

/// Validation of an input/output structure: present and of the expected XrStructureType.
#define XRSIM_CHECK_STRUCT(ptr, structType)                                             \
  do {                                                                                 \
    if ((ptr) == nullptr || (ptr)->type != (structType)) return XR_ERROR_VALIDATION_FAILURE; \
  } while (false)

/// Every live instance (owned here; xrDestroyInstance erases).
std::vector<std::unique_ptr<Instance>>& instanceList();

/// Resolves handles, mapping invalid / lost objects to the spec's error codes.
XrResult findInstance(XrInstance handle, Instance*& out) noexcept;
XrResult findSession(XrSession handle, Session*& out) noexcept;

/// The two-call idiom for arrays of trivially copyable elements.
template <class T>
XrResult twoCall(std::uint32_t capacity, std::uint32_t* countOut, T* out, const std::vector<T>& items) {
  if (countOut == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *countOut = std::uint32_t(items.size());
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < items.size()) return XR_ERROR_SIZE_INSUFFICIENT;
  if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (std::size_t i = 0; i < items.size(); ++i) out[i] = items[i];
  return XR_SUCCESS;
}
/// The two-call idiom for strings (the count includes the terminating zero).
XrResult twoCallString(std::uint32_t capacity, std::uint32_t* countOut, char* out, const std::string& text);

/// Now on the runtime's clock (XrTime = steady-clock nanoseconds).
XrTime now() noexcept;

/// Paths: interned per instance. wellFormedPath follows the spec's path grammar.
bool wellFormedPath(const std::string& path) noexcept;
XrPath internPath(Instance& instance, const std::string& path);
/// The string of a path, or nullptr for XR_NULL_PATH / unknown values.
const std::string* pathString(const Instance& instance, XrPath path) noexcept;

/// Queues an event for xrPollEvent.
void pushEvent(Instance& instance, const XrEventDataBuffer& event);
/// Changes the session state and queues XrEventDataSessionStateChanged.
void setState(Session& session, XrSessionState state);

/// Scripted user state at an XrTime of this session.
Sample sampleAt(const Session& session, XrTime time);
/// Pose of a space in the stage frame at `time`; false when not tracked.
bool spacePose(Session& session, const Space& space, XrTime time, Pose& out);

Pose fromXr(const XrPosef& pose) noexcept;
XrPosef toXr(const Pose& pose) noexcept;
Pose compose(const Pose& a, const Pose& b) noexcept;  // a * b
Pose inverse(const Pose& a) noexcept;
/// True for a unit quaternion (within the spec's tolerance), as xrCreate*Space require.
bool validPose(const XrPosef& pose) noexcept;

/// Hand index (0 left, 1 right) of a path under /user/hand/left|right, else -1.
int handOfPath(const std::string& path) noexcept;

// ---- entry points (XRAPI_CALL), grouped by source file ----
// instance.cpp
XrResult XRAPI_CALL enumerateInstanceExtensionProperties(const char*, std::uint32_t, std::uint32_t*, XrExtensionProperties*);
XrResult XRAPI_CALL enumerateApiLayerProperties(std::uint32_t, std::uint32_t*, XrApiLayerProperties*);
XrResult XRAPI_CALL createInstance(const XrInstanceCreateInfo*, XrInstance*);
XrResult XRAPI_CALL destroyInstance(XrInstance);
XrResult XRAPI_CALL getInstanceProperties(XrInstance, XrInstanceProperties*);
XrResult XRAPI_CALL pollEvent(XrInstance, XrEventDataBuffer*);
XrResult XRAPI_CALL resultToString(XrInstance, XrResult, char*);
XrResult XRAPI_CALL structureTypeToString(XrInstance, XrStructureType, char*);
XrResult XRAPI_CALL stringToPath(XrInstance, const char*, XrPath*);
XrResult XRAPI_CALL pathToString(XrInstance, XrPath, std::uint32_t, std::uint32_t*, char*);
// system.cpp
XrResult XRAPI_CALL getSystem(XrInstance, const XrSystemGetInfo*, XrSystemId*);
XrResult XRAPI_CALL getSystemProperties(XrInstance, XrSystemId, XrSystemProperties*);
XrResult XRAPI_CALL enumerateEnvironmentBlendModes(XrInstance, XrSystemId, XrViewConfigurationType, std::uint32_t, std::uint32_t*, XrEnvironmentBlendMode*);
XrResult XRAPI_CALL enumerateViewConfigurations(XrInstance, XrSystemId, std::uint32_t, std::uint32_t*, XrViewConfigurationType*);
XrResult XRAPI_CALL getViewConfigurationProperties(XrInstance, XrSystemId, XrViewConfigurationType, XrViewConfigurationProperties*);
XrResult XRAPI_CALL enumerateViewConfigurationViews(XrInstance, XrSystemId, XrViewConfigurationType, std::uint32_t, std::uint32_t*, XrViewConfigurationView*);
XrResult checkSystem(const Instance& instance, XrSystemId system) noexcept;
// session.cpp
XrResult XRAPI_CALL createSession(XrInstance, const XrSessionCreateInfo*, XrSession*);
XrResult XRAPI_CALL destroySession(XrSession);
XrResult XRAPI_CALL beginSession(XrSession, const XrSessionBeginInfo*);
XrResult XRAPI_CALL endSession(XrSession);
XrResult XRAPI_CALL requestExitSession(XrSession);
// frame.cpp
XrResult XRAPI_CALL waitFrame(XrSession, const XrFrameWaitInfo*, XrFrameState*);
XrResult XRAPI_CALL beginFrame(XrSession, const XrFrameBeginInfo*);
XrResult XRAPI_CALL endFrame(XrSession, const XrFrameEndInfo*);
XrResult XRAPI_CALL locateViews(XrSession, const XrViewLocateInfo*, XrViewState*, std::uint32_t, std::uint32_t*, XrView*);
// space.cpp
XrResult XRAPI_CALL enumerateReferenceSpaces(XrSession, std::uint32_t, std::uint32_t*, XrReferenceSpaceType*);
XrResult XRAPI_CALL createReferenceSpace(XrSession, const XrReferenceSpaceCreateInfo*, XrSpace*);
XrResult XRAPI_CALL getReferenceSpaceBoundsRect(XrSession, XrReferenceSpaceType, XrExtent2Df*);
XrResult XRAPI_CALL createActionSpace(XrSession, const XrActionSpaceCreateInfo*, XrSpace*);
XrResult XRAPI_CALL locateSpace(XrSpace, XrSpace, XrTime, XrSpaceLocation*);
XrResult XRAPI_CALL destroySpace(XrSpace);
// swapchain.cpp
XrResult XRAPI_CALL enumerateSwapchainFormats(XrSession, std::uint32_t, std::uint32_t*, std::int64_t*);
XrResult XRAPI_CALL createSwapchain(XrSession, const XrSwapchainCreateInfo*, XrSwapchain*);
XrResult XRAPI_CALL destroySwapchain(XrSwapchain);
XrResult XRAPI_CALL enumerateSwapchainImages(XrSwapchain, std::uint32_t, std::uint32_t*, XrSwapchainImageBaseHeader*);
XrResult XRAPI_CALL acquireSwapchainImage(XrSwapchain, const XrSwapchainImageAcquireInfo*, std::uint32_t*);
XrResult XRAPI_CALL waitSwapchainImage(XrSwapchain, const XrSwapchainImageWaitInfo*);
XrResult XRAPI_CALL releaseSwapchainImage(XrSwapchain, const XrSwapchainImageReleaseInfo*);
// actions.cpp
XrResult XRAPI_CALL createActionSet(XrInstance, const XrActionSetCreateInfo*, XrActionSet*);
XrResult XRAPI_CALL destroyActionSet(XrActionSet);
XrResult XRAPI_CALL createAction(XrActionSet, const XrActionCreateInfo*, XrAction*);
XrResult XRAPI_CALL destroyAction(XrAction);
XrResult XRAPI_CALL suggestInteractionProfileBindings(XrInstance, const XrInteractionProfileSuggestedBinding*);
XrResult XRAPI_CALL attachSessionActionSets(XrSession, const XrSessionActionSetsAttachInfo*);
XrResult XRAPI_CALL getCurrentInteractionProfile(XrSession, XrPath, XrInteractionProfileState*);
XrResult XRAPI_CALL enumerateBoundSourcesForAction(XrSession, const XrBoundSourcesForActionEnumerateInfo*, std::uint32_t, std::uint32_t*, XrPath*);
XrResult XRAPI_CALL getInputSourceLocalizedName(XrSession, const XrInputSourceLocalizedNameGetInfo*, std::uint32_t, std::uint32_t*, char*);
/// Bindings of `action` in the session's current interaction profile (for one hand, or all: -1).
std::vector<XrPath> boundPaths(const Session& session, const Action& action, int hand);
// input.cpp
XrResult XRAPI_CALL syncActions(XrSession, const XrActionsSyncInfo*);
XrResult XRAPI_CALL getActionStateBoolean(XrSession, const XrActionStateGetInfo*, XrActionStateBoolean*);
XrResult XRAPI_CALL getActionStateFloat(XrSession, const XrActionStateGetInfo*, XrActionStateFloat*);
XrResult XRAPI_CALL getActionStateVector2f(XrSession, const XrActionStateGetInfo*, XrActionStateVector2f*);
XrResult XRAPI_CALL getActionStatePose(XrSession, const XrActionStateGetInfo*, XrActionStatePose*);
XrResult XRAPI_CALL applyHapticFeedback(XrSession, const XrHapticActionInfo*, const XrHapticBaseHeader*);
XrResult XRAPI_CALL stopHapticFeedback(XrSession, const XrHapticActionInfo*);
/// XR_FB_haptic_pcm: the rate xrsim reports for its simulated controller motor.
inline constexpr float kPcmSampleRate_hz = 2000.0f;
XrResult XRAPI_CALL getDeviceSampleRate(XrSession, const XrHapticActionInfo*, XrDevicePcmSampleRateGetInfoFB*);
/// XR_EXT_haptic_parametric: the simulated controller motor's streaming timing and frequency range.
XrResult XRAPI_CALL hapticParametricGetProperties(XrSession, const XrHapticActionInfo*, XrHapticParametricPropertiesEXT*);
// hand_tracking.cpp
XrResult XRAPI_CALL createHandTracker(XrSession, const XrHandTrackerCreateInfoEXT*, XrHandTrackerEXT*);
XrResult XRAPI_CALL destroyHandTracker(XrHandTrackerEXT);
XrResult XRAPI_CALL locateHandJoints(XrHandTrackerEXT, const XrHandJointsLocateInfoEXT*, XrHandJointLocationsEXT*);
// time_conversion.cpp (XR_KHR_convert_timespec_time): XrTime is CLOCK_MONOTONIC in nanoseconds.
XrResult XRAPI_CALL convertTimespecTimeToTime(XrInstance, const struct timespec*, XrTime*);
XrResult XRAPI_CALL convertTimeToTimespecTime(XrInstance, XrTime, struct timespec*);
// vive_tracker.cpp (XR_HTCX_vive_tracker_interaction)
XrResult XRAPI_CALL enumerateViveTrackerPaths(XrInstance, std::uint32_t, std::uint32_t*, XrViveTrackerPathsHTCX*);
/// Queues the tracker-connected event (when the extension is enabled and the script has a tracker).
void announceTracker(Session& session);
/// Whether `action` is bound to the scripted tracker's grip pose (role or persistent path)
/// in /interaction_profiles/htc/vive_tracker_htcx, with the extension enabled.
bool trackerBound(const Session& session, const Action& action);
// vulkan.cpp
XrResult XRAPI_CALL getVulkanGraphicsRequirements2(XrInstance, XrSystemId, XrGraphicsRequirementsVulkanKHR*);
XrResult XRAPI_CALL createVulkanInstance(XrInstance, const XrVulkanInstanceCreateInfoKHR*, VkInstance*, VkResult*);
XrResult XRAPI_CALL getVulkanGraphicsDevice2(XrInstance, const XrVulkanGraphicsDeviceGetInfoKHR*, VkPhysicalDevice*);
XrResult XRAPI_CALL createVulkanDevice(XrInstance, const XrVulkanDeviceCreateInfoKHR*, VkDevice*, VkResult*);

}  // namespace xrsim
