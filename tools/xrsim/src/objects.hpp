#pragma once
// The runtime's objects behind each OpenXR handle, and the registry that validates handles.
// Every API entry point holds g_mutex (see api.hpp), so these are never touched concurrently.
#include <time.h>
#include <vulkan/vulkan.h>
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <array>
#include <deque>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "config.hpp"
#include "script.hpp"

namespace xrsim {

/// Base of every handle object; constructing registers the handle, destroying unregisters it.
struct Object {
  explicit Object(XrObjectType objectType);
  virtual ~Object();
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  const XrObjectType type;
};

/// True when `p` is a live object (checked before any dereference).
bool isLive(const void* p) noexcept;

/// The live object of type T behind a handle, or nullptr (wrong type, destroyed, garbage).
template <class T, class Handle>
T* lookup(Handle handle) noexcept {
  auto* object = reinterpret_cast<Object*>(handle);
  if (!isLive(object) || object->type != T::kType) return nullptr;
  return static_cast<T*>(object);
}

template <class T>
auto handleOf(T* object) noexcept {
  return reinterpret_cast<typename T::Handle>(object);
}

struct Instance;
struct Session;
struct Action;

struct Binding {
  Action* action = nullptr;
  XrPath path = XR_NULL_PATH;
};

struct ActionSet final : Object {
  using Handle = XrActionSet;
  static constexpr XrObjectType kType = XR_OBJECT_TYPE_ACTION_SET;
  ActionSet() : Object(kType) {}
  Instance* instance = nullptr;
  std::string name, localizedName;
  std::uint32_t priority = 0;
  bool attached = false;
  std::vector<std::unique_ptr<Action>> actions;
};

/// Slots of per-action state: 0 = no subaction path (all bindings), 1 = left hand, 2 = right hand.
inline constexpr int kStateSlots = 3;

struct ActionState {
  bool active = false;
  float value = 0.0f;
  glm::vec2 axes{0.0f};
  bool changed = false;
  XrTime lastChange = 0;
};

struct Action final : Object {
  using Handle = XrAction;
  static constexpr XrObjectType kType = XR_OBJECT_TYPE_ACTION;
  Action() : Object(kType) {}
  ActionSet* set = nullptr;
  std::string name, localizedName;
  XrActionType actionType = XR_ACTION_TYPE_BOOLEAN_INPUT;
  std::vector<XrPath> subactions;
  std::array<ActionState, kStateSlots> state{};
};

struct Swapchain final : Object {
  using Handle = XrSwapchain;
  static constexpr XrObjectType kType = XR_OBJECT_TYPE_SWAPCHAIN;
  Swapchain() : Object(kType) {}
  ~Swapchain() override;
  Session* session = nullptr;
  XrSwapchainCreateInfo info{};
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspect = 0;
  std::vector<VkImage> images;
  std::vector<VkDeviceMemory> memory;
  std::deque<std::uint32_t> acquired;  // acquired, not yet released, oldest first
  bool waited = false;                 // the oldest acquired image has been waited on
  std::uint32_t nextIndex = 0;
  std::int64_t lastReleased = -1;
};

struct Space final : Object {
  using Handle = XrSpace;
  static constexpr XrObjectType kType = XR_OBJECT_TYPE_SPACE;
  Space() : Object(kType) {}
  Session* session = nullptr;
  bool isAction = false;
  XrReferenceSpaceType referenceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
  Action* action = nullptr;  // may be destroyed before the space: check isLive
  XrPath subaction = XR_NULL_PATH;
  Pose offset;               // pose in the reference / action space
};

struct HandTracker final : Object {
  using Handle = XrHandTrackerEXT;
  static constexpr XrObjectType kType = XR_OBJECT_TYPE_HAND_TRACKER_EXT;
  HandTracker() : Object(kType) {}
  Session* session = nullptr;
  XrHandEXT hand = XR_HAND_LEFT_EXT;
};

class FrameCapture;
class Commands;

struct Session final : Object {
  using Handle = XrSession;
  static constexpr XrObjectType kType = XR_OBJECT_TYPE_SESSION;
  Session();
  ~Session() override;
  Instance* instance = nullptr;
  // Graphics binding (XR_KHR_vulkan_enable2).
  VkInstance vkInstance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0, queueIndex = 0;
  VkQueue queue = VK_NULL_HANDLE;
  // Lifecycle.
  XrSessionState state = XR_SESSION_STATE_UNKNOWN;
  bool running = false;
  bool exitRequested = false;
  bool lost = false;
  int restartsLeft = 0;
  // Frame loop.
  bool frameWaited = false;  // xrWaitFrame returned, xrBeginFrame not yet called
  bool frameBegun = false;
  std::uint64_t framesWaited = 0, framesEnded = 0;
  XrTime beginTime = 0;      // display time origin of the running session
  XrTime displayTime = 0;    // predicted display time of the newest waited frame
  // Input.
  bool actionSetsAttached = false;
  std::vector<ActionSet*> attachedSets;
  XrPath currentProfile = XR_NULL_PATH;
  bool profileEventSent = false;
  std::vector<std::unique_ptr<Swapchain>> swapchains;
  std::vector<std::unique_ptr<Space>> spaces;
  std::vector<std::unique_ptr<HandTracker>> handTrackers;
  std::unique_ptr<Commands> commands;  // one-shot submissions on the app's queue
  std::unique_ptr<FrameCapture> capture;
  std::ofstream hapticLog;
  /// XR_EXT_haptic_parametric streams, per controller (left, right): running, and the time of
  /// the last amplitude point so far (a frame may not go back before it).
  struct ParametricStream {
    bool running = false;
    XrDuration lastAmplitude_ns = 0;
  };
  std::array<ParametricStream, 2> parametric;
};

struct Instance final : Object {
  using Handle = XrInstance;
  static constexpr XrObjectType kType = XR_OBJECT_TYPE_INSTANCE;
  Instance() : Object(kType) {}
  ~Instance() override;
  Config config;
  Script script;
  std::string applicationName;
  bool handTrackingEnabled = false, depthEnabled = false, vulkan2Enabled = false, viveTrackerEnabled = false,
       timespecEnabled = false;
  bool hapticPcmEnabled = false, hapticEnvelopeEnabled = false;  // XR_FB_haptic_pcm / _amplitude_envelope
  bool hapticParametricEnabled = false;                          // XR_EXT_haptic_parametric
  XrViveTrackerPathsHTCX trackerPaths{};  // what the connected event points at (lives as long as the instance)
  bool lost = false;
  bool requirementsQueried = false;
  VkInstance vkInstance = VK_NULL_HANDLE;          // from xrGetVulkanGraphicsDevice2KHR
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  std::vector<std::string> pathStrings{""};        // XrPath n <-> pathStrings[n]
  std::map<std::string, XrPath> pathIds;
  std::deque<XrEventDataBuffer> events;
  std::map<XrPath, std::vector<Binding>> suggested;  // interaction profile -> bindings
  std::vector<std::unique_ptr<ActionSet>> actionSets;
  std::vector<std::unique_ptr<Session>> sessions;
};

/// The system id of the one simulated headset.
inline constexpr XrSystemId kSystemId = 1;

}  // namespace xrsim
