// Session creation, begin/end, exit requests and the state machine's lifecycle transitions.
#include "session.hpp"

#include <algorithm>

#include "api.hpp"
#include "frame_capture.hpp"
#include "vulkan.hpp"

namespace xrsim {

void stopSession(Session& session) {
  if (session.state == XR_SESSION_STATE_FOCUSED) setState(session, XR_SESSION_STATE_VISIBLE);
  if (session.state == XR_SESSION_STATE_VISIBLE) setState(session, XR_SESSION_STATE_SYNCHRONIZED);
  if (session.state == XR_SESSION_STATE_SYNCHRONIZED || session.state == XR_SESSION_STATE_READY)
    setState(session, XR_SESSION_STATE_STOPPING);
}

void loseSession(Session& session) {
  if (session.instance->config.loseInstance) {
    XrEventDataBuffer buffer{XR_TYPE_EVENT_DATA_BUFFER};
    auto* event = reinterpret_cast<XrEventDataInstanceLossPending*>(&buffer);
    *event = {XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING};
    event->lossTime = now();
    pushEvent(*session.instance, buffer);
    session.instance->lost = true;
    return;
  }
  setState(session, XR_SESSION_STATE_LOSS_PENDING);
  session.lost = true;
}

namespace {

const XrGraphicsBindingVulkan2KHR* findBinding(const void* next) {
  for (auto* s = static_cast<const XrBaseInStructure*>(next); s != nullptr; s = s->next)
    if (s->type == XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR) return reinterpret_cast<const XrGraphicsBindingVulkan2KHR*>(s);
  return nullptr;
}

}  // namespace

XrResult XRAPI_CALL createSession(XrInstance handle, const XrSessionCreateInfo* info, XrSession* out) {
  return guarded("xrCreateSession", [&]() -> XrResult {
    Instance* instance = nullptr;
    if (XrResult r = findInstance(handle, instance); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_SESSION_CREATE_INFO);
    if (out == nullptr || info->createFlags != 0) return XR_ERROR_VALIDATION_FAILURE;
    if (XrResult r = checkSystem(*instance, info->systemId); r != XR_SUCCESS) return r;
    const XrGraphicsBindingVulkan2KHR* binding = findBinding(info->next);
    if (binding == nullptr || !instance->vulkan2Enabled) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    if (!instance->requirementsQueried) return XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING;
    if (binding->instance != instance->vkInstance || binding->physicalDevice != instance->physicalDevice ||
        binding->device == VK_NULL_HANDLE)
      return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    if (instance->config.failure == Failure::RefuseSession) return XR_ERROR_INITIALIZATION_FAILED;
    if (!instance->sessions.empty()) return XR_ERROR_LIMIT_REACHED;  // one session at a time, like a headset

    auto session = std::make_unique<Session>();
    session->instance = instance;
    session->vkInstance = binding->instance;
    session->physicalDevice = binding->physicalDevice;
    session->device = binding->device;
    session->queueFamily = binding->queueFamilyIndex;
    session->queueIndex = binding->queueIndex;
    vkGetDeviceQueue(session->device, session->queueFamily, session->queueIndex, &session->queue);
    if (session->queue == VK_NULL_HANDLE) return XR_ERROR_GRAPHICS_DEVICE_INVALID;
    session->commands = std::make_unique<Commands>(*session);
    session->restartsLeft = instance->config.restarts;
    if (!instance->config.outputDir.empty()) {
      session->capture = std::make_unique<FrameCapture>(*session, instance->config.outputDir);
      session->hapticLog.open(instance->config.outputDir / "haptics.jsonl", std::ios::app);
      if (!session->hapticLog) vt::fail("cannot write ", (instance->config.outputDir / "haptics.jsonl").string());
    }
    setState(*session, XR_SESSION_STATE_IDLE);
    setState(*session, XR_SESSION_STATE_READY);
    *out = handleOf(session.get());
    instance->sessions.push_back(std::move(session));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL destroySession(XrSession handle) {
  return guarded("xrDestroySession", [&]() -> XrResult {
    Session* session = lookup<Session>(handle);
    if (session == nullptr) return XR_ERROR_HANDLE_INVALID;
    auto& list = session->instance->sessions;
    list.erase(std::find_if(list.begin(), list.end(), [&](const auto& s) { return s.get() == session; }));
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL beginSession(XrSession handle, const XrSessionBeginInfo* info) {
  return guarded("xrBeginSession", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_SESSION_BEGIN_INFO);
    if (info->primaryViewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO)
      return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
    if (session->running) return XR_ERROR_SESSION_RUNNING;
    if (session->state != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
    session->running = true;
    session->exitRequested = false;
    session->frameWaited = session->frameBegun = false;
    session->framesWaited = session->framesEnded = 0;
    session->beginTime = now();
    session->displayTime = session->beginTime;
    announceTracker(*session);
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL endSession(XrSession handle) {
  return guarded("xrEndSession", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    if (!session->running) return XR_ERROR_SESSION_NOT_RUNNING;
    if (session->state != XR_SESSION_STATE_STOPPING) return XR_ERROR_SESSION_NOT_STOPPING;
    session->running = false;
    session->frameWaited = session->frameBegun = false;
    setState(*session, XR_SESSION_STATE_IDLE);
    if (session->exitRequested || session->restartsLeft == 0) {
      setState(*session, XR_SESSION_STATE_EXITING);
    } else {
      --session->restartsLeft;  // the simulated user puts the headset back on
      setState(*session, XR_SESSION_STATE_READY);
    }
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL requestExitSession(XrSession handle) {
  return guarded("xrRequestExitSession", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    if (!session->running) return XR_ERROR_SESSION_NOT_RUNNING;
    session->exitRequested = true;
    stopSession(*session);
    return XR_SUCCESS;
  });
}

}  // namespace xrsim
