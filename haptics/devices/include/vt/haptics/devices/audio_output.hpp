#pragma once
// Drives voice-coil tactors and LRAs through a multichannel audio interface and an amplifier
// (the Syntacts approach): each actuator's waveform (the haptic loop's 8 kHz texture signal) is
// resampled to the device rate and played on its own channel of an ALSA PCM ("default",
// "plughw:CARD=...", "pipewire", or a test's file plugin). A writer thread consumes the loop's
// frames from an SpscRing and blocks on the device; the haptic thread never waits for it.
// Every exit path (stop, SIGINT/SIGTERM, a stalled loop) plays silence.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "vt/haptics/devices/queued_output.hpp"

namespace vt::haptics {

/// Parses "thumb,index,-,middle": device channel c plays the named actuator ("-": silent).
/// Throws vt::Error naming the entry when a name is unknown. Any thread.
std::vector<int> parseChannelMap(std::string_view text);

struct AudioOutputConfig {
  std::string device = "default";  // ALSA PCM name
  std::vector<int> channels;       // device channel -> actuator index (-1 silent); empty: 0..actuators-1
  int actuators = 5;               // channels when `channels` is empty
  unsigned rate_hz = 48000;        // asked of the device (ALSA's plug layer converts if needed)
  unsigned latency_us = 4000;      // device buffer; periods are a quarter of it
  FailsafeConfig failsafe;
  /// The haptic loop's tick counter (must outlive the output); nullptr: queued frames are the heartbeat.
  const std::atomic<std::uint64_t>* heartbeat = nullptr;
};

/// A snapshot for the HUD and --json.
struct AudioOutputStatus {
  std::string device;
  unsigned rate_hz = 0, channels = 0, period_frames = 0, buffer_frames = 0;
  bool clocked = true;               // false: the device consumes instantly (null/file), paced by the steady clock
  std::uint64_t framesWritten = 0;   // device frames (one sample per channel)
  std::uint64_t underruns = 0;       // device underruns (xruns) recovered
  std::uint64_t starvedFrames = 0;   // device frames padded with silence for want of input
  std::uint64_t skippedSamples = 0;  // input samples dropped to keep the latency bounded
  std::uint64_t queueDropped = 0;    // actuator frames refused by a full queue
  std::uint64_t reopens = 0;         // times the device was opened anew after a failed write
  FailsafeReason failsafe = FailsafeReason::None;
  std::string lastError;
};

/// One line per ALSA playback PCM: "NAME - description".
struct AudioDeviceInfo {
  std::string name, description;
};
/// Main thread: the playback devices ALSA knows (name hints), "default" first when present.
std::vector<AudioDeviceInfo> listAudioDevices();

class AudioOutput final : public QueuedOutput {
 public:
  /// Opens and configures the device (throws vt::Error naming the device and the step that
  /// failed), then starts the writer thread. Main thread.
  explicit AudioOutput(AudioOutputConfig config, const Clock& clock = SteadyClock::instance());
  /// Same as stop(): plays silence and drains the device first.
  ~AudioOutput() override;

  /// Any non-real-time thread.
  AudioOutputStatus status() const;
  /// ActuatorSink: felt after the device buffer.
  std::string name() const override;
  std::int64_t latency_ns() const override;
  std::string statusLine() const override;

 private:
  struct Device;
  void writerLoop() noexcept override;

  const AudioOutputConfig m_config;
  std::unique_ptr<Device> m_device;
  std::atomic<std::uint64_t> m_framesWritten{0}, m_underruns{0}, m_starved{0}, m_skipped{0}, m_reopens{0};
};

}  // namespace vt::haptics
