#pragma once
// The headset path: an OpenXR instance + session whose runtime creates the Vulkan instance and
// device (XR_KHR_vulkan_enable2) that the renderer then uses; per-eye colour swapchains (with
// depth swapchains submitted through XR_KHR_composition_layer_depth when the runtime offers it)
// drawn through the renderer's external-image target; the session state machine; hand poses from
// XR_EXT_hand_tracking or controllers published into the desktop mode's pose channel.
// No OpenXR types here: the app and tests see plain V-Touching types. Main (render) thread only.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "vt/core/latest_value.hpp"
#include "vt/renderer/device.hpp"
#include "vt/renderer/render_target.hpp"
#include "vt/scene/camera.hpp"
#include "vt/scene/hand.hpp"
#include "vt/scene/pose_history.hpp"

namespace vt::xr {

/// Why the headset path cannot be used (the app then continues in desktop mode).
enum class Unavailable { None, NoRuntime, NoHmd, SessionRefused };

/// What the controllers can play: a fixed-frequency rumble (core OpenXR), an amplitude envelope
/// (XR_FB_haptic_amplitude_envelope), amplitude and frequency curves (XR_EXT_haptic_parametric)
/// or a PCM waveform (XR_FB_haptic_pcm).
enum class ControllerHaptics { Rumble, AmplitudeEnvelope, Parametric, Pcm };

/// "PCM", "parametric", "envelope" or "rumble" (logs, status lines).
std::string_view controllerHapticsName(ControllerHaptics haptics) noexcept;

/// One point of a parametric curve: `value` 0..1 at `time_ns` since the haptic event began.
struct ParametricPoint {
  std::int64_t time_ns = 0;
  float value = 0.0f;
};
/// Where a parametric call stands in its stream (XrHapticParametricStreamFrameTypeEXT).
enum class ParametricFrame { Whole, First, Intermediate, Last };
/// A controller's parametric timing (XrHapticParametricPropertiesEXT).
struct ParametricProperties {
  std::int64_t idealFrameSubmission_ns = 0;
  std::int64_t minimumFirstFrame_ns = 0;
  float minFrequency_hz = 0.0f, maxFrequency_hz = 0.0f;
};

struct HeadsetOptions {
  std::string applicationName = "V-Touching";
  bool validate = false;           // Vulkan validation layer on the runtime-created instance
  bool preferHandTracking = true;  // XR_EXT_hand_tracking when the system has it, else controllers
  /// Where the scene's origin (the table-top centre) sits in the XR stage space until the head
  /// is first located, and always when placeAtHead is false (LOCAL: 1.6 m lower).
  glm::mat4 T_stage_world{1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f,
                          0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.75f, -0.45f, 1.0f};
  /// Place the scene in front of the head (sceneInFrontOfHead) at the first frame the head is
  /// located, and again after recenter() or the runtime's own re-centre.
  bool placeAtHead = true;
  /// A standing user's workbench (docs/app.md "Where the table is"): the table-top centre within
  /// forearm reach ahead of the eyes along the head's yaw, the top at elbow height (about 0.55 m
  /// below an adult's eyes: fine tactile work is done there), so a user looking down at it, about
  /// 50 degrees, has it in the middle of the view.
  float tableAhead_m = 0.45f;
  float tableBelowEyes_m = 0.55f;
  /// STAGE (the floor known): the table top's height above the floor stays within these (a
  /// seated user's 0.7 m desk up to a tall user's bench), whatever the head's tracked height.
  float tableMinHeight_m = 0.7f, tableMaxHeight_m = 1.2f;
  float near_m = 0.02f, far_m = 20.0f;
  /// XR_HTCX_vive_tracker_interaction when offered: a tracker in `trackerRole` worn on the back
  /// of the right hand gives its gross pose whenever hand tracking has no joints (see docs/xrsim.md).
  bool useTracker = true;
  std::string trackerRole = "handheld_object";
  /// The glove's finger flexion for the tracked hand (read by the render thread); nullptr or
  /// no value yet = the controller's trigger/squeeze curls.
  const LatestValue<FingerCurls>* gloveCurls = nullptr;
  /// Hand poses in scene (world) coordinates go here, left then right, stamped with the time
  /// they were located for; nullptr = not published. Their one writer is a sampler thread that
  /// asks the runtime every millisecond for the hands at now + setHandLookahead() (with
  /// XR_KHR_convert_timespec_time), else the render thread at each frame's display time.
  std::array<PoseHistory*, 2> handOutputs{};
  /// Extra Vulkan extensions for the runtime-created instance and device (a desktop mirror
  /// window's: renderer::addWindowExtensions). Refused ones: the device is made without any extra.
  std::vector<std::string> vulkanInstanceExtensions, vulkanDeviceExtensions;
};

/// Where the session is, as the app's loop needs it.
enum class SessionPhase {
  Idle,         // not running (waiting for READY): poll again later, render nothing
  Running,      // call frame()
  Exiting,      // the runtime ended the session for good: leave headset mode
  LossPending,  // session or instance lost: destroy the Headset, open() again to restart
};

/// Draws one eye: build a FrameDesc with this view and render into `target`.
using RenderEyeFn = std::function<void(int eye, const CameraView& view, renderer::RenderTarget& target)>;

class Headset {
 public:
  struct OpenResult {
    std::unique_ptr<Headset> headset;  // null when unavailable
    Unavailable reason = Unavailable::None;
    std::string message;               // one line saying which (and the OpenXR result)
  };
  /// Creates instance, system, Vulkan device, session, swapchains and input. Never throws for
  /// the expected absences (no runtime, no HMD, refused session): they come back as `reason`.
  static OpenResult open(const HeadsetOptions& options);
  ~Headset();
  Headset(const Headset&) = delete;
  Headset& operator=(const Headset&) = delete;

  /// The device the runtime created; give it to renderer::Renderer.
  const std::shared_ptr<renderer::Device>& device() const;
  /// Drains OpenXR events: begins the session on READY, ends it on STOPPING, reports exit/loss.
  SessionPhase pollEvents();
  /// One frame: xrWaitFrame, xrBeginFrame, input update at the predicted display time, `render`
  /// per eye only when the runtime says shouldRender, xrEndFrame. False when nothing was rendered.
  bool frame(const RenderEyeFn& render);
  /// Places the scene in front of the head again at the next frame the head is located (the
  /// mirror's R key); the hand poses published right after begin a new pose-history segment.
  void recenter();
  /// Times the scene was placed in front of the head (0 until the head was located).
  std::uint64_t placements() const;
  /// Asks the runtime to end the session (it then goes STOPPING -> EXITING through pollEvents).
  void requestExit();

  /// The current XrSessionState as its OpenXR value (for HUDs and tests).
  int sessionState() const;
  std::string runtimeName() const;
  /// "vive tracker (<role>)" while the tracker poses the right hand, else "hand tracking" or
  /// the current interaction profile path, for the HUD.
  std::string inputSource() const;
  bool handTracking() const;
  /// Whether XR_HTCX_vive_tracker_interaction is enabled and its pose action bound.
  bool viveTracker() const;
  /// Whether frames carry depth: XR_KHR_composition_layer_depth is offered and one of the
  /// runtime's depth swapchain formats suits the renderer.
  bool depthLayers() const;
  /// The depth swapchains' format (VK_FORMAT_UNDEFINED without depth layers).
  VkFormat depthFormat() const;
  /// Whether the device has HeadsetOptions' extra Vulkan extensions (false: they were refused).
  bool extraVulkanExtensions() const;
  std::uint64_t framesRendered() const;
  /// Predicted display period of the last frame (duration of one haptic pulse).
  std::int64_t displayPeriod_ns() const;
  /// The hand (0 left, 1 right) as located for the last frame's display time, stamped with that
  /// time (invalid when untracked): what the eyes show. Render thread.
  HandPose displayHand(int hand) const;
  /// How far past now the haptic side's hand poses are asked for (the felt outputs' latency). Any thread.
  void setHandLookahead(std::int64_t lookahead_ns);
  /// Controller vibration (0 left, 1 right); frequency 0 = runtime's choice.
  void vibrate(int hand, float amplitude, float frequency_hz, std::int64_t duration_ns);
  void stopVibration(int hand);
  /// The richest controller haptics the runtime offered (PCM, else parametric, else envelope,
  /// else rumble).
  ControllerHaptics controllerHaptics() const;
  /// What the controller of `hand` plays: PCM where it reports a PCM rate, else parametric where
  /// it gives parametric properties, else envelope, else rumble (chosen when the session opened).
  ControllerHaptics controllerHaptics(int hand) const;
  /// XR_EXT_haptic_parametric properties of the controller of `hand` (zero unless Parametric).
  ParametricProperties parametricProperties(int hand) const;
  /// XR_EXT_haptic_parametric: amplitude and (normalised, kMinFrequency_hz..kMaxFrequency_hz of
  /// vt/haptics/frequency_scale.hpp) frequency curves, at most 500 points each. Returns false
  /// when the runtime refused the frame (nothing played). Render thread.
  bool vibrateParametric(int hand, const ParametricPoint* amplitude, std::uint32_t amplitudeCount,
                         const ParametricPoint* frequency, std::uint32_t frequencyCount, ParametricFrame frame);
  /// XR_FB_haptic_pcm: queues `samples` (-1..1, at most 4000) at `sampleRate_hz` after what is
  /// playing. Returns the samples the runtime consumed. Render thread.
  std::uint32_t vibratePcm(int hand, const float* samples, std::uint32_t count, float sampleRate_hz);
  /// XR_FB_haptic_amplitude_envelope: `count` amplitudes (0..1, at most 4000) over `duration_ns`.
  void vibrateEnvelope(int hand, const float* amplitudes, std::uint32_t count, std::int64_t duration_ns);

  struct Impl;

 private:
  explicit Headset(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> m_impl;
};

/// T_space_world for a head at T_space_head: the scene origin (table-top centre)
/// options.tableAhead_m ahead of the eyes along the head's yaw (looking straight down: where the
/// top of the head points), options.tableBelowEyes_m below them, kept within the table heights
/// when `floorAtZero` (STAGE); the scene's -Z points away from the user, its +Y up.
glm::mat4 sceneInFrontOfHead(const glm::mat4& T_space_head, bool floorAtZero, const HeadsetOptions& options);

/// The text of each Unavailable value ("no OpenXR runtime", ...).
const char* describe(Unavailable reason) noexcept;

}  // namespace vt::xr
