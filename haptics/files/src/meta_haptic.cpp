// Meta's .haptic 1.0 (facebook/meta-haptics-sdk, resources/haptic-file-spec.md).
#include <algorithm>

#include "json_fields.hpp"
#include "json_writer.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace vt::haptics::files {

using nlohmann::json;

std::string writeMetaHaptic(const HapticClip& clip, std::size_t channel) {
  auto envelope = simplifyEnvelope(channelEnvelope(clip.channels.at(channel), clip.sampleRate_hz), 0.002f);
  if (std::max(clip.duration_s, envelope.empty() ? 0.0 : envelope.back().t_s) > kMaxClip_s)
    fail(".haptic: a clip of ", clip.duration_s, " s is over the ", kMaxClip_s, " s limit (split it first)");
  // At least two breakpoints spanning a positive duration.
  if (envelope.empty()) envelope.push_back({0.0, 0.0f, 0.0f});
  if (envelope.back().t_s < std::max(clip.duration_s, kShortestWrittenClip_s)) {
    envelope.push_back({std::max(clip.duration_s, kShortestWrittenClip_s), envelope.back().amplitude, envelope.back().frequency_hz});
  }
  // One point at or past that end (after 0, so the span is positive): its level holds from 0.
  if (envelope.size() == 1) envelope.insert(envelope.begin(), {0.0, envelope.front().amplitude, envelope.front().frequency_hz});
  std::string out;
  JsonWriter w(out);
  w.beginObject().key("version").beginObject().member("major", 1).member("minor", 0).member("patch", 0).endObject();
  w.key("metadata").beginObject().member("editor", "V-Touching").member("source", "").member("project", "")
      .key("tags").beginArray().endArray()
      .member("description", str(clip.description, " (", actuatorName(clip.channels[channel].actuator), ")")).endObject();
  w.key("signals").beginObject().key("continuous").beginObject().key("envelopes").beginObject().key("amplitude").beginArray();
  for (const EnvelopePoint& p : envelope)
    w.beginObject().member("time", p.t_s).member("amplitude", std::clamp(p.amplitude, 0.0f, 1.0f)).endObject();
  // Unknown frequencies (0 Hz) are written as the nominal one (normalised 0.5, the format's default).
  w.endArray().key("frequency").beginArray();
  for (const EnvelopePoint& p : envelope) w.beginObject().member("time", p.t_s).member("frequency", normaliseFrequency(p.frequency_hz)).endObject();
  w.endArray().endObject().endObject().endObject().endObject();
  return out;
}

HapticClip readMetaHaptic(std::string_view textIn, const std::string& source, ActuatorId actuator) {
  const json doc = parse(textIn, source, {{"amplitude", {"time", "amplitude", "emphasis.amplitude", "emphasis.frequency"}},
                                          {"frequency", {"time", "frequency"}}});
  const json& version = field(doc, "version", source);
  if (number(version, "major", source + ": version", 0, 1e6) != 1) fail(source, ": version.major must be 1");
  number(version, "minor", source + ": version", 0, 1e6);
  number(version, "patch", source + ": version", 0, 1e6);
  if (!field(doc, "metadata", source).is_object()) fail(source, ".metadata must be an object");
  const std::string ew = source + ": signals.continuous.envelopes";
  const json& envelopes = field(field(field(doc, "signals", source), "continuous", source + ": signals"), "envelopes",
                                source + ": signals.continuous");
  const Records amplitude(envelopes, "amplitude", 4, ew);
  if (amplitude.size() < 2) fail(ew, ".amplitude needs at least two breakpoints");
  HapticClip clip;
  clip.description = doc["metadata"].contains("description") && doc["metadata"]["description"].is_string()
                         ? doc["metadata"]["description"].get<std::string>() : ".haptic clip";
  ClipChannel channel;
  channel.actuator = actuator;
  for (std::size_t i = 0; i < amplitude.size(); ++i) {
    const double t = amplitude.number(i, 0, "time", 0, kMaxClip_s);
    const float a = float(amplitude.number(i, 1, "amplitude", 0, 1));
    if (!channel.envelope.empty() && t < channel.envelope.back().t_s) fail(amplitude.where(i), ".time goes backwards");
    if (amplitude.has(i, 2) || amplitude.has(i, 3)) {
      // A transient: kept as its amplitude at that breakpoint (the click itself is not rendered).
      const float e = float(amplitude.number(i, 2, "emphasis.amplitude", 0, 1));
      amplitude.number(i, 3, "emphasis.frequency", 0, 1);
      if (e < a) fail(amplitude.where(i), ".emphasis.amplitude ", e, " is below the envelope's ", a);
    }
    channel.envelope.push_back({t, a, 0.0f});
  }
  clip.duration_s = channel.envelope.back().t_s;
  if (!(clip.duration_s > 0.0)) fail(ew, ".amplitude spans no time");
  std::vector<EnvelopePoint> freq;
  if (envelopes.contains("frequency")) {
    const Records frequency(envelopes, "frequency", 2, ew);
    for (std::size_t i = 0; i < frequency.size(); ++i) {
      const double t = frequency.number(i, 0, "time", 0, kMaxClip_s);
      if (!freq.empty() && t < freq.back().t_s) fail(frequency.where(i), ".time goes backwards");
      if (t > clip.duration_s) fail(frequency.where(i), ".time ", t, " is after the amplitude envelope ends");
      freq.push_back({t, 0.0f, frequencyFromNormalised(float(frequency.number(i, 1, "frequency", 0, 1)))});
    }
  }
  const float fallback = frequencyFromNormalised(0.5f);  // the specification's default: the nominal frequency
  for (EnvelopePoint& p : channel.envelope) p.frequency_hz = freq.empty() ? fallback : envelopeAt(freq, p.t_s).frequency_hz;
  clip.channels.push_back(std::move(channel));
  return clip;
}

}  // namespace vt::haptics::files
