#pragma once
// Hand input: XR_EXT_hand_tracking joints, or controller grip poses posing a hand whose fingers
// curl with trigger and squeeze, through one action set with bindings for the common profiles.
// Also owns the haptic output action. The render thread syncs the actions and locates the hands
// for each frame's display time (what the eyes show); with XR_KHR_convert_timespec_time a
// sampler thread asks the runtime every millisecond where the hands will be when the haptic
// output is felt (now + lookahead) and publishes those poses: the haptic side never extrapolates
// frame-rate samples (docs/tactile-rendering.md, "Time"). OpenXR lets any thread locate spaces
// and hand joints; none of the handles used there is externally synchronized.
#include <array>
#include <atomic>
#include <string>
#include <thread>

#include <glm/glm.hpp>

#include "vt/core/latest_value.hpp"
#include "vt/xr/headset.hpp"
#include "xr_check.hpp"

namespace vt::xr {

/// An OpenXR pose as a rigid transform (the pose's space from its frame's).
glm::mat4 poseToMatrix(const XrPosef& pose);

class HandInput {
 public:
  /// Creates actions, suggests bindings, attaches them to `session`, creates hand trackers when
  /// `handTracking` (the extension is enabled and the system supports it), binds a pose action
  /// to the VIVE tracker role when `viveTracker` (XR_HTCX_vive_tracker_interaction enabled).
  /// `timespec`: XR_KHR_convert_timespec_time is enabled (poses are stamped with the XrTime
  /// they were located for, on CLOCK_MONOTONIC = vt::SteadyClock).
  HandInput(XrInstance instance, XrSession session, bool handTracking, bool viveTracker, bool timespec,
            const HeadsetOptions& options);
  ~HandInput();
  HandInput(const HandInput&) = delete;
  HandInput& operator=(const HandInput&) = delete;

  /// Render thread, once per frame: syncs actions and locates both hands at the frame's display
  /// `time` in world coordinates (displayHand). The hands published to the pose histories come
  /// from the sampler thread once it runs, else these, stamped with `time` on the app's clock;
  /// `jump`: the scene was placed again, the next poses begin a new segment (never swept across).
  /// Returns the xrSyncActions result (loss is the caller's business).
  XrResult update(XrSpace base, XrTime time, const glm::mat4& T_world_base, bool jump);
  /// The hand as located for the last frame's display time (invalid when untracked). Render thread.
  const HandPose& displayHand(int hand) const { return m_display[std::size_t(hand)]; }
  /// How far ahead of now the sampler asks for the hands: the felt outputs' latency. Any thread.
  void setLookahead(std::int64_t lookahead_ns) { m_lookahead_ns.store(lookahead_ns, std::memory_order_relaxed); }
  /// Whether the sampler thread publishes the hands (false: the render thread does, at frame rate).
  bool sampling() const { return m_sampler.joinable(); }
  /// Stops the sampler (before the session ends). Render thread; idempotent.
  void stopSampling();
  /// xrApplyHapticFeedback (any feedback structure) / xrStopHapticFeedback results on the
  /// hand's haptic action (loss is the caller's business).
  XrResult applyFeedback(int hand, const XrHapticBaseHeader* feedback);
  XrResult stopVibration(int hand);
  /// The hand's haptic action and subaction path, for the haptics queries.
  XrHapticActionInfo hapticAction(int hand) const;
  bool handTracking() const { return m_trackers[0] != XR_NULL_HANDLE; }
  bool viveTracker() const { return m_viveSpace != XR_NULL_HANDLE; }
  /// Whether the last update posed the right hand from the VIVE tracker.
  bool trackerPosedHand() const { return m_trackerPosed; }
  /// The current interaction profile path, or "" before one is known.
  std::string profile() const;

 private:
  /// Where to draw the scene's world from: the app space and its placement (render thread -> sampler).
  struct Placement {
    glm::mat4 T_world_base{1.0f};
    std::uint64_t jumps = 0;  // placements so far: a change starts a new pose-history segment
  };
  /// The hand at `time` (false when untracked); `tracker`: the VIVE tracker posed it. Any thread.
  bool locate(int hand, XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out, bool& tracker) const;
  bool locateJoints(int hand, XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out) const;
  bool controllerHand(int hand, XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out) const;
  bool trackerHand(XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out) const;
  void sampleLoop(XrSpace base) noexcept;
  FingerCurls controllerCurls(int hand) const;
  float floatState(XrAction action, int hand) const;

  XrInstance m_instance;
  XrSession m_session;
  /// XrTime -> SteadyClock nanoseconds (now, without XR_KHR_convert_timespec_time).
  std::int64_t steadyTime(XrTime time) const;
  /// SteadyClock nanoseconds -> XrTime (XR_KHR_convert_timespec_time); 0 when it cannot.
  XrTime xrTime(std::int64_t steady_ns) const;

  std::array<PoseHistory*, 2> m_outputs;
  PFN_xrConvertTimeToTimespecTimeKHR m_toTimespec = nullptr;
  PFN_xrConvertTimespecTimeToTimeKHR m_fromTimespec = nullptr;
  const LatestValue<FingerCurls>* m_gloveCurls;
  std::array<XrPath, 2> m_handPaths{};
  XrActionSet m_set = XR_NULL_HANDLE;
  XrAction m_grip = XR_NULL_HANDLE, m_trigger = XR_NULL_HANDLE, m_squeeze = XR_NULL_HANDLE,
           m_haptic = XR_NULL_HANDLE;
  std::array<XrSpace, 2> m_gripSpaces{};
  XrAction m_vivePose = XR_NULL_HANDLE;
  XrSpace m_viveSpace = XR_NULL_HANDLE;
  bool m_trackerPosed = false;
  std::array<XrHandTrackerEXT, 2> m_trackers{};
  PFN_xrCreateHandTrackerEXT m_createTracker = nullptr;
  PFN_xrDestroyHandTrackerEXT m_destroyTracker = nullptr;
  PFN_xrLocateHandJointsEXT m_locateJoints = nullptr;
  std::uint64_t m_sequence = 0;  // render thread's published poses
  std::array<HandPose, 2> m_display{};
  // The sampler thread and what it reads.
  LatestValue<Placement> m_placement;
  std::uint64_t m_jumps = 0;  // render thread: placements published
  std::atomic<std::int64_t> m_lookahead_ns{0};
  std::atomic<bool> m_stopSampler{false};
  std::thread m_sampler;
};

}  // namespace vt::xr
