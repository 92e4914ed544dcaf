// Action sets, actions, suggested bindings, attachment and the current interaction profile.
#include <algorithm>
#include <cctype>

#include "api.hpp"

namespace xrsim {
namespace {

// Spec 11.2: action and action set names are lowercase letters, digits, '-', '_', '.'.
bool validName(const char* name, std::size_t capacity) {
  const std::size_t n = strnlen(name, capacity);
  if (n == 0 || n == capacity) return false;
  return std::all_of(name, name + n, [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
  });
}

bool validLocalizedName(const char* name, std::size_t capacity) {
  const std::size_t n = strnlen(name, capacity);
  return n > 0 && n < capacity;
}

// The profiles a simulated user may be holding, in preference order after the configured one.
const char* const kKnownProfiles[] = {"/interaction_profiles/valve/index_controller",
                                      "/interaction_profiles/oculus/touch_controller",
                                      "/interaction_profiles/htc/vive_controller",
                                      "/interaction_profiles/khr/simple_controller"};

bool wellFormedProfile(const std::string& path) {
  // /interaction_profiles/<vendor>/<name>
  if (path.rfind("/interaction_profiles/", 0) != 0) return false;
  return std::count(path.begin(), path.end(), '/') == 3;
}

bool wellFormedBinding(const Instance& instance, const std::string& path) {
  // /user/<top level...>/(input|output)/<component>[/<feature>]; with XR_HTCX_vive_tracker_interaction
  // also a tracker's persistent path /devices/...
  const bool device = instance.viveTrackerEnabled && path.rfind("/devices/", 0) == 0;
  if (path.rfind("/user/", 0) != 0 && !device) return false;
  return path.find("/input/") != std::string::npos || path.find("/output/") != std::string::npos;
}

void eraseBindingsOf(Instance& instance, const Action* action) {
  for (auto& [profile, bindings] : instance.suggested)
    bindings.erase(std::remove_if(bindings.begin(), bindings.end(), [&](const Binding& b) { return b.action == action; }),
                   bindings.end());
}

std::string titleCase(std::string text) {
  bool start = true;
  for (char& c : text) {
    if (c == '_' || c == '-') {
      c = ' ';
      start = true;
    } else if (start) {
      c = char(std::toupper(static_cast<unsigned char>(c)));
      start = false;
    }
  }
  return text;
}

}  // namespace

std::vector<XrPath> boundPaths(const Session& session, const Action& action, int hand) {
  std::vector<XrPath> out;
  const auto it = session.instance->suggested.find(session.currentProfile);
  if (it == session.instance->suggested.end()) return out;
  for (const Binding& b : it->second)
    if (b.action == &action && (hand < 0 || handOfPath(*pathString(*session.instance, b.path)) == hand))
      out.push_back(b.path);
  return out;
}

XrResult XRAPI_CALL createActionSet(XrInstance handle, const XrActionSetCreateInfo* info, XrActionSet* out) {
  return guarded("xrCreateActionSet", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_ACTION_SET_CREATE_INFO);
    if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (!validName(info->actionSetName, sizeof(info->actionSetName))) return XR_ERROR_PATH_FORMAT_INVALID;
    if (!validLocalizedName(info->localizedActionSetName, sizeof(info->localizedActionSetName)))
      return XR_ERROR_LOCALIZED_NAME_INVALID;
    for (const auto& set : instance->actionSets) {
      if (set->name == info->actionSetName) return XR_ERROR_NAME_DUPLICATED;
      if (set->localizedName == info->localizedActionSetName) return XR_ERROR_LOCALIZED_NAME_DUPLICATED;
    }
    auto set = std::make_unique<ActionSet>();
    set->instance = instance;
    set->name = info->actionSetName;
    set->localizedName = info->localizedActionSetName;
    set->priority = info->priority;
    *out = handleOf(set.get());
    instance->actionSets.push_back(std::move(set));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL destroyActionSet(XrActionSet handle) {
  return guarded("xrDestroyActionSet", [&]() -> XrResult {
    ActionSet* set = lookup<ActionSet>(handle);
    if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
    Instance& instance = *set->instance;
    for (const auto& action : set->actions) eraseBindingsOf(instance, action.get());
    for (const auto& session : instance.sessions) {
      auto& attached = session->attachedSets;
      attached.erase(std::remove(attached.begin(), attached.end(), set), attached.end());
    }
    auto& list = instance.actionSets;
    list.erase(std::find_if(list.begin(), list.end(), [&](const auto& s) { return s.get() == set; }));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL createAction(XrActionSet handle, const XrActionCreateInfo* info, XrAction* out) {
  return guarded("xrCreateAction", [&]() -> XrResult {
    ActionSet* set = lookup<ActionSet>(handle);
    if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (set->instance->lost) return XR_ERROR_INSTANCE_LOST;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_ACTION_CREATE_INFO);
    if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (set->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
    if (!validName(info->actionName, sizeof(info->actionName))) return XR_ERROR_PATH_FORMAT_INVALID;
    if (!validLocalizedName(info->localizedActionName, sizeof(info->localizedActionName)))
      return XR_ERROR_LOCALIZED_NAME_INVALID;
    switch (info->actionType) {
      case XR_ACTION_TYPE_BOOLEAN_INPUT: case XR_ACTION_TYPE_FLOAT_INPUT: case XR_ACTION_TYPE_VECTOR2F_INPUT:
      case XR_ACTION_TYPE_POSE_INPUT: case XR_ACTION_TYPE_VIBRATION_OUTPUT: break;
      default: return XR_ERROR_VALIDATION_FAILURE;
    }
    for (const auto& action : set->actions) {
      if (action->name == info->actionName) return XR_ERROR_NAME_DUPLICATED;
      if (action->localizedName == info->localizedActionName) return XR_ERROR_LOCALIZED_NAME_DUPLICATED;
    }
    std::vector<XrPath> subactions;
    for (std::uint32_t i = 0; i < info->countSubactionPaths; ++i) {
      const XrPath path = info->subactionPaths[i];
      const std::string* text = pathString(*set->instance, path);
      if (text == nullptr) return XR_ERROR_PATH_INVALID;
      const bool topLevel = *text == "/user/hand/left" || *text == "/user/hand/right" || *text == "/user/head" ||
                            *text == "/user/gamepad" || *text == "/user/treadmill";
      if (!topLevel || std::find(subactions.begin(), subactions.end(), path) != subactions.end())
        return XR_ERROR_PATH_UNSUPPORTED;
      subactions.push_back(path);
    }
    auto action = std::make_unique<Action>();
    action->set = set;
    action->name = info->actionName;
    action->localizedName = info->localizedActionName;
    action->actionType = info->actionType;
    action->subactions = std::move(subactions);
    *out = handleOf(action.get());
    set->actions.push_back(std::move(action));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL destroyAction(XrAction handle) {
  return guarded("xrDestroyAction", [&]() -> XrResult {
    Action* action = lookup<Action>(handle);
    if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
    eraseBindingsOf(*action->set->instance, action);
    auto& list = action->set->actions;
    list.erase(std::find_if(list.begin(), list.end(), [&](const auto& a) { return a.get() == action; }));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL suggestInteractionProfileBindings(XrInstance handle, const XrInteractionProfileSuggestedBinding* info) {
  return guarded("xrSuggestInteractionProfileBindings", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING);
    if (info->countSuggestedBindings == 0 || info->suggestedBindings == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const std::string* profile = pathString(*instance, info->interactionProfile);
    if (profile == nullptr) return XR_ERROR_PATH_INVALID;
    if (!wellFormedProfile(*profile)) return XR_ERROR_PATH_UNSUPPORTED;
    std::vector<Binding> bindings;
    for (std::uint32_t i = 0; i < info->countSuggestedBindings; ++i) {
      const XrActionSuggestedBinding& b = info->suggestedBindings[i];
      Action* action = lookup<Action>(b.action);
      if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
      if (action->set->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
      const std::string* binding = pathString(*instance, b.binding);
      if (binding == nullptr) return XR_ERROR_PATH_INVALID;
      if (!wellFormedBinding(*instance, *binding)) return XR_ERROR_PATH_UNSUPPORTED;
      bindings.push_back({action, b.binding});
    }
    instance->suggested[info->interactionProfile] = std::move(bindings);  // replaces earlier suggestions
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL attachSessionActionSets(XrSession handle, const XrSessionActionSetsAttachInfo* info) {
  return guarded("xrAttachSessionActionSets", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO);
    if (session->actionSetsAttached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
    if (info->countActionSets == 0 || info->actionSets == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    std::vector<ActionSet*> sets;
    for (std::uint32_t i = 0; i < info->countActionSets; ++i) {
      ActionSet* set = lookup<ActionSet>(info->actionSets[i]);
      if (set == nullptr || set->instance != session->instance) return XR_ERROR_HANDLE_INVALID;
      sets.push_back(set);
    }
    for (ActionSet* set : sets) set->attached = true;
    session->attachedSets = sets;
    session->actionSetsAttached = true;

    // The "connected" controllers: the configured profile if the app suggested it, else the
    // first known profile it suggested.
    Instance& instance = *session->instance;
    std::vector<std::string> order{instance.config.profile};
    order.insert(order.end(), std::begin(kKnownProfiles), std::end(kKnownProfiles));
    for (const std::string& profile : order) {
      const auto id = instance.pathIds.find(profile);
      if (id != instance.pathIds.end() && instance.suggested.count(id->second)) {
        session->currentProfile = id->second;
        break;
      }
    }
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL getCurrentInteractionProfile(XrSession handle, XrPath topLevelPath, XrInteractionProfileState* state) {
  return guarded("xrGetCurrentInteractionProfile", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(state, XR_TYPE_INTERACTION_PROFILE_STATE);
    const std::string* top = pathString(*session->instance, topLevelPath);
    if (top == nullptr) return XR_ERROR_PATH_INVALID;
    if (!session->actionSetsAttached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    const bool hand = *top == "/user/hand/left" || *top == "/user/hand/right";
    if (!hand && *top != "/user/head" && *top != "/user/gamepad") return XR_ERROR_PATH_UNSUPPORTED;
    state->interactionProfile = hand ? session->currentProfile : XR_NULL_PATH;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL enumerateBoundSourcesForAction(XrSession handle, const XrBoundSourcesForActionEnumerateInfo* info,
                                                   std::uint32_t capacity, std::uint32_t* count, XrPath* out) {
  return guarded("xrEnumerateBoundSourcesForAction", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_BOUND_SOURCES_FOR_ACTION_ENUMERATE_INFO);
    Action* action = lookup<Action>(info->action);
    if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!action->set->attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    return twoCall(capacity, count, out, boundPaths(*session, *action, -1));
  });
}

XrResult XRAPI_CALL getInputSourceLocalizedName(XrSession handle, const XrInputSourceLocalizedNameGetInfo* info,
                                                std::uint32_t capacity, std::uint32_t* count, char* buffer) {
  return guarded("xrGetInputSourceLocalizedName", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_INPUT_SOURCE_LOCALIZED_NAME_GET_INFO);
    if (info->whichComponents == 0) return XR_ERROR_VALIDATION_FAILURE;
    const std::string* source = pathString(*session->instance, info->sourcePath);
    if (source == nullptr) return XR_ERROR_PATH_INVALID;
    if (!session->actionSetsAttached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    std::vector<std::string> parts;
    const int hand = handOfPath(*source);
    if (info->whichComponents & XR_INPUT_SOURCE_LOCALIZED_NAME_USER_PATH_BIT)
      parts.push_back(hand == 0 ? "Left Hand" : hand == 1 ? "Right Hand" : "User");
    if ((info->whichComponents & XR_INPUT_SOURCE_LOCALIZED_NAME_INTERACTION_PROFILE_BIT) &&
        session->currentProfile != XR_NULL_PATH) {
      const std::string& profile = *pathString(*session->instance, session->currentProfile);
      parts.push_back(titleCase(profile.substr(profile.rfind('/') + 1)));
    }
    if (info->whichComponents & XR_INPUT_SOURCE_LOCALIZED_NAME_COMPONENT_BIT) {
      const std::size_t io = source->find("put/");  // after /input/ or /output/
      std::string component = io == std::string::npos ? *source : source->substr(io + 4);
      std::replace(component.begin(), component.end(), '/', ' ');
      parts.push_back(titleCase(component));
    }
    std::string name;
    for (const auto& p : parts) name += (name.empty() ? "" : " ") + p;
    return twoCallString(capacity, count, buffer, name);
  });
}

}  // namespace xrsim
