// xrSyncActions, action state queries and haptic output (logged as JSONL).
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "api.hpp"

namespace xrsim {
namespace {

// The scripted value behind one binding path, e.g. /user/hand/left/input/trigger/value.
struct SourceValue {
  float value = 0.0f;
  glm::vec2 axes{0.0f};
};

SourceValue readSource(const HandSample& hand, const std::string& path) {
  SourceValue out;
  const std::size_t at = path.find("/input/");
  if (at == std::string::npos) return out;
  std::string component = path.substr(at + 7);
  std::string feature;
  if (const std::size_t slash = component.find('/'); slash != std::string::npos) {
    feature = component.substr(slash + 1);
    component.resize(slash);
  }
  if (const auto it = hand.axes.find(component); it != hand.axes.end()) {
    out.axes = it->second;
    if (feature == "x") out.value = it->second.x;
    else if (feature == "y") out.value = it->second.y;
    else if (feature == "click" || feature == "touch") out.value = glm::length(it->second) > 0.5f ? 1.0f : 0.0f;
    return out;
  }
  if (const auto it = hand.buttons.find(component); it != hand.buttons.end()) {
    out.value = it->second;
    if (feature == "click" || feature == "touch") out.value = out.value > 0.5f ? 1.0f : 0.0f;
    if (feature == "touch" && it->second > 0.0f) out.value = 1.0f;
  }
  return out;
}

int slotOf(const Instance& instance, XrPath subaction) {
  if (subaction == XR_NULL_PATH) return 0;
  const std::string* text = pathString(instance, subaction);
  return text == nullptr ? -1 : 1 + handOfPath(*text);
}

// Current value of an action for one slot (0 = all hands, 1 = left, 2 = right).
ActionState evaluate(Session& session, const Action& action, int slot, const Sample& sample) {
  ActionState state;
  for (XrPath path : boundPaths(session, action, slot - 1)) {
    const std::string& text = *pathString(*session.instance, path);
    const int hand = handOfPath(text);
    if (hand < 0 || !sample.hands[hand].controllerTracked) continue;
    const SourceValue v = readSource(sample.hands[hand], text);
    if (!state.active || std::abs(v.value) > std::abs(state.value)) state.value = v.value;
    if (!state.active || glm::length(v.axes) > glm::length(state.axes)) state.axes = v.axes;
    state.active = true;
  }
  if (slot == 0 && trackerBound(session, action) && sample.trackerTracked) state.active = true;
  if (action.actionType == XR_ACTION_TYPE_BOOLEAN_INPUT) state.value = state.value > 0.5f ? 1.0f : 0.0f;
  return state;
}

// Resolves the action and slot of a state query, with the spec's errors.
XrResult stateQuery(Session& session, const XrActionStateGetInfo* info, XrActionType type, Action*& action, int& slot) {
  XRSIM_CHECK_STRUCT(info, XR_TYPE_ACTION_STATE_GET_INFO);
  action = lookup<Action>(info->action);
  if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (!action->set->attached || std::find(session.attachedSets.begin(), session.attachedSets.end(), action->set) ==
                                    session.attachedSets.end())
    return XR_ERROR_ACTIONSET_NOT_ATTACHED;
  if (action->actionType != type) return XR_ERROR_ACTION_TYPE_MISMATCH;
  if (info->subactionPath != XR_NULL_PATH) {
    if (pathString(*session.instance, info->subactionPath) == nullptr) return XR_ERROR_PATH_INVALID;
    const auto& subs = action->subactions;
    if (std::find(subs.begin(), subs.end(), info->subactionPath) == subs.end()) return XR_ERROR_PATH_UNSUPPORTED;
  }
  slot = slotOf(*session.instance, info->subactionPath);
  if (slot < 0 || slot >= kStateSlots) return XR_ERROR_PATH_UNSUPPORTED;
  return XR_SUCCESS;
}

// Validates the action and logs `event` with `payload`'s fields for each hand it is bound to.
XrResult haptic(Session& session, const XrHapticActionInfo* info, const nlohmann::json& payload, const char* event) {
  XRSIM_CHECK_STRUCT(info, XR_TYPE_HAPTIC_ACTION_INFO);
  Action* action = lookup<Action>(info->action);
  if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (std::find(session.attachedSets.begin(), session.attachedSets.end(), action->set) == session.attachedSets.end())
    return XR_ERROR_ACTIONSET_NOT_ATTACHED;
  if (action->actionType != XR_ACTION_TYPE_VIBRATION_OUTPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
  int hand = -1;
  if (info->subactionPath != XR_NULL_PATH) {
    const std::string* text = pathString(*session.instance, info->subactionPath);
    if (text == nullptr) return XR_ERROR_PATH_INVALID;
    const auto& subs = action->subactions;
    if (std::find(subs.begin(), subs.end(), info->subactionPath) == subs.end()) return XR_ERROR_PATH_UNSUPPORTED;
    hand = handOfPath(*text);
  }
  if (session.state != XR_SESSION_STATE_FOCUSED) return XR_SESSION_NOT_FOCUSED;
  if (!session.hapticLog.is_open()) return XR_SUCCESS;
  std::vector<int> hands;
  for (XrPath path : boundPaths(session, *action, hand)) {
    const int h = handOfPath(*pathString(*session.instance, path));
    if (h >= 0 && std::find(hands.begin(), hands.end(), h) == hands.end()) hands.push_back(h);
  }
  for (int h : hands) {
    nlohmann::json line = {{"event", event},
                           {"time_ns", now()},
                           {"display_time_ns", session.displayTime},
                           {"frame", session.framesEnded},
                           {"hand", h == 0 ? "left" : "right"},
                           {"action", action->name}};
    line.update(payload);
    session.hapticLog << line.dump() << '\n';
  }
  session.hapticLog.flush();
  return XR_SUCCESS;
}

// The controller a haptic call names (its subaction path; the right one when it names none).
int handOf(Session& session, const XrHapticActionInfo* info) {
  const std::string* text = info->subactionPath != XR_NULL_PATH ? pathString(*session.instance, info->subactionPath) : nullptr;
  return text && handOfPath(*text) == 0 ? 0 : 1;
}

// Whether the controller of `hand` plays PCM (haptic_pcm_hands lists it).
bool pcmHand(const Session& session, int hand) {
  return session.instance->config.hapticPcmHands.find(hand == 0 ? "left" : "right") != std::string::npos;
}

// XR_EXT_haptic_parametric's timing for xrsim's motor: frames at the display rate, 5 ms first.
constexpr XrDuration kParametricFrameRate_ns = 11'111'111;
constexpr XrDuration kParametricFirstFrame_ns = 5'000'000;
constexpr float kParametricMin_hz = 50.0f, kParametricMax_hz = 500.0f;  // a voice-coil controller

// Points valid as the extension's validation rules say: values in 0..1, times never going back
// (from `from` on), and the first at 0 when `atZero`.
bool validPoints(const XrHapticParametricPointEXT* points, std::uint32_t count, bool atZero, XrDuration from) {
  if (count > XR_HAPTIC_PARAMETRIC_MAX_POINTS_TRANSIENTS_EXT || (count > 0 && points == nullptr)) return false;
  if (count > 0 && atZero && points[0].time != 0) return false;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (!(points[i].value >= 0.0f && points[i].value <= 1.0f)) return false;
    if (points[i].time < (i > 0 ? points[i - 1].time : from)) return false;
  }
  return true;
}

nlohmann::json pointsJson(const XrHapticParametricPointEXT* points, std::uint32_t count) {
  nlohmann::json out = nlohmann::json::array();
  for (std::uint32_t i = 0; i < count; ++i) out.push_back({points[i].time, points[i].value});
  return out;
}

// XR_EXT_haptic_parametric: checked against the extension's validation rules (a failing frame
// changes nothing), then logged with its curves so tests can compare them with the map.
XrResult parametricFeedback(Session& session, const XrHapticActionInfo* info, const XrHapticParametricVibrationEXT* p) {
  XRSIM_CHECK_STRUCT(info, XR_TYPE_HAPTIC_ACTION_INFO);
  Session::ParametricStream& stream = session.parametric[std::size_t(handOf(session, info))];
  const auto type = p->streamFrameType;
  if (type < XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_NONE_EXT || type > XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_LAST_FRAME_EXT)
    return XR_ERROR_VALIDATION_FAILURE;
  const bool starts = type == XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_NONE_EXT || type == XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_FIRST_FRAME_EXT;
  if (!starts && !stream.running) return XR_ERROR_VALIDATION_FAILURE;
  if (p->amplitudePointCount < (starts ? 2u : 1u)) return XR_ERROR_VALIDATION_FAILURE;
  const XrDuration from = starts ? 0 : stream.lastAmplitude_ns;
  if (!validPoints(p->amplitudePoints, p->amplitudePointCount, starts, from) ||
      !validPoints(p->frequencyPoints, p->frequencyPointCount, starts, 0))
    return XR_ERROR_VALIDATION_FAILURE;
  const XrDuration last = p->amplitudePoints[p->amplitudePointCount - 1].time;
  if (type == XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_FIRST_FRAME_EXT && last < kParametricFirstFrame_ns) return XR_ERROR_VALIDATION_FAILURE;
  if (p->frequencyPointCount > 0 && p->frequencyPoints[p->frequencyPointCount - 1].time > last) return XR_ERROR_VALIDATION_FAILURE;
  if (p->transientCount > XR_HAPTIC_PARAMETRIC_MAX_POINTS_TRANSIENTS_EXT || (p->transientCount > 0 && p->transients == nullptr))
    return XR_ERROR_VALIDATION_FAILURE;
  nlohmann::json transients = nlohmann::json::array();
  for (std::uint32_t i = 0; i < p->transientCount; ++i) {
    const auto& t = p->transients[i];
    if ((i > 0 && t.time <= p->transients[i - 1].time) || t.time > last || !(t.amplitude >= 0.0f && t.amplitude <= 1.0f) ||
        !(t.frequency >= 0.0f && t.frequency <= 1.0f))
      return XR_ERROR_VALIDATION_FAILURE;
    transients.push_back({t.time, t.amplitude, t.frequency});
  }
  const bool unspecified = p->minFrequencyHz == XR_FREQUENCY_UNSPECIFIED && p->maxFrequencyHz == XR_FREQUENCY_UNSPECIFIED;
  const bool inRange = p->minFrequencyHz >= XR_HAPTIC_PARAMETRIC_FREQUENCY_MIN_HZ_EXT && p->maxFrequencyHz <= XR_HAPTIC_PARAMETRIC_FREQUENCY_MAX_HZ_EXT &&
                       p->maxFrequencyHz >= p->minFrequencyHz;
  if (!(unspecified || (starts && inRange))) return XR_ERROR_VALIDATION_FAILURE;
  static const char* kFrames[] = {"none", "first", "intermediate", "last"};
  const XrResult r = haptic(session, info,
                            {{"stream", kFrames[type]},
                             {"amplitude", pointsJson(p->amplitudePoints, p->amplitudePointCount)},
                             {"frequency", pointsJson(p->frequencyPoints, p->frequencyPointCount)},
                             {"transients", transients},
                             {"min_frequency_hz", p->minFrequencyHz},
                             {"max_frequency_hz", p->maxFrequencyHz}},
                            "parametric");
  if (r == XR_SUCCESS) {
    stream.running = type == XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_FIRST_FRAME_EXT || type == XR_HAPTIC_PARAMETRIC_STREAM_FRAME_TYPE_INTERMEDIATE_FRAME_EXT;
    stream.lastAmplitude_ns = last;
  }
  return r;
}

// XR_FB_haptic_pcm: the buffer is consumed at once (xrsim has no motor to fill), or up to
// haptic_pcm_capacity samples of it (a motor buffer that is full), and what was taken is logged
// with its samples so tests can compare the waveform with what the app rendered.
XrResult pcmFeedback(Session& session, const XrHapticActionInfo* info, const XrHapticPcmVibrationFB* pcm) {
  if (pcm->bufferSize == 0 || pcm->bufferSize > XR_MAX_HAPTIC_PCM_BUFFER_SIZE_FB || pcm->buffer == nullptr ||
      pcm->samplesConsumed == nullptr || !(pcm->sampleRate > 0.0f))
    return XR_ERROR_VALIDATION_FAILURE;
  XRSIM_CHECK_STRUCT(info, XR_TYPE_HAPTIC_ACTION_INFO);
  if (!pcmHand(session, handOf(session, info))) return XR_ERROR_FEATURE_UNSUPPORTED;
  const double capacity = session.instance->config.hapticPcmCapacity;
  const std::uint32_t taken =
      capacity > 0.0 ? std::min<std::uint32_t>(pcm->bufferSize, std::uint32_t(capacity)) : pcm->bufferSize;
  std::vector<float> samples(pcm->buffer, pcm->buffer + taken);
  if (std::any_of(samples.begin(), samples.end(), [](float s) { return !(s >= -1.0f && s <= 1.0f); }))
    return XR_ERROR_VALIDATION_FAILURE;
  const XrResult r = haptic(session, info,
                            {{"sample_rate_hz", pcm->sampleRate}, {"append", pcm->append == XR_TRUE}, {"samples", samples}}, "pcm");
  if (r == XR_SUCCESS || r == XR_SESSION_NOT_FOCUSED) *pcm->samplesConsumed = r == XR_SUCCESS ? taken : 0;
  return r;
}

// XR_FB_haptic_amplitude_envelope: amplitudes spread over the duration, logged as given.
XrResult envelopeFeedback(Session& session, const XrHapticActionInfo* info, const XrHapticAmplitudeEnvelopeVibrationFB* envelope) {
  if (envelope->amplitudeCount == 0 || envelope->amplitudeCount > XR_MAX_HAPTIC_AMPLITUDE_ENVELOPE_SAMPLES_FB ||
      envelope->amplitudes == nullptr || envelope->duration <= 0)
    return XR_ERROR_VALIDATION_FAILURE;
  std::vector<float> amplitudes(envelope->amplitudes, envelope->amplitudes + envelope->amplitudeCount);
  if (std::any_of(amplitudes.begin(), amplitudes.end(), [](float a) { return !(a >= 0.0f && a <= 1.0f); }))
    return XR_ERROR_VALIDATION_FAILURE;
  return haptic(session, info, {{"duration_ns", envelope->duration}, {"amplitudes", amplitudes}}, "envelope");
}

}  // namespace

XrResult XRAPI_CALL getDeviceSampleRate(XrSession handle, const XrHapticActionInfo* info, XrDevicePcmSampleRateGetInfoFB* out) {
  return guarded("xrGetDeviceSampleRateFB", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_HAPTIC_ACTION_INFO);
    XRSIM_CHECK_STRUCT(out, XR_TYPE_DEVICE_PCM_SAMPLE_RATE_STATE_FB);
    out->sampleRate = pcmHand(*session, handOf(*session, info)) ? kPcmSampleRate_hz : 0.0f;  // 0: no PCM motor
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL hapticParametricGetProperties(XrSession handle, const XrHapticActionInfo* info, XrHapticParametricPropertiesEXT* out) {
  return guarded("xrHapticParametricGetPropertiesEXT", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_HAPTIC_ACTION_INFO);
    XRSIM_CHECK_STRUCT(out, XR_TYPE_HAPTIC_PARAMETRIC_PROPERTIES_EXT);
    Action* action = lookup<Action>(info->action);
    if (action == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (action->actionType != XR_ACTION_TYPE_VIBRATION_OUTPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
    out->idealFrameSubmissionRate = kParametricFrameRate_ns;
    out->minimumFirstFrameDuration = kParametricFirstFrame_ns;
    out->minFrequencyHz = kParametricMin_hz;
    out->maxFrequencyHz = kParametricMax_hz;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL syncActions(XrSession handle, const XrActionsSyncInfo* info) {
  return guarded("xrSyncActions", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(info, XR_TYPE_ACTIONS_SYNC_INFO);
    if (info->countActiveActionSets > 0 && info->activeActionSets == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    std::vector<ActionSet*> active;
    for (std::uint32_t i = 0; i < info->countActiveActionSets; ++i) {
      ActionSet* set = lookup<ActionSet>(info->activeActionSets[i].actionSet);
      if (set == nullptr) return XR_ERROR_HANDLE_INVALID;
      if (std::find(session->attachedSets.begin(), session->attachedSets.end(), set) == session->attachedSets.end())
        return XR_ERROR_ACTIONSET_NOT_ATTACHED;
      const XrPath sub = info->activeActionSets[i].subactionPath;
      if (sub != XR_NULL_PATH && pathString(*session->instance, sub) == nullptr) return XR_ERROR_PATH_INVALID;
      active.push_back(set);
    }
    const bool focused = session->state == XR_SESSION_STATE_FOCUSED;
    if (focused && !session->profileEventSent && session->currentProfile != XR_NULL_PATH) {
      XrEventDataBuffer buffer{XR_TYPE_EVENT_DATA_BUFFER};
      auto* event = reinterpret_cast<XrEventDataInteractionProfileChanged*>(&buffer);
      *event = {XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED};
      event->session = handle;
      pushEvent(*session->instance, buffer);
      session->profileEventSent = true;
    }
    const XrTime time = session->displayTime;
    const Sample sample = sampleAt(*session, time);
    for (ActionSet* set : session->attachedSets) {
      const bool isActive = focused && std::find(active.begin(), active.end(), set) != active.end();
      for (const auto& action : set->actions)
        for (int slot = 0; slot < kStateSlots; ++slot) {
          ActionState next = isActive ? evaluate(*session, *action, slot, sample) : ActionState{};
          ActionState& prev = action->state[std::size_t(slot)];
          next.changed = prev.active && next.active && (next.value != prev.value || next.axes != prev.axes);
          next.lastChange = next.changed ? time : prev.lastChange;
          prev = next;
        }
    }
    return focused ? XR_SUCCESS : XR_SESSION_NOT_FOCUSED;
  });
}

namespace {

// The three value-carrying action queries differ only in the struct they fill.
template <class State, class Fill>
XrResult valueActionState(const char* call, XrSession handle, const XrActionStateGetInfo* info, XrActionType type,
                          XrStructureType structType, State* out, Fill fillValue) {
  return guarded(call, [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    Action* action = nullptr;
    int slot = 0;
    if (XrResult r = stateQuery(*session, info, type, action, slot); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(out, structType);
    const ActionState& s = action->state[std::size_t(slot)];
    fillValue(s, *out);
    out->changedSinceLastSync = s.changed ? XR_TRUE : XR_FALSE;
    out->lastChangeTime = s.lastChange;
    out->isActive = s.active ? XR_TRUE : XR_FALSE;
    return XR_SUCCESS;
  });
}

}  // namespace

XrResult XRAPI_CALL getActionStateBoolean(XrSession handle, const XrActionStateGetInfo* info, XrActionStateBoolean* out) {
  return valueActionState("xrGetActionStateBoolean", handle, info, XR_ACTION_TYPE_BOOLEAN_INPUT,
                          XR_TYPE_ACTION_STATE_BOOLEAN, out, [](const ActionState& s, XrActionStateBoolean& o) {
                            o.currentState = s.value > 0.5f ? XR_TRUE : XR_FALSE;
                          });
}

XrResult XRAPI_CALL getActionStateFloat(XrSession handle, const XrActionStateGetInfo* info, XrActionStateFloat* out) {
  return valueActionState("xrGetActionStateFloat", handle, info, XR_ACTION_TYPE_FLOAT_INPUT,
                          XR_TYPE_ACTION_STATE_FLOAT, out,
                          [](const ActionState& s, XrActionStateFloat& o) { o.currentState = s.value; });
}

XrResult XRAPI_CALL getActionStateVector2f(XrSession handle, const XrActionStateGetInfo* info, XrActionStateVector2f* out) {
  return valueActionState("xrGetActionStateVector2f", handle, info, XR_ACTION_TYPE_VECTOR2F_INPUT,
                          XR_TYPE_ACTION_STATE_VECTOR2F, out,
                          [](const ActionState& s, XrActionStateVector2f& o) { o.currentState = {s.axes.x, s.axes.y}; });
}

XrResult XRAPI_CALL getActionStatePose(XrSession handle, const XrActionStateGetInfo* info, XrActionStatePose* out) {
  return guarded("xrGetActionStatePose", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    Action* action = nullptr;
    int slot = 0;
    if (XrResult r = stateQuery(*session, info, XR_ACTION_TYPE_POSE_INPUT, action, slot); r != XR_SUCCESS) return r;
    XRSIM_CHECK_STRUCT(out, XR_TYPE_ACTION_STATE_POSE);
    out->isActive = action->state[std::size_t(slot)].active ? XR_TRUE : XR_FALSE;
    return XR_SUCCESS;
  });
}

XrResult XRAPI_CALL applyHapticFeedback(XrSession handle, const XrHapticActionInfo* info, const XrHapticBaseHeader* feedback) {
  return guarded("xrApplyHapticFeedback", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    if (feedback == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (feedback->type == XR_TYPE_HAPTIC_PCM_VIBRATION_FB && session->instance->hapticPcmEnabled)
      return pcmFeedback(*session, info, reinterpret_cast<const XrHapticPcmVibrationFB*>(feedback));
    if (feedback->type == XR_TYPE_HAPTIC_AMPLITUDE_ENVELOPE_VIBRATION_FB && session->instance->hapticEnvelopeEnabled)
      return envelopeFeedback(*session, info, reinterpret_cast<const XrHapticAmplitudeEnvelopeVibrationFB*>(feedback));
    if (feedback->type == XR_TYPE_HAPTIC_PARAMETRIC_VIBRATION_EXT && session->instance->hapticParametricEnabled)
      return parametricFeedback(*session, info, reinterpret_cast<const XrHapticParametricVibrationEXT*>(feedback));
    XRSIM_CHECK_STRUCT(feedback, XR_TYPE_HAPTIC_VIBRATION);
    const auto* vibration = reinterpret_cast<const XrHapticVibration*>(feedback);
    if (vibration->amplitude < 0.0f || vibration->amplitude > 1.0f || vibration->frequency < 0.0f)
      return XR_ERROR_VALIDATION_FAILURE;
    return haptic(*session, info,
                  {{"amplitude", vibration->amplitude}, {"frequency_hz", vibration->frequency}, {"duration_ns", vibration->duration}},
                  "apply");
  });
}

XrResult XRAPI_CALL stopHapticFeedback(XrSession handle, const XrHapticActionInfo* info) {
  return guarded("xrStopHapticFeedback", [&]() -> XrResult {
    Session* session = nullptr;
    if (XrResult r = findSession(handle, session); r != XR_SUCCESS) return r;
    const XrResult r = haptic(*session, info, nlohmann::json::object(), "stop");
    if (r == XR_SUCCESS) session->parametric[std::size_t(handOf(*session, info))].running = false;
    return r;
  });
}

}  // namespace xrsim
