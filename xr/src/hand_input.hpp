#pragma once
// Hand input: XR_EXT_hand_tracking joints, or controller grip poses posing a hand whose fingers
// curl with trigger and squeeze, through one action set with bindings for the common profiles.
// Also owns the haptic output action. Render thread only.
#include <array>
#include <string>

#include <glm/glm.hpp>

#include "vt/xr/headset.hpp"
#include "xr_check.hpp"

namespace vt::xr {

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

  /// Syncs actions and publishes both hands' poses at `time` in world coordinates, stamped
  /// with `time` on the app's clock; `jump`: they begin a new pose-history segment (the scene
  /// was placed again: never swept across).
  /// Returns the xrSyncActions result (loss is the caller's business).
  XrResult update(XrSpace base, XrTime time, const glm::mat4& T_world_base, bool jump);
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
  bool locateJoints(int hand, XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out);
  bool controllerHand(int hand, XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out);
  bool trackerHand(XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out);
  FingerCurls controllerCurls(int hand) const;
  float floatState(XrAction action, int hand) const;

  XrInstance m_instance;
  XrSession m_session;
  /// XrTime -> SteadyClock nanoseconds (now, without XR_KHR_convert_timespec_time).
  std::int64_t steadyTime(XrTime time) const;

  std::array<PoseHistory*, 2> m_outputs;
  PFN_xrConvertTimeToTimespecTimeKHR m_toTimespec = nullptr;
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
  std::uint64_t m_sequence = 0;
};

}  // namespace vt::xr
