// MPEG haptics JSON interchange format (ISO/IEC 23090-31, "HJIF"). Written from the standard's
// description and the structure its reference software reads; see docs/haptic-files.md.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "json_fields.hpp"
#include "json_writer.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace vt::haptics::files {
namespace {

using nlohmann::json;

constexpr std::uint32_t kMaxTimescale = 48000;  // the Main profile's limit

std::string today() {
  const auto days = std::chrono::floor<std::chrono::days>(std::chrono::system_clock::now());
  const std::chrono::year_month_day ymd{days};
  char out[16];
  std::snprintf(out, sizeof out, "%04d-%02u-%02u", int(ymd.year()), unsigned(ymd.month()), unsigned(ymd.day()));
  return out;
}

// Where on the (right) hand each glove actuator sits, in the standard's body-part vocabulary.
const char* bodyPart(ActuatorId id) {
  static const char* kFingers[] = {"Thumb", "Index", "Middle", "Ring", "Pinky"};
  return int(id) < 5 ? kFingers[int(id)] : "Palm";
}

// Keyframes for a waveform under linear interpolation: samples on the line through their
// neighbours add nothing (silence and ramps collapse to their ends).
void pcmKeyframes(JsonWriter& w, const std::vector<float>& pcm) {
  for (std::size_t i = 0; i < pcm.size(); ++i) {
    const bool inner = i > 0 && i + 1 < pcm.size();
    if (inner && std::fabs(pcm[i] - 0.5f * (pcm[i - 1] + pcm[i + 1])) < 1e-7f) continue;
    w.beginObject().member("relative_position", std::uint64_t(i)).member("amplitude_modulation", pcm[i]).endObject();
  }
}

// The envelope as a VectorialWave band; an unknown frequency (0 Hz) has no frequency_modulation,
// which readers take as the nominal kNominalFrequency_hz.
void envelopeBand(JsonWriter& w, const std::vector<EnvelopePoint>& envelope) {
  float lo = 1e9f, hi = 0.0f;
  for (const EnvelopePoint& p : envelope)
    if (p.frequency_hz > 0.0f) lo = std::min(lo, p.frequency_hz), hi = std::max(hi, p.frequency_hz);
  if (hi < lo) lo = hi = 0.0f;
  w.beginObject().member("band_type", "VectorialWave").member("lower_frequency_limit", std::int64_t(std::floor(lo)))
      .member("upper_frequency_limit", std::int64_t(std::ceil(hi)));
  w.key("effects").beginArray().beginObject().member("id", 0).member("position", 0).member("effect_type", "Basis")
      .member("base_signal", "Sine").member("phase", 0.0).key("keyframes").beginArray();
  for (const EnvelopePoint& p : envelope) {
    w.beginObject().member("relative_position", std::int64_t(std::llround(p.t_s * 1000.0))).member("amplitude_modulation", p.amplitude);
    if (p.frequency_hz > 0.0f) w.member("frequency_modulation", std::int64_t(std::lround(p.frequency_hz)));
    w.endObject();
  }
  w.endArray().endObject().endArray().endObject();
}

// Which actuator each channel plays on: its description names one, else its body_part_target's
// finger, else the first actuator no other channel claims. Two channels on one actuator are
// refused (the glove would play only one of them).
std::vector<ActuatorId> channelActuators(const json& channels, const std::string& pw) {
  std::vector<int> claimed(channels.size(), -1);
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const std::string cw = str(pw, ".channels[", c, "]");
    // By name (actuatorFromName also reads the names older files used).
    if (const auto named = actuatorFromName(text(channels[c], "description", cw))) claimed[c] = int(*named);
    if (claimed[c] < 0 && channels[c].contains("body_part_target") && channels[c]["body_part_target"].is_array()) {
      for (const json& part : channels[c]["body_part_target"])
        for (int a = 0; a < 5; ++a)
          if (part.is_string() && part.get<std::string>() == bodyPart(ActuatorId(a))) claimed[c] = a;
    }
  }
  std::vector<ActuatorId> out(channels.size());
  std::vector<int> owner(kMaxActuators, -1);
  for (std::size_t c = 0; c < channels.size(); ++c) {
    int a = claimed[c];
    for (int k = 0; a < 0 && k < kMaxActuators; ++k)
      if (owner[std::size_t(k)] < 0 && std::find(claimed.begin(), claimed.end(), k) == claimed.end()) a = k;
    if (a < 0) fail(pw, ".channels[", c, "]: no actuator left for it (the glove has ", kMaxActuators, ")");
    if (owner[std::size_t(a)] >= 0)
      fail(pw, ".channels[", owner[std::size_t(a)], "] and channels[", c, "] both play on actuator '",
           actuatorName(ActuatorId(a)), "' (same description or body location): give each its own");
    owner[std::size_t(a)] = int(c);
    out[c] = ActuatorId(a);
  }
  return out;
}

}  // namespace

std::string writeHjif(const HapticClip& clip) {
  const bool pcm = clip.sampleRate_hz > 0 && std::any_of(clip.channels.begin(), clip.channels.end(),
                                                          [](const ClipChannel& c) { return !c.pcm.empty(); });
  if (pcm && clip.sampleRate_hz > kMaxTimescale) fail("HJIF: sample rate ", clip.sampleRate_hz, " Hz above the Main profile's 48000");
  const std::uint32_t timescale = pcm ? clip.sampleRate_hz : 1000;
  std::string out;
  JsonWriter w(out);
  w.beginObject().member("version", "2023").member("profile", "Main").member("level", 1).member("date", today())
      .member("description", clip.description.empty() ? "V-Touching haptic clip" : clip.description)
      .member("timescale", std::uint64_t(timescale));
  w.key("avatars").beginArray().beginObject().member("id", 1).member("lod", 0).member("type", "Vibration").endObject().endArray();
  w.key("perceptions").beginArray().beginObject().member("id", 0).member("avatar_id", 1).member("description", "glove actuators")
      .member("perception_modality", "Vibrotactile").key("effect_library").beginArray().endArray().key("channels").beginArray();
  for (std::size_t i = 0; i < clip.channels.size(); ++i) {
    const ClipChannel& c = clip.channels[i];
    w.beginObject().member("id", std::uint64_t(i)).member("description", actuatorName(c.actuator)).member("gain", 1.0)
        .member("mixing_coefficient", 1.0).member("body_part_mask", 0);
    w.key("body_part_target").beginArray().value("Right").value("Hand").value(bodyPart(c.actuator)).endArray();
    if (pcm) w.member("frequency_sampling", std::uint64_t(clip.sampleRate_hz)).member("sample_count", std::uint64_t(c.pcm.size()));
    w.key("bands").beginArray();
    if (pcm) {
      w.beginObject().member("band_type", "Curve").member("curve_type", "Linear").member("lower_frequency_limit", 0)
          .member("upper_frequency_limit", std::uint64_t(clip.sampleRate_hz / 2));
      w.key("effects").beginArray().beginObject().member("id", 0).member("position", 0).member("effect_type", "Basis")
          .key("keyframes").beginArray();
      pcmKeyframes(w, c.pcm);
      w.endArray().endObject().endArray().endObject();
    } else {
      envelopeBand(w, simplifyEnvelope(c.envelope, 0.002f));
    }
    w.endArray().endObject();
  }
  w.endArray().endObject().endArray().key("syncs").beginArray().endArray().endObject();
  return out;
}

HapticClip readHjif(std::string_view textIn, const std::string& source) {
  const json doc = parse(textIn, source, {{"keyframes", {"relative_position", "amplitude_modulation", "frequency_modulation"}}});
  for (const char* key : {"version", "profile", "date", "description"}) text(doc, key, source);
  const int level = int(number(doc, "level", source, 1, 2));
  const auto timescale = std::uint32_t(number(doc, "timescale", source, 1, kMaxTimescale));
  array(doc, "avatars", source);
  array(doc, "syncs", source);
  const json& perceptions = array(doc, "perceptions", source);
  HapticClip clip;
  clip.description = text(doc, "description", source);
  // Curve bands become PCM: sizes from the file are checked against the clip's sample budget
  // before anything is allocated (channels of every perception count together).
  std::size_t samplesBefore = 0;  // in the channels already read
  std::size_t vibrationChannels = 0;
  auto resizePcm = [&](ClipChannel& channel, std::size_t samples, const std::string& where) {
    if (samplesBefore + samples > kMaxClipSamples)
      fail(where, ": ", samples, " samples would take the clip past its budget of ", kMaxClipSamples,
           " samples (docs/RELIABILITY.md)");
    channel.pcm.resize(samples, 0.0f);
  };
  for (std::size_t p = 0; p < perceptions.size(); ++p) {
    const std::string pw = str(source, ": perceptions[", p, "]");
    const std::string modality = text(perceptions[p], "perception_modality", pw);
    number(perceptions[p], "id", pw, -32768, 32767);
    number(perceptions[p], "avatar_id", pw, -32768, 32767);
    text(perceptions[p], "description", pw);
    array(perceptions[p], "effect_library", pw);
    const json& channels = array(perceptions[p], "channels", pw);
    if (modality != "Vibrotactile" && modality != "Vibration") continue;  // V-Touching renders vibration only
    if (level == 1 && channels.size() > 128) fail(pw, ".channels: level 1 allows at most 128");
    vibrationChannels += channels.size();
    if (vibrationChannels > std::size_t(kMaxActuators))
      fail(pw, ".channels: ", vibrationChannels, " vibration channels in the file, the glove has ", kMaxActuators);
    const std::vector<ActuatorId> actuators = channelActuators(channels, pw);
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const json& ch = channels[c];
      const std::string cw = str(pw, ".channels[", c, "]");
      for (const char* key : {"gain", "mixing_coefficient"}) number(ch, key, cw, -1e6, 1e6);
      number(ch, "body_part_mask", cw, 0, 4294967295.0);
      ClipChannel out;
      out.actuator = actuators[c];
      for (const ClipChannel& other : clip.channels)
        if (other.actuator == out.actuator) fail(cw, ": a channel of an earlier perception already plays on actuator '", actuatorName(out.actuator), "'");
      const float gain = float(ch["gain"].get<double>());
      const double rate_hz = ch.contains("frequency_sampling") ? number(ch, "frequency_sampling", cw, 1, kMaxTimescale) : timescale;
      const json& bands = array(ch, "bands", cw);
      for (std::size_t b = 0; b < bands.size(); ++b) {
        const std::string bw = str(cw, ".bands[", b, "]");
        const std::string type = text(bands[b], "band_type", bw);
        const double lower = number(bands[b], "lower_frequency_limit", bw, 0, 1e6);
        if (number(bands[b], "upper_frequency_limit", bw, 0, 1e6) < lower) fail(bw, ": upper_frequency_limit below lower");
        if (type != "Curve" && bands[b].contains("curve_type")) fail(bw, ": curve_type is only for Curve bands");
        const json& effects = array(bands[b], "effects", bw);
        if (type == "WaveletWave" || type == "Transient") {
          fail(bw, ": ", type, " bands are not read (V-Touching reads Curve and VectorialWave bands)");
        }
        if (type != "Curve" && type != "VectorialWave") fail(bw, ".band_type '", type, "' is not Transient, Curve, VectorialWave or WaveletWave");
        for (std::size_t e = 0; e < effects.size(); ++e) {
          const std::string ew = str(bw, ".effects[", e, "]");
          const std::string effectType = text(effects[e], "effect_type", ew);
          if (effectType != "Basis") fail(ew, ".effect_type '", effectType, "': only Basis effects are read");
          const double position = number(effects[e], "position", ew, 0, 4294967295.0);
          const Records keyframes(effects[e], "keyframes", 3, ew);
          double last = -1.0;
          for (std::size_t k = 0; k < keyframes.size(); ++k) {
            const double at = position + keyframes.number(k, 0, "relative_position", 0, 4294967295.0);
            if (at / timescale > kMaxClip_s) fail(keyframes.where(k), ": keyframe at ", at / timescale, " s, past the ", kMaxClip_s, " s limit");
            if (at < last) fail(keyframes.where(k), ".relative_position goes backwards");
            const float amplitude = float(keyframes.number(k, 1, "amplitude_modulation", -1, 1)) * gain;
            const float freq = keyframes.has(k, 2) ? float(keyframes.number(k, 2, "frequency_modulation", 0, kMaxEnvelopeFrequency_hz)) : 0.0f;
            if (type == "VectorialWave") {
              out.envelope.push_back({at / timescale, std::clamp(amplitude, 0.0f, 1.0f), freq});
            } else {
              // Curve band: the waveform itself, linear between keyframes, at the channel's rate.
              const double sample = at * rate_hz / timescale;
              const auto index = std::size_t(std::llround(sample));
              if (out.pcm.size() <= index) resizePcm(out, index + 1, keyframes.where(k));
              if (last >= 0.0) {
                const auto from = std::size_t(std::llround(last * rate_hz / timescale));
                const float a = out.pcm[from];
                for (std::size_t s = from + 1; s < index; ++s) out.pcm[s] = a + (amplitude - a) * float(s - from) / float(index - from);
              }
              out.pcm[index] = amplitude;
            }
            last = at;
          }
        }
      }
      if (!out.pcm.empty()) {
        if (clip.sampleRate_hz && clip.sampleRate_hz != std::uint32_t(rate_hz)) fail(cw, ": channels at different sample rates are not read");
        clip.sampleRate_hz = std::uint32_t(rate_hz);
        if (ch.contains("sample_count")) resizePcm(out, std::size_t(number(ch, "sample_count", cw, 0, rate_hz * kMaxClip_s)), cw + ".sample_count");
      }
      std::sort(out.envelope.begin(), out.envelope.end(), [](const auto& a, const auto& b) { return a.t_s < b.t_s; });
      if (out.envelope.empty() && out.pcm.empty()) continue;
      clip.duration_s = std::max({clip.duration_s, out.envelope.empty() ? 0.0 : out.envelope.back().t_s,
                                  clip.sampleRate_hz ? double(out.pcm.size()) / clip.sampleRate_hz : 0.0});
      samplesBefore += out.pcm.size();
      clip.channels.push_back(std::move(out));
    }
  }
  if (clip.channels.empty()) fail(source, ": no vibrotactile channel with a Curve or VectorialWave band");
  return clip;
}

}  // namespace vt::haptics::files
