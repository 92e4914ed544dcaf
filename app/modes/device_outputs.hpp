#pragma once
// The `--output` sinks of a touch pipeline: audio interfaces (ALSA) and OSC targets, each on its
// own thread reading the frame source's frames from its queue (docs/outputs.md). Main thread.
#include <memory>
#include <string>
#include <vector>

#include "cli.hpp"
#include "vt/haptics/actuator_sink.hpp"

namespace vt::app {

/// What the command line asked for: every `--output` (repeatable) and `--channels`.
struct OutputSpecs {
  std::vector<std::string> outputs;  // "audio", "audio:DEVICE", "osc://HOST:PORT[?blocks]"
  std::string channels;              // audio channel map, empty = actuator c on channel c
};

/// Reads --output (any number) and --channels, checking their syntax (throws vt::Error naming
/// the option and the value).
OutputSpecs readOutputSpecs(cli::Args& args);

/// Opens every --output for `actuators` actuators as realtime sinks (audio interfaces, OSC), each
/// with its own writer thread (throws vt::Error naming the output).
std::vector<std::unique_ptr<haptics::ActuatorSink>> openOutputs(const OutputSpecs& specs, int actuators);

}  // namespace vt::app
