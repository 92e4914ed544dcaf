// The session state machine (events) and the frame loop.
#include <algorithm>
#include <cmath>

#include "headset_impl.hpp"
#include "vt/core/log.hpp"

namespace vt::xr {
namespace {

CameraView toCameraView(const XrView& view, const glm::mat4& T_world_app, const HeadsetOptions& options) {
  CameraView out;
  out.T_world_eye = T_world_app * poseToMatrix(view.pose);
  out.tanLeft = std::tan(view.fov.angleLeft);
  out.tanRight = std::tan(view.fov.angleRight);
  out.tanDown = std::tan(view.fov.angleDown);
  out.tanUp = std::tan(view.fov.angleUp);
  out.near_m = options.near_m;
  out.far_m = options.far_m;
  return out;
}

// Places the scene in front of the head located at `time`; false while the head is not tracked.
bool placeScene(Headset::Impl& h, XrTime time) {
  XrSpaceLocation head{XR_TYPE_SPACE_LOCATION};
  if (XR_FAILED(xrLocateSpace(h.viewSpace, h.appSpace, time, &head))) return false;
  const XrSpaceLocationFlags needed = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
  if ((head.locationFlags & needed) != needed) return false;
  const glm::mat4 T_app_world = sceneInFrontOfHead(poseToMatrix(head.pose), h.stage, h.options);
  h.T_world_app = glm::inverse(T_app_world);
  h.placed = true;
  h.jumpPending = true;
  ++h.placements;
  vt::log::info("OpenXR: scene placed in front of the head, table top at (", T_app_world[3].x, ", ", T_app_world[3].y,
                ", ", T_app_world[3].z, ") m in ", h.stage ? "STAGE" : "LOCAL");
  return true;
}

void onStateChanged(Headset::Impl& h, XrSessionState state) {
  vt::log::debug("OpenXR: session state ", int(h.state), " -> ", int(state));
  h.state = state;
  switch (state) {
    case XR_SESSION_STATE_READY: {
      XrSessionBeginInfo begin{XR_TYPE_SESSION_BEGIN_INFO};
      begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
      VT_XR_CHECK(xrBeginSession(h.session, &begin));
      h.running = true;
      break;
    }
    case XR_SESSION_STATE_STOPPING:
      VT_XR_CHECK(xrEndSession(h.session));
      h.running = false;
      break;
    case XR_SESSION_STATE_EXITING:
      h.exiting = true;
      h.running = false;
      break;
    case XR_SESSION_STATE_LOSS_PENDING:
      h.lost = true;
      h.running = false;
      break;
    default:
      break;
  }
}

}  // namespace

glm::mat4 sceneInFrontOfHead(const glm::mat4& T_space_head, bool floorAtZero, const HeadsetOptions& options) {
  const glm::vec3 eye(T_space_head[3]);
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  // The head looks down its -Z; looking straight down (or up), its +Y points ahead instead.
  glm::vec3 forward = -glm::vec3(T_space_head[2]);
  forward.y = 0.0f;
  if (glm::length(forward) < 1e-3f) {
    forward = glm::vec3(T_space_head[1]) * (T_space_head[2].y > 0.0f ? 1.0f : -1.0f);
    forward.y = 0.0f;
  }
  if (glm::length(forward) < 1e-3f) forward = {0.0f, 0.0f, -1.0f};
  forward = glm::normalize(forward);
  glm::vec3 origin = eye + forward * options.tableAhead_m;
  origin.y = eye.y - options.tableBelowEyes_m;
  if (floorAtZero) origin.y = std::clamp(origin.y, options.tableMinHeight_m, options.tableMaxHeight_m);
  glm::mat4 T(1.0f);
  T[2] = glm::vec4(-forward, 0.0f);                      // the scene's +Z toward the user
  T[0] = glm::vec4(glm::cross(up, -forward), 0.0f);      // +X to the user's right
  T[3] = glm::vec4(origin, 1.0f);
  return T;
}

void Headset::recenter() {
  if (m_impl->options.placeAtHead) m_impl->placed = false;
}

SessionPhase Headset::pollEvents() {
  Impl& h = *m_impl;
  while (!h.lost) {
    XrEventDataBuffer event{XR_TYPE_EVENT_DATA_BUFFER};
    const XrResult r = xrPollEvent(h.instance, &event);
    if (r == XR_EVENT_UNAVAILABLE) break;
    if (isLoss(r)) {
      h.lost = true;
      break;
    }
    VT_XR_CHECK(r);
    switch (event.type) {
      case XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED: {
        const auto& changed = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
        if (changed.session == h.session) onStateChanged(h, changed.state);
        break;
      }
      case XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING:
        vt::log::warn("OpenXR: instance loss pending (", h.runtimeName, ")");
        h.lost = true;
        h.running = false;
        break;
      case XR_TYPE_EVENT_DATA_REFERENCE_SPACE_CHANGE_PENDING: {
        // The runtime re-centred (or the user redefined the play area): place the scene again.
        const auto& changed = reinterpret_cast<const XrEventDataReferenceSpaceChangePending&>(event);
        const XrReferenceSpaceType type = h.stage ? XR_REFERENCE_SPACE_TYPE_STAGE : XR_REFERENCE_SPACE_TYPE_LOCAL;
        if (changed.session == h.session && changed.referenceSpaceType == type) recenter();
        break;
      }
      case XR_TYPE_EVENT_DATA_EVENTS_LOST:
        vt::log::warn("OpenXR: the runtime dropped events");
        break;
      default:
        break;  // interaction profile changes are read on demand (inputSource)
    }
  }
  if (h.lost) return SessionPhase::LossPending;
  if (h.exiting) return SessionPhase::Exiting;
  return h.running ? SessionPhase::Running : SessionPhase::Idle;
}

void Headset::requestExit() {
  Impl& h = *m_impl;
  if (!h.running) {
    h.exiting = true;  // nothing to stop: done at once
    return;
  }
  const XrResult r = xrRequestExitSession(h.session);
  if (isLoss(r)) h.lost = true;
  else VT_XR_CHECK(r);
}

bool Headset::frame(const RenderEyeFn& render) {
  Impl& h = *m_impl;
  if (!h.running || h.lost) return false;
  // Results that mean loss end the frame quietly; pollEvents then reports LossPending.
  auto ok = [&](XrResult r, const char* call) {
    if (isLoss(r)) {
      h.lost = true;
      return false;
    }
    xrCheck(r, call);
    return true;
  };
  auto acquire = [&](XrSwapchain swapchain, std::uint32_t& index) {
    if (!ok(xrAcquireSwapchainImage(swapchain, nullptr, &index), "xrAcquireSwapchainImage")) return false;
    XrSwapchainImageWaitInfo wait{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO};
    wait.timeout = XR_INFINITE_DURATION;
    return ok(xrWaitSwapchainImage(swapchain, &wait), "xrWaitSwapchainImage");
  };
  XrFrameState frameState{XR_TYPE_FRAME_STATE};
  if (!ok(xrWaitFrame(h.session, nullptr, &frameState), "xrWaitFrame")) return false;
  if (!ok(xrBeginFrame(h.session, nullptr), "xrBeginFrame")) return false;
  h.displayPeriod = frameState.predictedDisplayPeriod;
  if (h.options.placeAtHead && !h.placed) placeScene(h, frameState.predictedDisplayTime);
  if (!ok(h.input->update(h.appSpace, frameState.predictedDisplayTime, h.T_world_app, h.jumpPending), "xrSyncActions"))
    return false;
  h.jumpPending = false;

  std::array<XrCompositionLayerProjectionView, 2> projectionViews{};
  std::array<XrCompositionLayerDepthInfoKHR, 2> depthInfos{};
  XrCompositionLayerProjection layer{XR_TYPE_COMPOSITION_LAYER_PROJECTION};
  bool rendered = false;
  if (frameState.shouldRender) {
    std::array<XrView, 2> views{};
    views.fill({XR_TYPE_VIEW});
    XrViewLocateInfo locate{XR_TYPE_VIEW_LOCATE_INFO};
    locate.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
    locate.displayTime = frameState.predictedDisplayTime;
    locate.space = h.appSpace;
    XrViewState viewState{XR_TYPE_VIEW_STATE};
    std::uint32_t count = 0;
    if (!ok(xrLocateViews(h.session, &locate, &viewState, 2, &count, views.data()), "xrLocateViews")) return false;
    const XrViewStateFlags needed = XR_VIEW_STATE_POSITION_VALID_BIT | XR_VIEW_STATE_ORIENTATION_VALID_BIT;
    if ((viewState.viewStateFlags & needed) == needed && count == 2) {
      for (std::size_t eye = 0; eye < 2; ++eye) {
        EyeSwapchain& swapchain = h.eyes[eye];
        const bool depth = swapchain.depthHandle != XR_NULL_HANDLE;
        std::uint32_t index = 0, depthIndex = 0;
        if (!acquire(swapchain.handle, index)) return false;
        if (depth && !acquire(swapchain.depthHandle, depthIndex)) return false;
        swapchain.target->setCurrentImage(index);
        if (depth) swapchain.target->setCurrentDepthImage(depthIndex);
        render(int(eye), toCameraView(views[eye], h.T_world_app, h.options), *swapchain.target);
        if (!ok(xrReleaseSwapchainImage(swapchain.handle, nullptr), "xrReleaseSwapchainImage")) return false;
        if (depth && !ok(xrReleaseSwapchainImage(swapchain.depthHandle, nullptr), "xrReleaseSwapchainImage")) return false;
        XrCompositionLayerProjectionView& pv = projectionViews[eye];
        pv = {XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW};
        pv.pose = views[eye].pose;
        pv.fov = views[eye].fov;
        pv.subImage.swapchain = swapchain.handle;
        pv.subImage.imageRect = {{0, 0}, swapchain.extent};
        pv.subImage.imageArrayIndex = 0;
        if (depth) {
          // The renderer's projection maps near_m to depth 0 and far_m to 1 (CameraView).
          XrCompositionLayerDepthInfoKHR& info = depthInfos[eye];
          info = {XR_TYPE_COMPOSITION_LAYER_DEPTH_INFO_KHR};
          info.subImage = {swapchain.depthHandle, {{0, 0}, swapchain.extent}, 0};
          info.minDepth = 0.0f;
          info.maxDepth = 1.0f;
          info.nearZ = h.options.near_m;
          info.farZ = h.options.far_m;
          pv.next = &info;
        }
      }
      layer.space = h.appSpace;
      layer.viewCount = 2;
      layer.views = projectionViews.data();
      rendered = true;
    }
  }
  const XrCompositionLayerBaseHeader* layers[] = {reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer)};
  XrFrameEndInfo end{XR_TYPE_FRAME_END_INFO};
  end.displayTime = frameState.predictedDisplayTime;
  end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  end.layerCount = rendered ? 1 : 0;
  end.layers = layers;
  if (!ok(xrEndFrame(h.session, &end), "xrEndFrame")) return false;
  if (rendered) ++h.framesRendered;
  return rendered;
}

void Headset::Impl::applyHaptics(int hand, const XrHapticBaseHeader* feedback) {
  if (!input || !running || lost) return;
  const XrResult r = input->applyFeedback(hand, feedback);
  if (isLoss(r)) lost = true;  // reported by the next pollEvents, not thrown at the haptic caller
  else xrCheck(r, "xrApplyHapticFeedback");
}

void Headset::vibrate(int hand, float amplitude, float frequency_hz, std::int64_t duration_ns) {
  XrHapticVibration vibration{XR_TYPE_HAPTIC_VIBRATION};
  vibration.amplitude = amplitude;
  vibration.frequency = frequency_hz > 0.0f ? frequency_hz : XR_FREQUENCY_UNSPECIFIED;
  vibration.duration = duration_ns > 0 ? duration_ns : XR_MIN_HAPTIC_DURATION;
  m_impl->applyHaptics(hand, reinterpret_cast<const XrHapticBaseHeader*>(&vibration));
}

std::uint32_t Headset::vibratePcm(int hand, const float* samples, std::uint32_t count, float sampleRate_hz) {
  if (controllerHaptics(hand) != ControllerHaptics::Pcm) return 0;
  std::uint32_t consumed = 0;
  XrHapticPcmVibrationFB pcm{XR_TYPE_HAPTIC_PCM_VIBRATION_FB};
  pcm.bufferSize = std::min<std::uint32_t>(count, XR_MAX_HAPTIC_PCM_BUFFER_SIZE_FB);
  pcm.buffer = samples;
  pcm.sampleRate = sampleRate_hz;
  pcm.append = XR_TRUE;  // the blocks follow each other: no gap, no restart
  pcm.samplesConsumed = &consumed;
  m_impl->applyHaptics(hand, reinterpret_cast<const XrHapticBaseHeader*>(&pcm));
  return consumed;
}

void Headset::vibrateEnvelope(int hand, const float* amplitudes, std::uint32_t count, std::int64_t duration_ns) {
  if (controllerHaptics(hand) != ControllerHaptics::AmplitudeEnvelope) return;
  XrHapticAmplitudeEnvelopeVibrationFB envelope{XR_TYPE_HAPTIC_AMPLITUDE_ENVELOPE_VIBRATION_FB};
  envelope.duration = duration_ns;
  envelope.amplitudeCount = std::min<std::uint32_t>(count, XR_MAX_HAPTIC_AMPLITUDE_ENVELOPE_SAMPLES_FB);
  envelope.amplitudes = amplitudes;
  m_impl->applyHaptics(hand, reinterpret_cast<const XrHapticBaseHeader*>(&envelope));
}

void Headset::stopVibration(int hand) {
  Impl& h = *m_impl;
  if (!h.input || !h.running || h.lost) return;
  const XrResult r = h.input->stopVibration(hand);
  if (isLoss(r)) h.lost = true;
  else xrCheck(r, "xrStopHapticFeedback");
}

}  // namespace vt::xr
