// Meta's .haptic 1.0 (facebook/meta-haptics-sdk, resources/haptic-file-spec.md).
#include <algorithm>

#include "json_fields.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace vt::haptics::files {

using nlohmann::json;

std::string writeMetaHaptic(const HapticClip& clip, std::size_t channel) {
  auto envelope = simplifyEnvelope(channelEnvelope(clip.channels.at(channel), clip.sampleRate_hz), 0.002f);
  // At least two breakpoints spanning a positive duration.
  if (envelope.empty()) envelope.push_back({0.0, 0.0f, 0.0f});
  if (envelope.back().t_s < std::max(clip.duration_s, 0.001)) {
    envelope.push_back({std::max(clip.duration_s, 0.001), envelope.back().amplitude, envelope.back().frequency_hz});
  }
  json amplitude = json::array(), frequency = json::array();
  for (const EnvelopePoint& p : envelope) {
    amplitude.push_back({{"time", p.t_s}, {"amplitude", std::clamp(p.amplitude, 0.0f, 1.0f)}});
    if (p.frequency_hz > 0.0f) frequency.push_back({{"time", p.t_s}, {"frequency", normaliseFrequency(p.frequency_hz)}});
  }
  const json doc = {{"version", {{"major", 1}, {"minor", 0}, {"patch", 0}}},
                    {"metadata", {{"editor", "V-Touching"}, {"source", ""}, {"project", ""}, {"tags", json::array()},
                                  {"description", str(clip.description, " (", actuatorName(clip.channels[channel].actuator), ")")}}},
                    {"signals", {{"continuous", {{"envelopes", {{"amplitude", amplitude}, {"frequency", frequency}}}}}}}};
  return doc.dump(1);
}

HapticClip readMetaHaptic(std::string_view textIn, const std::string& source, ActuatorId actuator) {
  const json doc = parse(textIn, source);
  const json& version = field(doc, "version", source);
  if (number(version, "major", source + ": version", 0, 1e6) != 1) fail(source, ": version.major must be 1");
  number(version, "minor", source + ": version", 0, 1e6);
  number(version, "patch", source + ": version", 0, 1e6);
  if (!field(doc, "metadata", source).is_object()) fail(source, ".metadata must be an object");
  const std::string ew = source + ": signals.continuous.envelopes";
  const json& envelopes = field(field(field(doc, "signals", source), "continuous", source + ": signals"), "envelopes",
                                source + ": signals.continuous");
  const json& amplitude = array(envelopes, "amplitude", ew);
  if (amplitude.size() < 2) fail(ew, ".amplitude needs at least two breakpoints");
  HapticClip clip;
  clip.description = doc["metadata"].contains("description") && doc["metadata"]["description"].is_string()
                         ? doc["metadata"]["description"].get<std::string>() : ".haptic clip";
  ClipChannel channel;
  channel.actuator = actuator;
  for (std::size_t i = 0; i < amplitude.size(); ++i) {
    const std::string pw = str(ew, ".amplitude[", i, "]");
    const double t = number(amplitude[i], "time", pw, 0, kMaxClip_s);
    const float a = float(number(amplitude[i], "amplitude", pw, 0, 1));
    if (!channel.envelope.empty() && t < channel.envelope.back().t_s) fail(pw, ".time goes backwards");
    if (amplitude[i].contains("emphasis")) {
      // A transient: kept as its amplitude at that breakpoint (the click itself is not rendered).
      const float e = float(number(amplitude[i]["emphasis"], "amplitude", pw + ".emphasis", 0, 1));
      number(amplitude[i]["emphasis"], "frequency", pw + ".emphasis", 0, 1);
      if (e < a) fail(pw, ".emphasis.amplitude ", e, " is below the envelope's ", a);
    }
    channel.envelope.push_back({t, a, 0.0f});
  }
  clip.duration_s = channel.envelope.back().t_s;
  if (!(clip.duration_s > 0.0)) fail(ew, ".amplitude spans no time");
  std::vector<EnvelopePoint> freq;
  if (envelopes.contains("frequency")) {
    const json& frequency = array(envelopes, "frequency", ew);
    for (std::size_t i = 0; i < frequency.size(); ++i) {
      const std::string pw = str(ew, ".frequency[", i, "]");
      const double t = number(frequency[i], "time", pw, 0, kMaxClip_s);
      if (!freq.empty() && t < freq.back().t_s) fail(pw, ".time goes backwards");
      if (t > clip.duration_s) fail(pw, ".time ", t, " is after the amplitude envelope ends");
      freq.push_back({t, 0.0f, frequencyFromNormalised(float(number(frequency[i], "frequency", pw, 0, 1)))});
    }
  }
  const float fallback = frequencyFromNormalised(0.5f);  // the specification's default
  for (EnvelopePoint& p : channel.envelope) p.frequency_hz = freq.empty() ? fallback : envelopeAt(freq, p.t_s).frequency_hz;
  clip.channels.push_back(std::move(channel));
  return clip;
}

}  // namespace vt::haptics::files
