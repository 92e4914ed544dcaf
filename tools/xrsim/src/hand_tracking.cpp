// XR_EXT_hand_tracking: 26 scripted joints per hand.
#include <algorithm>
#include <cmath>

#include "api.hpp"

namespace xrsim {
namespace {

// A hand tracker with a camera at `rate_hz` (config hand_rate_hz) knows the joints only at its
// frame times; like a runtime's pose history it answers any other time by continuing the
// motion of its two newest frames at or before that time (exact for steady motion, late at
// turns and stops).
HandSample trackedHand(const Session& session, XrTime time, int hand) {
  const double rate_hz = session.instance->config.handRate_hz;
  if (rate_hz <= 0.0 || session.beginTime == 0) return sampleAt(session, time).hands[std::size_t(hand)];
  const double t_s = double(time - session.beginTime) * 1e-9;
  const double newest_s = std::floor(t_s * rate_hz) / rate_hz;
  const double previous_s = newest_s - 1.0 / rate_hz;
  auto at = [&](double s) { return session.instance->script.sample(std::max(0.0, s)).hands[std::size_t(hand)]; };
  HandSample out = at(newest_s);
  if (previous_s < 0.0) return out;
  const HandSample before = at(previous_s);
  const auto w = float(1.0 + (t_s - newest_s) * rate_hz);
  for (std::size_t j = 0; j < out.joints.size(); ++j) {
    out.joints[j].position = glm::mix(before.joints[j].position, out.joints[j].position, w);
    out.joints[j].orientation = glm::normalize(glm::slerp(before.joints[j].orientation, out.joints[j].orientation, w));
  }
  return out;
}

}  // namespace

XrResult XRAPI_CALL createHandTracker(XrSession handle, const XrHandTrackerCreateInfoEXT* info, XrHandTrackerEXT* out) {
  return guarded("xrCreateHandTrackerEXT", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_HAND_TRACKER_CREATE_INFO_EXT);
    if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (!session->instance->config.handTracking) return XR_ERROR_FEATURE_UNSUPPORTED;
    if (info->hand != XR_HAND_LEFT_EXT && info->hand != XR_HAND_RIGHT_EXT) return XR_ERROR_VALIDATION_FAILURE;
    if (info->handJointSet != XR_HAND_JOINT_SET_DEFAULT_EXT) return XR_ERROR_VALIDATION_FAILURE;
    auto tracker = std::make_unique<HandTracker>();
    tracker->session = session;
    tracker->hand = info->hand;
    *out = handleOf(tracker.get());
    session->handTrackers.push_back(std::move(tracker));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL destroyHandTracker(XrHandTrackerEXT handle) {
  return guarded("xrDestroyHandTrackerEXT", [&]() -> XrResult {
    HandTracker* tracker = lookup<HandTracker>(handle);
    if (tracker == nullptr) return XR_ERROR_HANDLE_INVALID;
    auto& list = tracker->session->handTrackers;
    list.erase(std::find_if(list.begin(), list.end(), [&](const auto& t) { return t.get() == tracker; }));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL locateHandJoints(XrHandTrackerEXT handle, const XrHandJointsLocateInfoEXT* info,
                                     XrHandJointLocationsEXT* locations) {
  return guarded("xrLocateHandJointsEXT", [&]() -> XrResult {
    HandTracker* tracker = lookup<HandTracker>(handle);
    if (tracker == nullptr) return XR_ERROR_HANDLE_INVALID;
    Session* session = nullptr;
    if (XrResult r = findSession(handleOf(tracker->session), session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_HAND_JOINTS_LOCATE_INFO_EXT);
    XRSIM_CHECK_STRUCT(locations, XR_TYPE_HAND_JOINT_LOCATIONS_EXT);
    Space* base = lookup<Space>(info->baseSpace);
    if (base == nullptr || base->session != session) return XR_ERROR_HANDLE_INVALID;
    if (info->time <= 0) return XR_ERROR_TIME_INVALID;
    if (locations->jointCount != XR_HAND_JOINT_COUNT_EXT || locations->jointLocations == nullptr)
      return XR_ERROR_VALIDATION_FAILURE;
    XrHandJointVelocitiesEXT* velocities = nullptr;
    for (auto* next = static_cast<XrBaseOutStructure*>(locations->next); next != nullptr; next = next->next)
      if (next->type == XR_TYPE_HAND_JOINT_VELOCITIES_EXT) velocities = reinterpret_cast<XrHandJointVelocitiesEXT*>(next);
    if (velocities != nullptr && (velocities->jointCount != XR_HAND_JOINT_COUNT_EXT || velocities->jointVelocities == nullptr))
      return XR_ERROR_VALIDATION_FAILURE;

    const HandSample hand = trackedHand(*session, info->time, tracker->hand == XR_HAND_LEFT_EXT ? 0 : 1);
    Pose T_stage_base;
    // Hands are only seen by a running, visible session (a headset off the head tracks nothing).
    const bool visible = session->state == XR_SESSION_STATE_VISIBLE || session->state == XR_SESSION_STATE_FOCUSED;
    const bool active = visible && hand.jointsActive && spacePose(*session, *base, info->time, T_stage_base);
    locations->isActive = active ? XR_TRUE : XR_FALSE;
    const Pose T_base_stage = inverse(T_stage_base);
    for (int j = 0; j < XR_HAND_JOINT_COUNT_EXT; ++j) {
      XrHandJointLocationEXT& out = locations->jointLocations[j];
      out.locationFlags = 0;
      out.pose = toXr(Pose{});
      out.radius = 0.0f;
      if (active) {
        out.pose = toXr(compose(T_base_stage, hand.joints[std::size_t(j)]));
        out.radius = hand.radius_m[std::size_t(j)];
        out.locationFlags = XR_SPACE_LOCATION_ORIENTATION_VALID_BIT | XR_SPACE_LOCATION_POSITION_VALID_BIT |
                            XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT;
      }
      if (velocities != nullptr) velocities->jointVelocities[j].velocityFlags = 0;
    }
    return XR_SUCCESS;
  });
}

}  // namespace xrsim
