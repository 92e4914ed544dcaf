#pragma once
// Actuator frames from the haptic loop -> controller vibration, so a standard headset's
// controllers feel the vibration maps without a glove. Each controller plays the richest its
// runtime offers it (Headset::controllerHaptics(hand)): with XR_FB_haptic_pcm the texture
// waveform itself (all actuators mixed, the blocks appended back to back); with
// XR_EXT_haptic_parametric the strongest actuator's level and frequency as curves, one point per
// haptic tick, streamed one frame per display frame; with XR_FB_haptic_amplitude_envelope the
// levels as an envelope; otherwise a rumble at the strongest actuator's level and frequency.
// Render thread only (OpenXR session thread).
#include <cstdint>
#include <vector>

#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/actuator_sink.hpp"
#include "vt/xr/headset.hpp"

namespace vt::xr {

class XrHapticSink final : public haptics::ActuatorSink {
 public:
  /// Vibrates the controller of `hand` (0 left, 1 right); `headset` must outlive the sink.
  XrHapticSink(Headset& headset, int hand);
  /// Takes the loop's frames in order (every one of them for PCM and envelopes).
  void push(const haptics::ActuatorFrame& frame);
  // flush() (below), once per display frame: sends what push() collected. PCM: the mixed blocks;
  // parametric: the ticks' points as the next frame of a stream; envelope: one amplitude per
  // frame over their duration; rumble: the newest frame for one display period. Silence stops
  // the vibration (once).
  /// push + flush, for a caller with one frame per display frame.
  void apply(const haptics::ActuatorFrame& frame);
  /// Feedback calls made so far (pulses, PCM buffers or envelopes).
  std::uint64_t pulses() const { return m_pulses; }
  /// PCM samples the runtime did not take, dropped because the backlog outgrew kMaxPcmBacklog_s
  /// (the oldest go first: late texture is worse than a gap).
  std::uint64_t pcmSamplesDropped() const { return m_pcmDropped; }
  /// PCM samples waiting for the runtime (offered again first at the next flush).
  std::size_t pcmSamplesPending() const { return m_mode == ControllerHaptics::Pcm ? m_samples.size() : 0; }
  /// Longest PCM backlog kept for a runtime that takes less than it is given.
  static constexpr double kMaxPcmBacklog_s = 0.05;
  ControllerHaptics mode() const { return m_mode; }
  /// ActuatorSink: the main thread delivers every frame (push) and flushes once per display
  /// frame; a frame is felt after the rest of its display frame plus what the runtime still
  /// holds queued ahead of it.
  std::string name() const override { return "xr controller"; }
  haptics::SinkThread thread() const override { return haptics::SinkThread::Main; }
  void deliver(const haptics::ActuatorFrame& frame) override { push(frame); }
  void flush() override;
  std::int64_t latency_ns() const override;
  /// Ends any vibration (once).
  void stop() override;

 private:

  Headset& m_headset;
  int m_hand;
  ControllerHaptics m_mode;
  void flushParametric();

  std::vector<float> m_samples;      // PCM samples or envelope amplitudes since the last flush
  std::vector<ParametricPoint> m_amplitude, m_frequency;  // parametric points since the last flush
  std::int64_t m_streamTime_ns = 0;  // the next tick's time in the running parametric stream
  bool m_streaming = false;
  float m_sampleRate_hz = 0.0f;      // of m_samples (PCM)
  std::int64_t m_duration_ns = 0;    // covered by m_samples (envelope)
  haptics::ActuatorFrame m_newest;   // rumble
  bool m_haveNewest = false;
  bool m_on = false;
  std::uint64_t m_pulses = 0;
  std::uint64_t m_pcmDropped = 0;
};

}  // namespace vt::xr
