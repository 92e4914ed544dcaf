#pragma once
// Turns a HapticClip into the actuator frames a glove (or any sink) plays, tick by tick.
#include <cstdint>
#include <vector>

#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/files/haptic_clip.hpp"

namespace vt::haptics::files {

class ClipPlayer {
 public:
  /// Prepares playback at `tickRate_hz` (main thread): the waveform is resampled to a rate whose
  /// block fits one frame (the clip's own when it can), envelope-only channels get a sine at their
  /// frequency (kNominalFrequency_hz where unknown). Throws vt::Error when the rate is not 100..4000 Hz or the
  /// clip is longer than kMaxClip_s.
  explicit ClipPlayer(const HapticClip& clip, int tickRate_hz = 1000);

  /// Ticks the clip lasts (tick i covers [i, i+1) / tick rate).
  std::uint64_t tickCount() const noexcept { return m_ticks; }
  /// Waveform rate of the frames.
  std::uint32_t sampleRate_hz() const noexcept { return m_rate_hz; }
  /// The frame of tick `tick` (silent past the end). Any thread; no allocation.
  ActuatorFrame frame(std::uint64_t tick) const noexcept;

 private:
  struct Track {
    ActuatorId actuator;
    std::vector<EnvelopePoint> envelope;
    std::vector<float> pcm;  // at m_rate_hz
  };
  std::vector<Track> m_tracks;
  int m_tickRate_hz;
  std::uint32_t m_rate_hz = 8000;
  int m_block = 8;
  std::uint64_t m_ticks = 0;
  std::uint8_t m_actuatorCount = 0;
};

}  // namespace vt::haptics::files
