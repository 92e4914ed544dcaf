// XR_EXT_hand_tracking: 26 scripted joints per hand.
#include <algorithm>

#include "api.hpp"

namespace xrsim {

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

    const Sample sample = sampleAt(*session, info->time);
    const HandSample& hand = sample.hands[tracker->hand == XR_HAND_LEFT_EXT ? 0 : 1];
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
