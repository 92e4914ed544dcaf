// Per-controller haptics (issue #32): PCM where the controller reports a PCM rate, else
// XR_EXT_haptic_parametric where it gives parametric properties, else the envelope, else rumble;
// and the parametric call itself.
#include <algorithm>

#include "headset_impl.hpp"
#include "vt/core/log.hpp"
#include "vt/haptics/frequency_scale.hpp"

namespace vt::xr {

std::string_view controllerHapticsName(ControllerHaptics haptics) noexcept {
  switch (haptics) {
    case ControllerHaptics::Pcm: return "PCM";
    case ControllerHaptics::Parametric: return "parametric";
    case ControllerHaptics::AmplitudeEnvelope: return "envelope";
    case ControllerHaptics::Rumble: break;
  }
  return "rumble";
}

void Headset::Impl::chooseControllerHaptics() {
  PFN_xrGetDeviceSampleRateFB sampleRate = nullptr;
  PFN_xrHapticParametricGetPropertiesEXT parametricProperties = nullptr;
  if (pcmEnabled)
    xrGetInstanceProcAddr(instance, "xrGetDeviceSampleRateFB", reinterpret_cast<PFN_xrVoidFunction*>(&sampleRate));
  if (parametricEnabled)
    xrGetInstanceProcAddr(instance, "xrHapticParametricGetPropertiesEXT", reinterpret_cast<PFN_xrVoidFunction*>(&parametricProperties));
  for (int hand = 0; hand < 2; ++hand) {
    const XrHapticActionInfo info = input->hapticAction(hand);
    ControllerHaptics& chosen = handHaptics[std::size_t(hand)];
    chosen = envelopeEnabled ? ControllerHaptics::AmplitudeEnvelope : ControllerHaptics::Rumble;
    XrHapticParametricPropertiesEXT props{XR_TYPE_HAPTIC_PARAMETRIC_PROPERTIES_EXT};
    if (parametricProperties && XR_SUCCEEDED(parametricProperties(session, &info, &props))) {
      chosen = ControllerHaptics::Parametric;
      parametric[std::size_t(hand)] = {props.idealFrameSubmissionRate, props.minimumFirstFrameDuration, props.minFrequencyHz,
                                       props.maxFrequencyHz};
    }
    XrDevicePcmSampleRateStateFB rate{XR_TYPE_DEVICE_PCM_SAMPLE_RATE_STATE_FB};
    if (sampleRate && XR_SUCCEEDED(sampleRate(session, &info, &rate)) && rate.sampleRate > 0.0f) chosen = ControllerHaptics::Pcm;
  }
}

bool Headset::vibrateParametric(int hand, const ParametricPoint* amplitude, std::uint32_t amplitudeCount,
                                const ParametricPoint* frequency, std::uint32_t frequencyCount, ParametricFrame frame) {
  Impl& h = *m_impl;
  if (controllerHaptics(hand) != ControllerHaptics::Parametric || !h.input || !h.running || h.lost) return false;
  // ParametricPoint has XrHapticParametricPointEXT's layout; copied anyway (at most 500 each).
  std::array<XrHapticParametricPointEXT, XR_HAPTIC_PARAMETRIC_MAX_POINTS_TRANSIENTS_EXT> a{}, f{};
  amplitudeCount = std::min<std::uint32_t>(amplitudeCount, XR_HAPTIC_PARAMETRIC_MAX_POINTS_TRANSIENTS_EXT);
  frequencyCount = std::min<std::uint32_t>(frequencyCount, XR_HAPTIC_PARAMETRIC_MAX_POINTS_TRANSIENTS_EXT);
  for (std::uint32_t i = 0; i < amplitudeCount; ++i) a[i] = {amplitude[i].time_ns, amplitude[i].value};
  for (std::uint32_t i = 0; i < frequencyCount; ++i) f[i] = {frequency[i].time_ns, frequency[i].value};
  XrHapticParametricVibrationEXT vibration{XR_TYPE_HAPTIC_PARAMETRIC_VIBRATION_EXT};
  vibration.amplitudePointCount = amplitudeCount;
  vibration.amplitudePoints = a.data();
  vibration.frequencyPointCount = frequencyCount;
  vibration.frequencyPoints = frequencyCount ? f.data() : nullptr;
  const bool starts = frame == ParametricFrame::Whole || frame == ParametricFrame::First;
  // The frequency scale of the haptic files (vt/haptics/frequency_scale.hpp), set once per event.
  vibration.minFrequencyHz = starts ? haptics::kMinFrequency_hz : XR_FREQUENCY_UNSPECIFIED;
  vibration.maxFrequencyHz = starts ? haptics::kMaxFrequency_hz : XR_FREQUENCY_UNSPECIFIED;
  vibration.streamFrameType = XrHapticParametricStreamFrameTypeEXT(int(frame));
  const XrResult r = h.input->applyFeedback(hand, reinterpret_cast<const XrHapticBaseHeader*>(&vibration));
  if (isLoss(r)) h.lost = true;
  else if (r == XR_ERROR_VALIDATION_FAILURE) {
    log::warn("xrApplyHapticFeedback (parametric) refused a frame: XR_ERROR_VALIDATION_FAILURE");
    return false;
  } else xrCheck(r, "xrApplyHapticFeedback");
  return XR_SUCCEEDED(r);
}

}  // namespace vt::xr
