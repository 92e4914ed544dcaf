// Registry, locking, paths, events and pose maths shared by the entry points.
#include <chrono>
#include <unordered_set>

#include "api.hpp"
#include "frame_capture.hpp"
#include "vulkan.hpp"

namespace xrsim {
namespace {

std::unordered_set<const void*>& registry() {
  static std::unordered_set<const void*> live;
  return live;
}

}  // namespace

std::recursive_mutex& apiMutex() noexcept {
  static std::recursive_mutex mutex;
  return mutex;
}

Object::Object(XrObjectType objectType) : type(objectType) { registry().insert(this); }
Object::~Object() { registry().erase(this); }
bool isLive(const void* p) noexcept { return p != nullptr && registry().count(p) != 0; }

Session::Session() : Object(kType) {}
Session::~Session() {
  // Children first: swapchain images live on the application's device we still know.
  handTrackers.clear();
  spaces.clear();
  capture.reset();
  swapchains.clear();
  commands.reset();
}
Instance::~Instance() {
  sessions.clear();
  actionSets.clear();
}

XrResult findInstance(XrInstance handle, Instance*& out) noexcept {
  out = lookup<Instance>(handle);
  if (out == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (out->lost) return XR_ERROR_INSTANCE_LOST;
  return XR_SUCCESS;
}

XrResult findSession(XrSession handle, Session*& out) noexcept {
  out = lookup<Session>(handle);
  if (out == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (out->instance->lost) return XR_ERROR_INSTANCE_LOST;
  if (out->lost) return XR_ERROR_SESSION_LOST;
  return XR_SUCCESS;
}

XrResult twoCallString(std::uint32_t capacity, std::uint32_t* countOut, char* out, const std::string& text) {
  if (countOut == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *countOut = std::uint32_t(text.size() + 1);
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < text.size() + 1) return XR_ERROR_SIZE_INSUFFICIENT;
  if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  std::memcpy(out, text.c_str(), text.size() + 1);
  return XR_SUCCESS;
}

XrTime now() noexcept {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

bool wellFormedPath(const std::string& path) noexcept {
  // Spec 6.1: "/" then components of [a-z0-9-_.], no empty components, no trailing slash,
  // no component made only of dots.
  if (path.size() < 2 || path.size() >= XR_MAX_PATH_LENGTH || path.front() != '/' || path.back() == '/') return false;
  std::size_t componentStart = 1;
  bool onlyDots = true;
  for (std::size_t i = 1; i <= path.size(); ++i) {
    if (i == path.size() || path[i] == '/') {
      if (i == componentStart || onlyDots) return false;
      componentStart = i + 1;
      onlyDots = true;
      continue;
    }
    const char c = path[i];
    const bool allowed = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
    if (!allowed) return false;
    if (c != '.') onlyDots = false;
  }
  return true;
}

XrPath internPath(Instance& instance, const std::string& path) {
  const auto it = instance.pathIds.find(path);
  if (it != instance.pathIds.end()) return it->second;
  const XrPath id = instance.pathStrings.size();
  instance.pathStrings.push_back(path);
  instance.pathIds.emplace(path, id);
  return id;
}

const std::string* pathString(const Instance& instance, XrPath path) noexcept {
  if (path == XR_NULL_PATH || path >= instance.pathStrings.size()) return nullptr;
  return &instance.pathStrings[path];
}

void pushEvent(Instance& instance, const XrEventDataBuffer& event) { instance.events.push_back(event); }

void setState(Session& session, XrSessionState state) {
  session.state = state;
  XrEventDataBuffer buffer{XR_TYPE_EVENT_DATA_BUFFER};
  auto* event = reinterpret_cast<XrEventDataSessionStateChanged*>(&buffer);
  *event = {XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED};
  event->session = handleOf(&session);
  event->state = state;
  event->time = now();
  pushEvent(*session.instance, buffer);
  vt::log::debug("xrsim: session state -> ", int(state));
}

Sample sampleAt(const Session& session, XrTime time) {
  const double t_s = session.beginTime == 0 ? 0.0 : double(time - session.beginTime) * 1e-9;
  return session.instance->script.sample(std::max(0.0, t_s));
}

Pose fromXr(const XrPosef& pose) noexcept {
  return {{pose.position.x, pose.position.y, pose.position.z},
          {pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z}};
}

XrPosef toXr(const Pose& pose) noexcept {
  XrPosef out;
  out.position = {pose.position.x, pose.position.y, pose.position.z};
  out.orientation = {pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w};
  return out;
}

Pose compose(const Pose& a, const Pose& b) noexcept {
  return {a.position + a.orientation * b.position, glm::normalize(a.orientation * b.orientation)};
}

Pose inverse(const Pose& a) noexcept {
  const glm::quat q = glm::conjugate(a.orientation);
  return {-(q * a.position), q};
}

bool validPose(const XrPosef& pose) noexcept {
  const auto& q = pose.orientation;
  const float norm = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  return std::abs(norm - 1.0f) < 0.01f;
}

int handOfPath(const std::string& path) noexcept {
  auto under = [&](const char* prefix) {
    const std::size_t n = std::strlen(prefix);
    return path.compare(0, n, prefix) == 0 && (path.size() == n || path[n] == '/');
  };
  if (under("/user/hand/left")) return 0;
  if (under("/user/hand/right")) return 1;
  return -1;
}

}  // namespace xrsim
