// Reference spaces (VIEW, LOCAL, STAGE), action spaces and xrLocateSpace. The stage frame is
// the simulator's world: scripts give every pose in it.
#include <algorithm>

#include "api.hpp"

namespace xrsim {
namespace {

bool supportedReferenceSpace(XrReferenceSpaceType type) {
  return type == XR_REFERENCE_SPACE_TYPE_VIEW || type == XR_REFERENCE_SPACE_TYPE_LOCAL ||
         type == XR_REFERENCE_SPACE_TYPE_STAGE;
}

XrResult addSpace(Session& session, std::unique_ptr<Space> space, XrSpace* out) {
  space->session = &session;
  *out = handleOf(space.get());
  session.spaces.push_back(std::move(space));
  return XR_SUCCESS;
}

bool actionPose(Session& session, const Space& space, XrTime time, Pose& out) {
  if (!isLive(space.action)) return false;
  if (space.subaction == XR_NULL_PATH && trackerBound(session, *space.action)) {
    const Sample sample = sampleAt(session, time);
    out = sample.tracker;
    return sample.trackerTracked;
  }
  if (session.currentProfile == XR_NULL_PATH) return false;
  const Instance& instance = *session.instance;
  int hand = -1;
  if (space.subaction != XR_NULL_PATH) hand = handOfPath(*pathString(instance, space.subaction));
  bool aim = false;
  bool bound = false;
  for (XrPath path : boundPaths(session, *space.action, hand)) {
    const std::string& text = *pathString(instance, path);
    const int pathHand = handOfPath(text);
    if (pathHand < 0) continue;
    if (hand < 0) hand = pathHand;  // no subaction path: the first bound hand
    if (pathHand != hand) continue;
    bound = true;
    aim = text.find("/input/aim/") != std::string::npos;
    break;
  }
  if (!bound) return false;
  const Sample sample = sampleAt(session, time);
  const HandSample& state = sample.hands[std::size_t(hand)];
  if (!state.controllerTracked) return false;
  out = aim ? state.aim : state.grip;
  return true;
}

}  // namespace

bool spacePose(Session& session, const Space& space, XrTime time, Pose& out) {
  Pose origin;
  if (space.isAction) {
    if (!actionPose(session, space, time, origin)) return false;
  } else if (space.referenceType == XR_REFERENCE_SPACE_TYPE_VIEW) {
    origin = sampleAt(session, time).head;
  } else if (space.referenceType == XR_REFERENCE_SPACE_TYPE_LOCAL) {
    // LOCAL: gravity-aligned, at the head's starting position (orientation kept level).
    origin.position = session.instance->script.sample(0.0).head.position;
  }
  out = compose(origin, space.offset);
  return true;
}

XrResult XRAPI_CALL enumerateReferenceSpaces(XrSession handle, std::uint32_t capacity, std::uint32_t* count,
                                             XrReferenceSpaceType* out) {
  return guarded("xrEnumerateReferenceSpaces", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    return twoCall(capacity, count, out,
                   std::vector<XrReferenceSpaceType>{XR_REFERENCE_SPACE_TYPE_VIEW, XR_REFERENCE_SPACE_TYPE_LOCAL,
                                                     XR_REFERENCE_SPACE_TYPE_STAGE});
  });
}

XrResult XRAPI_CALL createReferenceSpace(XrSession handle, const XrReferenceSpaceCreateInfo* info, XrSpace* out) {
  return guarded("xrCreateReferenceSpace", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
    if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (!supportedReferenceSpace(info->referenceSpaceType)) return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
    if (!validPose(info->poseInReferenceSpace)) return XR_ERROR_POSE_INVALID;
    auto space = std::make_unique<Space>();
    space->referenceType = info->referenceSpaceType;
    space->offset = fromXr(info->poseInReferenceSpace);
    return addSpace(*session, std::move(space), out);
  });
}

XrResult XRAPI_CALL getReferenceSpaceBoundsRect(XrSession handle, XrReferenceSpaceType type, XrExtent2Df* bounds) {
  return guarded("xrGetReferenceSpaceBoundsRect", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    if (bounds == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (!supportedReferenceSpace(type)) return XR_ERROR_REFERENCE_SPACE_UNSUPPORTED;
    if (type != XR_REFERENCE_SPACE_TYPE_STAGE) {
      *bounds = {0.0f, 0.0f};
      return XR_SPACE_BOUNDS_UNAVAILABLE;
    }
    *bounds = {3.0f, 3.0f};
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL createActionSpace(XrSession handle, const XrActionSpaceCreateInfo* info, XrSpace* out) {
  return guarded("xrCreateActionSpace", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_ACTION_SPACE_CREATE_INFO);
    if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    Action* action = lookup<Action>(info->action);
    if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (action->actionType != XR_ACTION_TYPE_POSE_INPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
    if (info->subactionPath != XR_NULL_PATH) {
      if (pathString(*session->instance, info->subactionPath) == nullptr) return XR_ERROR_PATH_INVALID;
      const auto& subs = action->subactions;
      if (std::find(subs.begin(), subs.end(), info->subactionPath) == subs.end()) return XR_ERROR_PATH_UNSUPPORTED;
    }
    if (!validPose(info->poseInActionSpace)) return XR_ERROR_POSE_INVALID;
    auto space = std::make_unique<Space>();
    space->isAction = true;
    space->action = action;
    space->subaction = info->subactionPath;
    space->offset = fromXr(info->poseInActionSpace);
    return addSpace(*session, std::move(space), out);
  });
}

XrResult XRAPI_CALL locateSpace(XrSpace spaceHandle, XrSpace baseHandle, XrTime time, XrSpaceLocation* location) {
  return guarded("xrLocateSpace", [&]() -> XrResult {
    Space* space = lookup<Space>(spaceHandle);
    Space* base = lookup<Space>(baseHandle);
    if (space == nullptr || base == nullptr) return XR_ERROR_HANDLE_INVALID;
    Session* session = nullptr;
    if (XrResult r = findSession(handleOf(space->session), session); r != XR_SUCCESS) return r;
    if (base->session != session) return XR_ERROR_VALIDATION_FAILURE;
    XRSIM_CHECK_STRUCT(location, XR_TYPE_SPACE_LOCATION);
    if (time <= 0) return XR_ERROR_TIME_INVALID;
    for (auto* next = static_cast<XrBaseOutStructure*>(location->next); next != nullptr; next = next->next)
      if (next->type == XR_TYPE_SPACE_VELOCITY) reinterpret_cast<XrSpaceVelocity*>(next)->velocityFlags = 0;
    Pose T_stage_space, T_stage_base;
    if (!spacePose(*session, *space, time, T_stage_space) || !spacePose(*session, *base, time, T_stage_base)) {
      location->locationFlags = 0;
      location->pose = toXr(Pose{});
      return XR_SUCCESS;
    }
    location->pose = toXr(compose(inverse(T_stage_base), T_stage_space));
    location->locationFlags = XR_SPACE_LOCATION_ORIENTATION_VALID_BIT | XR_SPACE_LOCATION_POSITION_VALID_BIT |
                              XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT | XR_SPACE_LOCATION_POSITION_TRACKED_BIT;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL destroySpace(XrSpace handle) {
  return guarded("xrDestroySpace", [&]() -> XrResult {
    Space* space = lookup<Space>(handle);
    if (space == nullptr) return XR_ERROR_HANDLE_INVALID;
    auto& list = space->session->spaces;
    list.erase(std::find_if(list.begin(), list.end(), [&](const auto& s) { return s.get() == space; }));
    return XR_SUCCESS;
  });
}

}  // namespace xrsim
