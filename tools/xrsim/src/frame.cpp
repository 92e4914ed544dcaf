// The frame loop (xrWaitFrame / xrBeginFrame / xrEndFrame) and view locations.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include "api.hpp"
#include "frame_capture.hpp"
#include "session.hpp"

namespace xrsim {
namespace {

XrResult validateSwapchainImage(const Session& session, const XrSwapchainSubImage& sub) {
  Swapchain* swapchain = lookup<Swapchain>(sub.swapchain);
  if (swapchain == nullptr || swapchain->session != &session) return XR_ERROR_HANDLE_INVALID;
  if (swapchain->lastReleased < 0) return XR_ERROR_LAYER_INVALID;  // never released: nothing to show
  const auto& r = sub.imageRect;
  if (r.offset.x < 0 || r.offset.y < 0 || r.extent.width <= 0 || r.extent.height <= 0 ||
      std::uint32_t(r.offset.x + r.extent.width) > swapchain->info.width ||
      std::uint32_t(r.offset.y + r.extent.height) > swapchain->info.height)
    return XR_ERROR_SWAPCHAIN_RECT_INVALID;
  if (sub.imageArrayIndex >= swapchain->info.arraySize) return XR_ERROR_VALIDATION_FAILURE;
  return XR_SUCCESS;
}

const XrCompositionLayerDepthInfoKHR* depthInfo(const XrCompositionLayerProjectionView& view) {
  for (auto* next = static_cast<const XrBaseInStructure*>(view.next); next != nullptr; next = next->next)
    if (next->type == XR_TYPE_COMPOSITION_LAYER_DEPTH_INFO_KHR) return reinterpret_cast<const XrCompositionLayerDepthInfoKHR*>(next);
  return nullptr;
}

XrResult validateProjection(const Session& session, const XrCompositionLayerProjection& layer) {
  if (layer.viewCount != 2 || layer.views == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (std::uint32_t v = 0; v < layer.viewCount; ++v) {
    const auto& view = layer.views[v];
    if (view.type != XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW) return XR_ERROR_VALIDATION_FAILURE;
    if (!validPose(view.pose)) return XR_ERROR_POSE_INVALID;
    if (XrResult r = validateSwapchainImage(session, view.subImage); r != XR_SUCCESS) return r;
    for (auto* next = static_cast<const XrBaseInStructure*>(view.next); next != nullptr; next = next->next) {
      if (next->type != XR_TYPE_COMPOSITION_LAYER_DEPTH_INFO_KHR) continue;
      if (!session.instance->depthEnabled) return XR_ERROR_VALIDATION_FAILURE;
      const auto* depth = reinterpret_cast<const XrCompositionLayerDepthInfoKHR*>(next);
      if (XrResult r = validateSwapchainImage(session, depth->subImage); r != XR_SUCCESS) return r;
      if ((lookup<Swapchain>(depth->subImage.swapchain)->aspect & VK_IMAGE_ASPECT_DEPTH_BIT) == 0)
        return XR_ERROR_VALIDATION_FAILURE;  // depth info must name a depth swapchain
      if (depth->minDepth < 0.0f || depth->maxDepth > 1.0f || depth->minDepth >= depth->maxDepth ||
          depth->nearZ == depth->farZ)
        return XR_ERROR_VALIDATION_FAILURE;
    }
  }
  return XR_SUCCESS;
}

XrResult validateLayers(const Session& session, const XrFrameEndInfo& info) {
  if (info.layerCount > 16) return XR_ERROR_LAYER_LIMIT_EXCEEDED;
  if (info.layerCount > 0 && info.layers == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (std::uint32_t i = 0; i < info.layerCount; ++i) {
    const XrCompositionLayerBaseHeader* layer = info.layers[i];
    if (layer == nullptr) return XR_ERROR_LAYER_INVALID;
    Space* space = lookup<Space>(layer->space);
    if (space == nullptr || space->session != &session) return XR_ERROR_HANDLE_INVALID;
    if (layer->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION) {
      if (XrResult r = validateProjection(session, *reinterpret_cast<const XrCompositionLayerProjection*>(layer)); r != XR_SUCCESS)
        return r;
    } else if (layer->type == XR_TYPE_COMPOSITION_LAYER_QUAD) {
      const auto* quad = reinterpret_cast<const XrCompositionLayerQuad*>(layer);
      if (!validPose(quad->pose)) return XR_ERROR_POSE_INVALID;
      if (XrResult r = validateSwapchainImage(session, quad->subImage); r != XR_SUCCESS) return r;
    } else {
      return XR_ERROR_LAYER_INVALID;
    }
  }
  return XR_SUCCESS;
}

void captureFrame(Session& session, const XrFrameEndInfo& info) {
  const std::uint64_t every = session.instance->config.saveEvery;
  if (!session.capture || every == 0 || session.framesEnded % every != 0) return;
  for (std::uint32_t i = 0; i < info.layerCount; ++i) {
    if (info.layers[i]->type != XR_TYPE_COMPOSITION_LAYER_PROJECTION) continue;
    const auto* layer = reinterpret_cast<const XrCompositionLayerProjection*>(info.layers[i]);
    const char* eyes[2] = {"left", "right"};
    for (std::uint32_t v = 0; v < 2; ++v) {
      session.capture->save(layer->views[v], session.framesEnded, eyes[v]);
      if (const XrCompositionLayerDepthInfoKHR* depth = depthInfo(layer->views[v]))
        session.capture->saveDepth(*depth, session.framesEnded, eyes[v]);
    }
    return;  // the first projection layer is the scene
  }
}

}  // namespace

XrResult XRAPI_CALL waitFrame(XrSession handle, const XrFrameWaitInfo* info, XrFrameState* state) {
  XrTime wakeAt = 0;  // realtime pacing sleeps after the lock is released
  const XrResult result = guarded("xrWaitFrame", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    if (info != nullptr && info->type != XR_TYPE_FRAME_WAIT_INFO) return XR_ERROR_VALIDATION_FAILURE;
    XRSIM_CHECK_STRUCT(state, XR_TYPE_FRAME_STATE);
    if (!session->running) return XR_ERROR_SESSION_NOT_RUNNING;
    // Display times advance one frame period per frame from xrBeginSession, independent of
    // how slowly software rendering runs: scripted input then replays identically.
    const Config& config = session->instance->config;
    const auto period = XrDuration(1e9 / config.frameRate_hz);
    ++session->framesWaited;
    if (config.realtime) {
      // One period after the previous frame, or one period from now when the app runs late.
      session->displayTime = std::max(session->displayTime + period, now() + period);
      wakeAt = session->displayTime - period;
    } else {
      session->displayTime = session->beginTime + XrTime(session->framesWaited) * period;
    }
    if (session->state == XR_SESSION_STATE_READY) setState(*session, XR_SESSION_STATE_SYNCHRONIZED);
    state->predictedDisplayTime = session->displayTime;
    state->predictedDisplayPeriod = period;
    state->shouldRender = (session->state == XR_SESSION_STATE_VISIBLE || session->state == XR_SESSION_STATE_FOCUSED)
                              ? XR_TRUE : XR_FALSE;
    session->frameWaited = true;
    return XR_SUCCESS;
  });
  if (result == XR_SUCCESS && wakeAt > now()) std::this_thread::sleep_for(std::chrono::nanoseconds(wakeAt - now()));
  return result;
}

XrResult XRAPI_CALL beginFrame(XrSession handle, const XrFrameBeginInfo* info) {
  return guarded("xrBeginFrame", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    if (info != nullptr && info->type != XR_TYPE_FRAME_BEGIN_INFO) return XR_ERROR_VALIDATION_FAILURE;
    if (!session->running) return XR_ERROR_SESSION_NOT_RUNNING;
    if (!session->frameWaited) return XR_ERROR_CALL_ORDER_INVALID;
    session->frameWaited = false;
    if (session->frameBegun) return XR_FRAME_DISCARDED;  // the previous begun frame is dropped
    session->frameBegun = true;
    return XR_SUCCESS;
  });
}

namespace {

// The user re-centred (a system button on a real headset): one change-pending event per
// reference space type, effective at the next display time. The spaces themselves stay put.
void recenter(Session& session) {
  for (const XrReferenceSpaceType type : {XR_REFERENCE_SPACE_TYPE_LOCAL, XR_REFERENCE_SPACE_TYPE_STAGE}) {
    XrEventDataBuffer buffer{XR_TYPE_EVENT_DATA_BUFFER};
    auto* event = reinterpret_cast<XrEventDataReferenceSpaceChangePending*>(&buffer);
    *event = {XR_TYPE_EVENT_DATA_REFERENCE_SPACE_CHANGE_PENDING};
    event->session = handleOf(&session);
    event->referenceSpaceType = type;
    event->changeTime = session.displayTime;
    event->poseValid = XR_FALSE;
    pushEvent(*session.instance, buffer);
  }
}

}  // namespace

XrResult XRAPI_CALL endFrame(XrSession handle, const XrFrameEndInfo* info) {
  return guarded("xrEndFrame", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_FRAME_END_INFO);
    if (!session->running) return XR_ERROR_SESSION_NOT_RUNNING;
    if (!session->frameBegun) return XR_ERROR_CALL_ORDER_INVALID;
    if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
    if (info->environmentBlendMode != XR_ENVIRONMENT_BLEND_MODE_OPAQUE) return XR_ERROR_ENVIRONMENT_BLEND_MODE_UNSUPPORTED;
    if (XrResult r = validateLayers(*session, *info); r != XR_SUCCESS) return r;
    session->frameBegun = false;
    ++session->framesEnded;
    captureFrame(*session, *info);

    const Config& config = session->instance->config;
    if (session->state == XR_SESSION_STATE_SYNCHRONIZED && !session->exitRequested) {
      setState(*session, XR_SESSION_STATE_VISIBLE);
      setState(*session, XR_SESSION_STATE_FOCUSED);
    }
    if (config.stopAfterFrames != 0 && session->framesEnded == config.stopAfterFrames) stopSession(*session);
    if (config.loseAfterFrames != 0 && session->framesEnded == config.loseAfterFrames) loseSession(*session);
    if (config.recenterAfterFrames != 0 && session->framesEnded == config.recenterAfterFrames) recenter(*session);
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL locateViews(XrSession handle, const XrViewLocateInfo* info, XrViewState* viewState,
                                std::uint32_t capacity, std::uint32_t* count, XrView* views) {
  return guarded("xrLocateViews", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_VIEW_LOCATE_INFO);
    XRSIM_CHECK_STRUCT(viewState, XR_TYPE_VIEW_STATE);
    if (info->viewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO)
      return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
    if (info->displayTime <= 0) return XR_ERROR_TIME_INVALID;
    Space* base = lookup<Space>(info->space);
    if (base == nullptr || base->session != session) return XR_ERROR_HANDLE_INVALID;
    if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    *count = 2;
    if (capacity == 0) return XR_SUCCESS;
    if (capacity < 2) return XR_ERROR_SIZE_INSUFFICIENT;
    if (views == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    for (std::uint32_t i = 0; i < 2; ++i)
      if (views[i].type != XR_TYPE_VIEW) return XR_ERROR_VALIDATION_FAILURE;

    const Config& config = session->instance->config;
    Pose T_stage_base;
    if (!spacePose(*session, *base, info->displayTime, T_stage_base)) {
      viewState->viewStateFlags = 0;
      return XR_SUCCESS;
    }
    const Pose head = sampleAt(*session, info->displayTime).head;
    const Pose T_base_stage = inverse(T_stage_base);
    const float ax = std::atan(config.tanHalfFovX), ay = std::atan(config.tanHalfFovY);
    for (int eye = 0; eye < 2; ++eye) {
      Pose T_head_eye;
      T_head_eye.position.x = (eye == 0 ? -0.5f : 0.5f) * config.ipd_m;
      views[eye].pose = toXr(compose(T_base_stage, compose(head, T_head_eye)));
      views[eye].fov = {-ax, ax, ay, -ay};
    }
    viewState->viewStateFlags = XR_VIEW_STATE_ORIENTATION_VALID_BIT | XR_VIEW_STATE_POSITION_VALID_BIT |
                                XR_VIEW_STATE_ORIENTATION_TRACKED_BIT | XR_VIEW_STATE_POSITION_TRACKED_BIT;
    return XR_SUCCESS;
  });
}

}  // namespace xrsim
