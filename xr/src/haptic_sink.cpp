#include "vt/xr/haptic_sink.hpp"

#include <algorithm>

#include "vt/haptics/frequency_scale.hpp"
#include "vt/xr/openxr_ext_haptic_parametric.hpp"
#include "vt/xr/openxr_fb_haptics.hpp"

namespace vt::xr {
namespace {

/// One controller motor stands for all actuators: the strongest one (-1 when all are silent).
int strongestActuator(const haptics::ActuatorFrame& frame) {
  int strongest = -1;
  float amplitude = 0.0f;
  for (int i = 0; i < frame.actuatorCount && i < haptics::kMaxActuators; ++i)
    if (frame.intensity[std::size_t(i)] > amplitude) {
      amplitude = frame.intensity[std::size_t(i)];
      strongest = i;
    }
  return strongest;
}

}  // namespace

XrHapticSink::XrHapticSink(Headset& headset, int hand)
    : m_headset(headset), m_hand(hand), m_mode(headset.controllerHaptics(hand)) {}

void XrHapticSink::push(const haptics::ActuatorFrame& frame) {
  switch (m_mode) {
    case ControllerHaptics::Pcm: {
      if (frame.blockLength == 0 || frame.sampleRate_hz == 0) return;
      if (float(frame.sampleRate_hz) != m_sampleRate_hz) flush();  // one rate per buffer
      m_sampleRate_hz = float(frame.sampleRate_hz);
      // The motor plays the hand's touch: every actuator's waveform mixed.
      for (int s = 0; s < frame.blockLength && s < haptics::kMaxBlockSamples; ++s) {
        float sum = 0.0f;
        for (int a = 0; a < frame.actuatorCount && a < haptics::kMaxActuators; ++a) sum += frame.block[std::size_t(a)][std::size_t(s)];
        m_samples.push_back(std::clamp(sum, -1.0f, 1.0f));
      }
      if (m_samples.size() + haptics::kMaxBlockSamples > XR_MAX_HAPTIC_PCM_BUFFER_SIZE_FB) flush();
      return;
    }
    case ControllerHaptics::AmplitudeEnvelope: {
      if (frame.blockLength == 0 || frame.sampleRate_hz == 0) return;
      const int strongest = strongestActuator(frame);
      m_samples.push_back(strongest < 0 ? 0.0f : std::clamp(frame.intensity[std::size_t(strongest)], 0.0f, 1.0f));
      m_duration_ns += std::int64_t(frame.blockLength) * 1'000'000'000 / std::int64_t(frame.sampleRate_hz);
      if (m_samples.size() >= XR_MAX_HAPTIC_AMPLITUDE_ENVELOPE_SAMPLES_FB) flush();
      return;
    }
    case ControllerHaptics::Parametric: {
      if (frame.blockLength == 0 || frame.sampleRate_hz == 0) return;
      const int strongest = strongestActuator(frame);
      const float amplitude = strongest < 0 ? 0.0f : std::clamp(frame.intensity[std::size_t(strongest)], 0.0f, 1.0f);
      // A stream starts at its first tick (time 0) and runs on by each tick's duration (the
      // loop's ticks are contiguous); silence ends it at flush.
      if (!m_streaming && m_amplitude.empty()) m_streamTime_ns = 0;
      const std::int64_t t = m_streamTime_ns;
      m_streamTime_ns += std::int64_t(frame.blockLength) * 1'000'000'000 / std::int64_t(frame.sampleRate_hz);
      m_amplitude.push_back({t, amplitude});
      m_frequency.push_back({t, haptics::normaliseFrequency(strongest < 0 ? 0.0f : frame.frequency_hz[std::size_t(strongest)])});
      if (m_amplitude.size() >= XR_HAPTIC_PARAMETRIC_MAX_POINTS_TRANSIENTS_EXT) flushParametric();
      return;
    }
    case ControllerHaptics::Rumble:
      m_newest = frame;
      m_haveNewest = true;
      return;
  }
}

std::int64_t XrHapticSink::latency_ns() const {
  const std::int64_t queued_ns =
      m_sampleRate_hz > 0.0f ? std::int64_t(double(pcmSamplesPending()) * 1e9 / double(m_sampleRate_hz)) : 0;
  return m_headset.displayPeriod_ns() + queued_ns;
}

void XrHapticSink::stop() {
  if (m_on) m_headset.stopVibration(m_hand);
  m_on = false;
  m_streaming = false;
}

void XrHapticSink::flushParametric() {
  if (m_amplitude.empty()) return;
  const bool silent = std::all_of(m_amplitude.begin(), m_amplitude.end(), [](const ParametricPoint& p) { return p.value == 0.0f; });
  if (silent) {
    stop();
    m_amplitude.clear(), m_frequency.clear();
    return;
  }
  // A stream's first frame needs two points spanning the controller's minimum first frame;
  // until then the points wait (a few milliseconds at most).
  const std::int64_t minimumFirst_ns = m_headset.parametricProperties(m_hand).minimumFirstFrame_ns;
  if (!m_streaming && (m_amplitude.size() < 2 || m_amplitude.back().time_ns < minimumFirst_ns) &&
      m_amplitude.size() < XR_HAPTIC_PARAMETRIC_MAX_POINTS_TRANSIENTS_EXT)
    return;
  const ParametricFrame frame = m_streaming ? ParametricFrame::Intermediate : ParametricFrame::First;
  if (m_headset.vibrateParametric(m_hand, m_amplitude.data(), std::uint32_t(m_amplitude.size()), m_frequency.data(),
                                  std::uint32_t(m_frequency.size()), frame)) {
    m_streaming = true;
    m_on = true;
    ++m_pulses;
  } else {
    m_streaming = false;  // refused: the next points start a new stream
  }
  m_amplitude.clear(), m_frequency.clear();
}

void XrHapticSink::flush() {
  if (m_mode == ControllerHaptics::Parametric) return flushParametric();
  if (m_mode == ControllerHaptics::Rumble) {
    if (!m_haveNewest) return;
    m_haveNewest = false;
    const int strongest = strongestActuator(m_newest);
    const float amplitude = strongest < 0 ? 0.0f : std::clamp(m_newest.intensity[std::size_t(strongest)], 0.0f, 1.0f);
    if (amplitude <= 0.0f) return stop();
    m_headset.vibrate(m_hand, amplitude, std::max(0.0f, m_newest.frequency_hz[std::size_t(strongest)]),
                      m_headset.displayPeriod_ns());
    m_on = true;
    ++m_pulses;
    return;
  }
  if (m_samples.empty()) return;
  const bool silent = std::all_of(m_samples.begin(), m_samples.end(), [](float s) { return s == 0.0f; });
  if (silent) {
    stop();
  } else if (m_mode == ControllerHaptics::Pcm) {
    // The runtime says how much it took (a full motor buffer takes less): the rest goes first
    // next time, so the waveform stays continuous, up to a short backlog.
    const std::uint32_t consumed =
        m_headset.vibratePcm(m_hand, m_samples.data(), std::uint32_t(m_samples.size()), m_sampleRate_hz);
    m_on = true;
    ++m_pulses;
    m_samples.erase(m_samples.begin(), m_samples.begin() + std::min<std::size_t>(consumed, m_samples.size()));
    const auto backlog = std::size_t(kMaxPcmBacklog_s * double(m_sampleRate_hz));
    if (m_samples.size() > backlog) {
      const std::size_t excess = m_samples.size() - backlog;
      m_pcmDropped += excess;
      m_samples.erase(m_samples.begin(), m_samples.begin() + long(excess));
    }
    return;
  } else {
    m_headset.vibrateEnvelope(m_hand, m_samples.data(), std::uint32_t(m_samples.size()), m_duration_ns);
    m_on = true;
    ++m_pulses;
  }
  m_samples.clear();
  m_duration_ns = 0;
}

void XrHapticSink::apply(const haptics::ActuatorFrame& frame) {
  push(frame);
  flush();
  // A silent frame ends the vibration whatever the mode (the session's last frame).
  if (strongestActuator(frame) < 0 && frame.blockLength == 0) stop();
}

}  // namespace vt::xr
