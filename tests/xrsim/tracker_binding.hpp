#pragma once
// The VIVE tracker's pose action as an app sets it up, shared by the xrsim tracker tests.
#include <catch2/catch.hpp>

#include <cstdio>

#include <openxr/openxr.h>

namespace vt::test {

struct TrackerPoseAction {
  XrActionSet set = XR_NULL_HANDLE;
  XrAction action = XR_NULL_HANDLE;
  XrResult suggested = XR_ERROR_RUNTIME_FAILURE;  // what xrSuggestInteractionProfileBindings said
};

/// An action set "set" with one pose action "tracker_pose", suggested in the
/// htc/vive_tracker_htcx profile at `binding` (a role or a /devices/ path).
inline TrackerPoseAction suggestTrackerPose(XrInstance instance, const char* binding) {
  TrackerPoseAction out;
  XrActionSetCreateInfo setInfo{XR_TYPE_ACTION_SET_CREATE_INFO};
  std::snprintf(setInfo.actionSetName, sizeof(setInfo.actionSetName), "set");
  std::snprintf(setInfo.localizedActionSetName, sizeof(setInfo.localizedActionSetName), "Set");
  REQUIRE(xrCreateActionSet(instance, &setInfo, &out.set) == XR_SUCCESS);
  XrActionCreateInfo actionInfo{XR_TYPE_ACTION_CREATE_INFO};
  std::snprintf(actionInfo.actionName, sizeof(actionInfo.actionName), "tracker_pose");
  std::snprintf(actionInfo.localizedActionName, sizeof(actionInfo.localizedActionName), "Tracker pose");
  actionInfo.actionType = XR_ACTION_TYPE_POSE_INPUT;
  REQUIRE(xrCreateAction(out.set, &actionInfo, &out.action) == XR_SUCCESS);
  XrActionSuggestedBinding suggestion{out.action, XR_NULL_PATH};
  REQUIRE(xrStringToPath(instance, binding, &suggestion.binding) == XR_SUCCESS);
  XrInteractionProfileSuggestedBinding suggested{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING};
  REQUIRE(xrStringToPath(instance, "/interaction_profiles/htc/vive_tracker_htcx", &suggested.interactionProfile) ==
          XR_SUCCESS);
  suggested.countSuggestedBindings = 1;
  suggested.suggestedBindings = &suggestion;
  out.suggested = xrSuggestInteractionProfileBindings(instance, &suggested);
  return out;
}

}  // namespace vt::test
