#pragma once
// The `--output` sinks of a touch session: audio interfaces (ALSA) and OSC targets, each on its
// own thread reading the haptic loop's frames from its queue (docs/outputs.md). Main thread.
#include <memory>
#include <string>
#include <vector>

#include "cli.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/devices/audio_output.hpp"
#include "vt/haptics/devices/osc_output.hpp"

namespace vt::app {

/// What the command line asked for: every `--output` (repeatable) and `--channels`.
struct OutputSpecs {
  std::vector<std::string> outputs;  // "audio", "audio:DEVICE", "osc://HOST:PORT[?blocks]"
  std::string channels;              // audio channel map, empty = actuator c on channel c
};

/// Reads --output (any number) and --channels, checking their syntax (throws vt::Error naming
/// the option and the value).
OutputSpecs readOutputSpecs(cli::Args& args);

class DeviceOutputs {
 public:
  /// Opens every output for `actuators` actuators (throws vt::Error naming the output).
  DeviceOutputs(const OutputSpecs& specs, int actuators);
  /// Stops every output (each ends in silence).
  ~DeviceOutputs();
  DeviceOutputs(const DeviceOutputs&) = delete;
  DeviceOutputs& operator=(const DeviceOutputs&) = delete;

  /// The queues to register with HapticLoop::addOutput (one producer each).
  std::vector<SpscRing<haptics::ActuatorFrame>*> queues();
  bool empty() const { return m_audio.empty() && m_osc.empty(); }
  /// One line for the HUD: each output's state and counters ("" when there are none).
  std::string status() const;
  /// Silences and stops every output. Idempotent.
  void stop();

 private:
  std::vector<std::unique_ptr<haptics::AudioOutput>> m_audio;
  std::vector<std::unique_ptr<haptics::OscOutput>> m_osc;
};

}  // namespace vt::app
