#include "modes/device_outputs.hpp"

#include "vt/core/error.hpp"
#include "vt/haptics/devices/audio_output.hpp"
#include "vt/haptics/devices/osc_output.hpp"

namespace vt::app {
namespace {

bool isAudio(const std::string& spec) { return spec == "audio" || spec.rfind("audio:", 0) == 0; }
bool isOsc(const std::string& spec) { return spec.rfind("osc://", 0) == 0; }

}  // namespace

OutputSpecs readOutputSpecs(cli::Args& args) {
  OutputSpecs specs;
  for (const std::string& output : args.values("output")) {  // repeatable: one per device
    if (isOsc(output)) haptics::parseOscUrl(output);  // syntax errors now, before anything opens
    else if (!isAudio(output)) fail(args.command(), ": --output '", output, "' is not audio[:DEVICE] or osc://HOST:PORT");
    specs.outputs.push_back(output);
  }
  specs.channels = args.valueOr("channels", "");
  if (!specs.channels.empty()) {
    haptics::parseChannelMap(specs.channels);
    bool audio = false;
    for (const auto& o : specs.outputs) audio = audio || isAudio(o);
    if (!audio) fail(args.command(), ": --channels maps audio channels; add --output audio[:DEVICE]");
  }
  return specs;
}

std::vector<std::unique_ptr<haptics::ActuatorSink>> openOutputs(const OutputSpecs& specs, int actuators) {
  std::vector<std::unique_ptr<haptics::ActuatorSink>> sinks;
  for (const std::string& spec : specs.outputs) {
    if (isAudio(spec)) {
      haptics::AudioOutputConfig config;
      if (spec.size() > 6) config.device = spec.substr(6);
      config.actuators = actuators;
      if (!specs.channels.empty()) config.channels = haptics::parseChannelMap(specs.channels);
      sinks.push_back(std::make_unique<haptics::AudioOutput>(config));
    } else {
      sinks.push_back(std::make_unique<haptics::OscOutput>(haptics::parseOscUrl(spec)));
    }
  }
  return sinks;
}

}  // namespace vt::app
