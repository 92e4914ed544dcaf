// XR_HTCX_vive_tracker_interaction: one scripted tracker (when the script has a "tracker"),
// its paths, the connected event and its grip pose binding.
#include "api.hpp"

namespace xrsim {
namespace {

constexpr const char* kTrackerProfile = "/interaction_profiles/htc/vive_tracker_htcx";
constexpr const char* kPersistentPath = "/devices/htc/vive_tracker_xrsim";

// Fills the instance's tracker paths (interned); false when the script has no tracker.
bool trackerPaths(Instance& instance) {
  const std::string& role = instance.script.trackerRole();
  if (!instance.viveTrackerEnabled || role.empty()) return false;
  instance.trackerPaths = {XR_TYPE_VIVE_TRACKER_PATHS_HTCX};
  instance.trackerPaths.persistentPath = internPath(instance, kPersistentPath);
  instance.trackerPaths.rolePath = internPath(instance, "/user/vive_tracker_htcx/role/" + role);
  return true;
}

}  // namespace

XrResult XRAPI_CALL enumerateViveTrackerPaths(XrInstance handle, std::uint32_t capacity, std::uint32_t* count,
                                              XrViveTrackerPathsHTCX* out) {
  return guarded("xrEnumerateViveTrackerPathsHTCX", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    std::vector<XrViveTrackerPathsHTCX> list;
    if (trackerPaths(*instance)) list.push_back(instance->trackerPaths);
    if (out != nullptr)
      for (std::uint32_t i = 0; i < capacity && i < list.size(); ++i)
        if (out[i].type != XR_TYPE_VIVE_TRACKER_PATHS_HTCX) return XR_ERROR_VALIDATION_FAILURE;
    if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    *count = std::uint32_t(list.size());
    if (capacity == 0) return XR_SUCCESS;
    if (capacity < list.size()) return XR_ERROR_SIZE_INSUFFICIENT;
    for (std::size_t i = 0; i < list.size(); ++i) {
      out[i].persistentPath = list[i].persistentPath;  // keeps the caller's next pointer
      out[i].rolePath = list[i].rolePath;
    }
    return XR_SUCCESS;
  });
}

void announceTracker(Session& session) {
  Instance& instance = *session.instance;
  if (!trackerPaths(instance)) return;
  XrEventDataBuffer buffer{XR_TYPE_EVENT_DATA_BUFFER};
  auto* event = reinterpret_cast<XrEventDataViveTrackerConnectedHTCX*>(&buffer);
  *event = {XR_TYPE_EVENT_DATA_VIVE_TRACKER_CONNECTED_HTCX};
  event->paths = &instance.trackerPaths;
  pushEvent(instance, buffer);
}

bool trackerBound(const Session& session, const Action& action) {
  const Instance& instance = *session.instance;
  const std::string& role = instance.script.trackerRole();
  if (!instance.viveTrackerEnabled || role.empty()) return false;
  const auto profile = instance.pathIds.find(kTrackerProfile);
  if (profile == instance.pathIds.end()) return false;
  const auto bindings = instance.suggested.find(profile->second);
  if (bindings == instance.suggested.end()) return false;
  const std::string rolePose = "/user/vive_tracker_htcx/role/" + role + "/input/grip/pose";
  const std::string persistentPose = std::string(kPersistentPath) + "/input/grip/pose";
  for (const Binding& b : bindings->second) {
    if (b.action != &action) continue;
    const std::string& text = *pathString(instance, b.path);
    if (text == rolePose || text == persistentPose) return true;
  }
  return false;
}

}  // namespace xrsim
