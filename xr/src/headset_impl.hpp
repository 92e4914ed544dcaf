#pragma once
// Headset internals shared by headset.cpp (creation) and frame_loop.cpp (events and frames).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "hand_input.hpp"
#include "vt/renderer/external_target.hpp"
#include "vt/xr/headset.hpp"
#include "vt/xr/openxr_ext_haptic_parametric.hpp"
#include "vt/xr/openxr_fb_haptics.hpp"
#include "xr_check.hpp"

namespace vt::xr {

struct EyeSwapchain {
  XrSwapchain handle = XR_NULL_HANDLE;
  XrSwapchain depthHandle = XR_NULL_HANDLE;  // XR_KHR_composition_layer_depth only
  std::unique_ptr<renderer::ExternalTarget> target;
  XrExtent2Di extent{};
};

struct Headset::Impl {
  HeadsetOptions options;
  XrInstance instance = XR_NULL_HANDLE;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  XrSession session = XR_NULL_HANDLE;
  XrSpace appSpace = XR_NULL_HANDLE;  // STAGE when offered, else LOCAL
  XrSpace viewSpace = XR_NULL_HANDLE;  // the head, located in appSpace to place the scene
  bool stage = false;                  // appSpace is STAGE (floor at y = 0)
  bool placed = false;                 // the scene sits in front of the head (placeAtHead)
  bool jumpPending = false;            // the next published hand poses follow a new placement
  std::uint64_t placements = 0;
  std::shared_ptr<renderer::Device> device;
  std::array<EyeSwapchain, 2> eyes;
  std::unique_ptr<HandInput> input;
  std::string runtimeName;
  bool handTracking = false;
  bool extraVulkanExtensions = false;  // HeadsetOptions' extra Vulkan extensions are enabled
  bool depthOffered = false;  // XR_KHR_composition_layer_depth enabled on the instance
  ControllerHaptics controllerHaptics = ControllerHaptics::Rumble;  // richest haptics extension enabled
  bool pcmEnabled = false, parametricEnabled = false, envelopeEnabled = false;
  std::array<ControllerHaptics, 2> handHaptics{ControllerHaptics::Rumble, ControllerHaptics::Rumble};
  std::array<ParametricProperties, 2> parametric{};
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;  // of the depth swapchains; UNDEFINED = none submitted
  XrSessionState state = XR_SESSION_STATE_UNKNOWN;
  bool running = false;
  bool exiting = false;
  bool lost = false;
  std::uint64_t framesRendered = 0;
  XrDuration displayPeriod = 11'111'111;
  glm::mat4 T_world_app{1.0f};  // scene world from the app space

  ~Impl();
  /// xrApplyHapticFeedback with `feedback` on `hand`, loss noted for pollEvents, else checked.
  void applyHaptics(int hand, const XrHapticBaseHeader* feedback);
  /// Picks each controller's haptics (controller_haptics.cpp); needs `input`.
  void chooseControllerHaptics();
  void destroySession() noexcept;
};

}  // namespace vt::xr
