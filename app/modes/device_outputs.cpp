#include "modes/device_outputs.hpp"

#include "vt/core/error.hpp"

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

DeviceOutputs::DeviceOutputs(const OutputSpecs& specs, int actuators) {
  for (const std::string& spec : specs.outputs) {
    if (isAudio(spec)) {
      haptics::AudioOutputConfig config;
      if (spec.size() > 6) config.device = spec.substr(6);
      config.actuators = actuators;
      if (!specs.channels.empty()) config.channels = haptics::parseChannelMap(specs.channels);
      m_audio.push_back(std::make_unique<haptics::AudioOutput>(config));
    } else {
      m_osc.push_back(std::make_unique<haptics::OscOutput>(haptics::parseOscUrl(spec)));
    }
  }
}

DeviceOutputs::~DeviceOutputs() { stop(); }

std::vector<SpscRing<haptics::ActuatorFrame>*> DeviceOutputs::queues() {
  std::vector<SpscRing<haptics::ActuatorFrame>*> out;
  for (auto& a : m_audio) out.push_back(&a->queue());
  for (auto& o : m_osc) out.push_back(&o->queue());
  return out;
}

std::string DeviceOutputs::status() const {
  std::string text;
  auto failsafe = [](haptics::FailsafeReason r) {
    return r == haptics::FailsafeReason::None ? std::string() : str(" (silent: ", haptics::failsafeReasonName(r), ")");
  };
  for (const auto& a : m_audio) {
    const haptics::AudioOutputStatus s = a->status();
    if (!text.empty()) text += "; ";
    text += str("audio ", s.device, " ", s.channels, " ch ", s.rate_hz, " Hz, buffer ", s.buffer_frames, ", underruns ",
                s.underruns, ", starved ", s.starvedFrames, ", skipped ", s.skippedSamples, failsafe(s.failsafe));
    if (!s.lastError.empty()) text += ", " + s.lastError;
  }
  for (const auto& o : m_osc) {
    const haptics::OscOutputStatus s = o->status();
    if (!text.empty()) text += "; ";
    text += str(s.target, " ", s.messagesSent, " messages, ", s.sendErrors, " errors", failsafe(s.failsafe));
  }
  return text;
}

void DeviceOutputs::stop() {
  for (auto& a : m_audio) a->stop();
  for (auto& o : m_osc) o->stop();
}

}  // namespace vt::app
