#include "hand_input.hpp"

#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "vt/core/clock.hpp"

namespace vt::xr {
namespace {

XrPath path(XrInstance instance, const char* text) {
  XrPath out = XR_NULL_PATH;
  VT_XR_CHECK(xrStringToPath(instance, text, &out));
  return out;
}

XrAction makeAction(XrActionSet set, const char* name, const char* localized, XrActionType type,
                    const std::array<XrPath, 2>& hands) {
  XrActionCreateInfo info{XR_TYPE_ACTION_CREATE_INFO};
  std::snprintf(info.actionName, sizeof(info.actionName), "%s", name);
  std::snprintf(info.localizedActionName, sizeof(info.localizedActionName), "%s", localized);
  info.actionType = type;
  info.countSubactionPaths = 2;
  info.subactionPaths = hands.data();
  XrAction action = XR_NULL_HANDLE;
  VT_XR_CHECK(xrCreateAction(set, &info, &action));
  return action;
}

constexpr const char* kSides[2] = {"left", "right"};


// The VIVE tracker sits on the back of the right hand (on the glove), its grip frame aligned
// with the palm frame (+Y out of the back of the hand, -Z along the fingers) and 3 cm above
// the palm centre: the palm is 3 cm along the tracker's -Y.
constexpr float kTrackerAbovePalm_m = 0.03f;

}  // namespace

glm::mat4 poseToMatrix(const XrPosef& pose) {
  const glm::quat q(pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z);
  glm::mat4 m = glm::mat4_cast(q);
  m[3] = glm::vec4(pose.position.x, pose.position.y, pose.position.z, 1.0f);
  return m;
}

HandInput::HandInput(XrInstance instance, XrSession session, bool handTracking, bool viveTracker, bool timespec,
                     const HeadsetOptions& options)
    : m_instance(instance), m_session(session), m_outputs(options.handOutputs), m_gloveCurls(options.gloveCurls) {
  if (timespec) {
    VT_XR_CHECK(xrGetInstanceProcAddr(instance, "xrConvertTimeToTimespecTimeKHR",
                                      reinterpret_cast<PFN_xrVoidFunction*>(&m_toTimespec)));
    VT_XR_CHECK(xrGetInstanceProcAddr(instance, "xrConvertTimespecTimeToTimeKHR",
                                      reinterpret_cast<PFN_xrVoidFunction*>(&m_fromTimespec)));
  }
  m_handPaths = {path(instance, "/user/hand/left"), path(instance, "/user/hand/right")};
  XrActionSetCreateInfo setInfo{XR_TYPE_ACTION_SET_CREATE_INFO};
  std::snprintf(setInfo.actionSetName, sizeof(setInfo.actionSetName), "vtouching");
  std::snprintf(setInfo.localizedActionSetName, sizeof(setInfo.localizedActionSetName), "V-Touching");
  VT_XR_CHECK(xrCreateActionSet(instance, &setInfo, &m_set));
  m_grip = makeAction(m_set, "hand_pose", "Hand pose", XR_ACTION_TYPE_POSE_INPUT, m_handPaths);
  m_trigger = makeAction(m_set, "index_curl", "Index finger curl", XR_ACTION_TYPE_FLOAT_INPUT, m_handPaths);
  m_squeeze = makeAction(m_set, "grip_curl", "Grip curl", XR_ACTION_TYPE_FLOAT_INPUT, m_handPaths);
  m_haptic = makeAction(m_set, "texture_vibration", "Texture vibration", XR_ACTION_TYPE_VIBRATION_OUTPUT, m_handPaths);

  // Per profile: which component curls the index finger and which the others.
  struct Profile {
    const char* path;
    const char* trigger;
    const char* squeeze;  // nullptr: the profile has none
  };
  const Profile profiles[] = {
      {"/interaction_profiles/khr/simple_controller", "select/click", nullptr},
      {"/interaction_profiles/valve/index_controller", "trigger/value", "squeeze/value"},
      {"/interaction_profiles/htc/vive_controller", "trigger/value", "squeeze/click"},
      {"/interaction_profiles/oculus/touch_controller", "trigger/value", "squeeze/value"},
  };
  for (const Profile& profile : profiles) {
    std::vector<XrActionSuggestedBinding> bindings;
    for (const char* side : kSides) {
      const std::string hand = std::string("/user/hand/") + side;
      bindings.push_back({m_grip, path(instance, (hand + "/input/grip/pose").c_str())});
      bindings.push_back({m_trigger, path(instance, (hand + "/input/" + profile.trigger).c_str())});
      if (profile.squeeze) bindings.push_back({m_squeeze, path(instance, (hand + "/input/" + profile.squeeze).c_str())});
      bindings.push_back({m_haptic, path(instance, (hand + "/output/haptic").c_str())});
    }
    XrInteractionProfileSuggestedBinding suggested{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING};
    suggested.interactionProfile = path(instance, profile.path);
    suggested.countSuggestedBindings = std::uint32_t(bindings.size());
    suggested.suggestedBindings = bindings.data();
    VT_XR_CHECK(xrSuggestInteractionProfileBindings(instance, &suggested));
  }
  if (viveTracker) {
    // No subaction path: the role's binding alone identifies the tracker.
    XrActionCreateInfo info{XR_TYPE_ACTION_CREATE_INFO};
    std::snprintf(info.actionName, sizeof(info.actionName), "tracker_pose");
    std::snprintf(info.localizedActionName, sizeof(info.localizedActionName), "Glove tracker pose");
    info.actionType = XR_ACTION_TYPE_POSE_INPUT;
    VT_XR_CHECK(xrCreateAction(m_set, &info, &m_vivePose));
    const std::string binding = "/user/vive_tracker_htcx/role/" + options.trackerRole + "/input/grip/pose";
    XrActionSuggestedBinding suggestion{m_vivePose, path(instance, binding.c_str())};
    XrInteractionProfileSuggestedBinding suggested{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING};
    suggested.interactionProfile = path(instance, "/interaction_profiles/htc/vive_tracker_htcx");
    suggested.countSuggestedBindings = 1;
    suggested.suggestedBindings = &suggestion;
    VT_XR_CHECK(xrSuggestInteractionProfileBindings(instance, &suggested));
  }
  XrSessionActionSetsAttachInfo attach{XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO};
  attach.countActionSets = 1;
  attach.actionSets = &m_set;
  VT_XR_CHECK(xrAttachSessionActionSets(session, &attach));

  for (int h = 0; h < 2; ++h) {
    XrActionSpaceCreateInfo spaceInfo{XR_TYPE_ACTION_SPACE_CREATE_INFO};
    spaceInfo.action = m_grip;
    spaceInfo.subactionPath = m_handPaths[std::size_t(h)];
    spaceInfo.poseInActionSpace.orientation.w = 1.0f;
    VT_XR_CHECK(xrCreateActionSpace(session, &spaceInfo, &m_gripSpaces[std::size_t(h)]));
  }

  if (viveTracker) {
    XrActionSpaceCreateInfo spaceInfo{XR_TYPE_ACTION_SPACE_CREATE_INFO};
    spaceInfo.action = m_vivePose;
    spaceInfo.poseInActionSpace.orientation.w = 1.0f;
    VT_XR_CHECK(xrCreateActionSpace(session, &spaceInfo, &m_viveSpace));
  }

  if (handTracking) {
    VT_XR_CHECK(xrGetInstanceProcAddr(instance, "xrCreateHandTrackerEXT", reinterpret_cast<PFN_xrVoidFunction*>(&m_createTracker)));
    VT_XR_CHECK(xrGetInstanceProcAddr(instance, "xrDestroyHandTrackerEXT", reinterpret_cast<PFN_xrVoidFunction*>(&m_destroyTracker)));
    VT_XR_CHECK(xrGetInstanceProcAddr(instance, "xrLocateHandJointsEXT", reinterpret_cast<PFN_xrVoidFunction*>(&m_locateJoints)));
    for (int h = 0; h < 2; ++h) {
      XrHandTrackerCreateInfoEXT info{XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT};
      info.hand = h == 0 ? XR_HAND_LEFT_EXT : XR_HAND_RIGHT_EXT;
      info.handJointSet = XR_HAND_JOINT_SET_DEFAULT_EXT;
      VT_XR_CHECK(m_createTracker(session, &info, &m_trackers[std::size_t(h)]));
    }
  }
}

HandInput::~HandInput() {
  stopSampling();
  for (XrHandTrackerEXT tracker : m_trackers)
    if (tracker != XR_NULL_HANDLE) m_destroyTracker(tracker);
  for (XrSpace space : m_gripSpaces)
    if (space != XR_NULL_HANDLE) xrDestroySpace(space);
  if (m_viveSpace != XR_NULL_HANDLE) xrDestroySpace(m_viveSpace);
  if (m_set != XR_NULL_HANDLE) xrDestroyActionSet(m_set);  // destroys its actions too
}

std::string HandInput::profile() const {
  XrInteractionProfileState state{XR_TYPE_INTERACTION_PROFILE_STATE};
  if (XR_FAILED(xrGetCurrentInteractionProfile(m_session, m_handPaths[1], &state)) ||
      state.interactionProfile == XR_NULL_PATH)
    return "";
  char buffer[XR_MAX_PATH_LENGTH];
  std::uint32_t count = 0;
  if (XR_FAILED(xrPathToString(m_instance, state.interactionProfile, sizeof(buffer), &count, buffer))) return "";
  return buffer;
}

float HandInput::floatState(XrAction action, int hand) const {
  XrActionStateGetInfo info{XR_TYPE_ACTION_STATE_GET_INFO};
  info.action = action;
  info.subactionPath = m_handPaths[std::size_t(hand)];
  XrActionStateFloat state{XR_TYPE_ACTION_STATE_FLOAT};
  if (XR_FAILED(xrGetActionStateFloat(m_session, &info, &state)) || !state.isActive) return 0.0f;
  return state.currentState;
}

bool HandInput::locateJoints(int hand, XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out) const {
  XrHandJointLocationEXT joints[XR_HAND_JOINT_COUNT_EXT];
  XrHandJointLocationsEXT locations{XR_TYPE_HAND_JOINT_LOCATIONS_EXT};
  locations.jointCount = XR_HAND_JOINT_COUNT_EXT;
  locations.jointLocations = joints;
  XrHandJointsLocateInfoEXT info{XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT};
  info.baseSpace = base;
  info.time = time;
  if (XR_FAILED(m_locateJoints(m_trackers[std::size_t(hand)], &info, &locations)) || !locations.isActive) return false;
  static_assert(XR_HAND_JOINT_COUNT_EXT == kHandJointCount, "vt::HandJoint follows XrHandJointEXT");
  const XrSpaceLocationFlags needed = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
  for (int j = 0; j < kHandJointCount; ++j) {
    if ((joints[j].locationFlags & needed) != needed) return false;
    const glm::mat4 T_world_joint = T_world_base * poseToMatrix(joints[j].pose);
    out.position[std::size_t(j)] = glm::vec3(T_world_joint[3]);
    out.orientation[std::size_t(j)] = glm::quat_cast(glm::mat3(T_world_joint));
    out.radius_m[std::size_t(j)] = joints[j].radius;
  }
  return true;
}

bool HandInput::controllerHand(int hand, XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out) const {
  XrSpaceLocation location{XR_TYPE_SPACE_LOCATION};
  if (XR_FAILED(xrLocateSpace(m_gripSpaces[std::size_t(hand)], base, time, &location))) return false;
  const XrSpaceLocationFlags needed = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
  if ((location.locationFlags & needed) != needed) return false;
  // The hand in the grip frame. OpenXR's grip (semantic paths, "grip"): +X normal to the palm
  // (out of the back of the right hand, out of the left palm), -Z through the tube the closed
  // fingers make around the handle, little finger to thumb: in a natural hold the way the
  // controller points, and +Y up (where the thumb rests on top). The real hand around the handle
  // faces the midline, which drawn as is shows the hand edge-on, a blade. The virtual hand is
  // drawn turned palm down about the controller instead: its palm frame is the grip frame
  // (fingers forward along -Z, the back of the hand up along +Y, the palm centre at the grip;
  // poseHand mirrors the left hand), so touching the table is reaching forward and tilting the
  // controller down, as a hand would.
  const glm::mat4 T_world_palm = T_world_base * poseToMatrix(location.pose);
  out = poseHand(T_world_palm, controllerCurls(hand), hand == 0);
  return true;
}

FingerCurls HandInput::controllerCurls(int hand) const {
  const float trigger = floatState(m_trigger, hand);
  const float squeeze = floatState(m_squeeze, hand);
  return {0.2f + 0.6f * squeeze, trigger, squeeze, squeeze, squeeze};
}

bool HandInput::trackerHand(XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out) const {
  if (m_viveSpace == XR_NULL_HANDLE) return false;
  XrSpaceLocation location{XR_TYPE_SPACE_LOCATION};
  if (XR_FAILED(xrLocateSpace(m_viveSpace, base, time, &location))) return false;
  const XrSpaceLocationFlags needed = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
  if ((location.locationFlags & needed) != needed) return false;
  const glm::mat4 T_tracker_palm = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -kTrackerAbovePalm_m, 0.0f));
  FingerCurls curls{};
  if (m_gloveCurls == nullptr || !m_gloveCurls->read(curls)) curls = controllerCurls(1);
  out = poseHand(T_world_base * poseToMatrix(location.pose) * T_tracker_palm, curls, false);
  return true;
}

std::int64_t HandInput::steadyTime(XrTime time) const {
  timespec ts{};
  if (m_toTimespec != nullptr && XR_SUCCEEDED(m_toTimespec(m_instance, time, &ts)))
    return std::int64_t(ts.tv_sec) * 1'000'000'000 + std::int64_t(ts.tv_nsec);
  return SteadyClock::instance().now_ns();  // no conversion offered: the pose is as of now
}

XrTime HandInput::xrTime(std::int64_t steady_ns) const {
  if (m_fromTimespec == nullptr) return 0;
  const timespec ts{time_t(steady_ns / 1'000'000'000), long(steady_ns % 1'000'000'000)};
  XrTime out = 0;
  return XR_SUCCEEDED(m_fromTimespec(m_instance, &ts, &out)) ? out : 0;
}

bool HandInput::locate(int hand, XrSpace base, XrTime time, const glm::mat4& T_world_base, HandPose& out,
                       bool& tracker) const {
  // Priority: tracked joints, then (right hand) the glove's VIVE tracker, then the controller.
  const bool joints = handTracking() && locateJoints(hand, base, time, T_world_base, out);
  tracker = !joints && hand == 1 && trackerHand(base, time, T_world_base, out);
  return joints || tracker || controllerHand(hand, base, time, T_world_base, out);
}

XrResult HandInput::update(XrSpace base, XrTime time, const glm::mat4& T_world_base, bool jump) {
  XrActiveActionSet active{m_set, XR_NULL_PATH};
  XrActionsSyncInfo sync{XR_TYPE_ACTIONS_SYNC_INFO};
  sync.countActiveActionSets = 1;
  sync.activeActionSets = &active;
  const XrResult result = xrSyncActions(m_session, &sync);
  if (XR_FAILED(result)) return result;
  if (jump) ++m_jumps;
  m_placement.publish({T_world_base, m_jumps});
  for (int h = 0; h < 2; ++h) {
    HandPose& pose = m_display[std::size_t(h)];
    pose = HandPose{};
    bool tracker = false;
    pose.valid = locate(h, base, time, T_world_base, pose, tracker);
    pose.t_ns = steadyTime(time);
    if (h == 1) m_trackerPosed = tracker;
  }
  // The haptic side's hands: asked of the runtime for their own times once the actions are
  // synced (the sampler), else these display-time poses.
  if (!m_sampler.joinable() && m_fromTimespec != nullptr && (m_outputs[0] || m_outputs[1]))
    m_sampler = std::thread([this, base] { sampleLoop(base); });
  if (!m_sampler.joinable()) {
    for (int h = 0; h < 2; ++h) {
      if (PoseHistory* output = m_outputs[std::size_t(h)]) {
        HandPose pose = m_display[std::size_t(h)];
        pose.sequence = ++m_sequence;
        output->publish(pose, jump);
      }
    }
  }
  return result;
}

void HandInput::sampleLoop(XrSpace base) noexcept {
  // Every millisecond, the hands at now + lookahead (+ a margin of two periods, so a tick finds
  // poses on both sides of its time): the time the haptic loop's ticks render.
  constexpr std::int64_t kPeriod_ns = 1'000'000;
  constexpr std::int64_t kMargin_ns = 2 * kPeriod_ns;
  const Clock& clock = SteadyClock::instance();
  std::uint64_t sequence = 0, jumps = 0;
  std::int64_t last_ns = 0;
  for (std::int64_t next = clock.now_ns(); !m_stopSampler.load(std::memory_order_acquire); next += kPeriod_ns) {
    clock.sleepUntil(next);
    const std::int64_t now_ns = clock.now_ns();
    if (next < now_ns - 10 * kPeriod_ns) next = now_ns;  // descheduled: no burst to catch up
    // A shrinking lookahead asks for a time the histories already hold poses past: nothing to
    // publish. (Stamped a nanosecond after the last one instead, as before, such a pose repeated
    // it up to rounding, and a prediction's velocity over that span was the rounding, magnified.)
    const std::int64_t t_ns = now_ns + m_lookahead_ns.load(std::memory_order_relaxed) + kMargin_ns;
    if (t_ns < last_ns + kPeriod_ns / 2) continue;
    const XrTime time = xrTime(t_ns);
    Placement placement;
    if (time == 0 || !m_placement.read(placement)) continue;
    for (int h = 0; h < 2; ++h) {
      PoseHistory* output = m_outputs[std::size_t(h)];
      if (output == nullptr) continue;
      HandPose pose;
      bool tracker = false;
      pose.valid = locate(h, base, time, placement.T_world_base, pose, tracker);
      pose.t_ns = t_ns;
      pose.sequence = ++sequence;
      output->publish(pose, placement.jumps != jumps);
    }
    jumps = placement.jumps;
    last_ns = t_ns;
  }
}

void HandInput::stopSampling() {
  m_stopSampler.store(true, std::memory_order_release);
  if (m_sampler.joinable()) m_sampler.join();
}

XrHapticActionInfo HandInput::hapticAction(int hand) const {
  XrHapticActionInfo info{XR_TYPE_HAPTIC_ACTION_INFO};
  info.action = m_haptic;
  info.subactionPath = m_handPaths[std::size_t(hand)];
  return info;
}

XrResult HandInput::applyFeedback(int hand, const XrHapticBaseHeader* feedback) {
  const XrHapticActionInfo info = hapticAction(hand);
  return xrApplyHapticFeedback(m_session, &info, feedback);
}

XrResult HandInput::stopVibration(int hand) {
  const XrHapticActionInfo info = hapticAction(hand);
  return xrStopHapticFeedback(m_session, &info);
}

}  // namespace vt::xr
