// MPEG haptics JSON interchange format (ISO/IEC 23090-31, "HJIF"). Written from the standard's
// description and the structure its reference software reads; see docs/haptic-files.md.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "json_fields.hpp"
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
json bodyPartTarget(ActuatorId id) {
  static const char* kFingers[] = {"Thumb", "Index", "Middle", "Ring", "Pinky"};
  if (int(id) < 5) return {"Right", "Hand", kFingers[int(id)]};
  return {"Right", "Hand", "Palm"};
}

// Keyframes for a waveform under linear interpolation: samples on the line through their
// neighbours add nothing (silence and ramps collapse to their ends).
json pcmKeyframes(const std::vector<float>& pcm) {
  json frames = json::array();
  for (std::size_t i = 0; i < pcm.size(); ++i) {
    const bool inner = i > 0 && i + 1 < pcm.size();
    if (inner && std::fabs(pcm[i] - 0.5f * (pcm[i - 1] + pcm[i + 1])) < 1e-7f) continue;
    frames.push_back({{"relative_position", i}, {"amplitude_modulation", pcm[i]}});
  }
  return frames;
}

json envelopeBand(const std::vector<EnvelopePoint>& envelope) {
  json frames = json::array();
  float lo = kMaxFrequency_hz, hi = 0.0f;
  for (const EnvelopePoint& p : envelope) {
    json k = {{"relative_position", std::lround(p.t_s * 1000.0)}, {"amplitude_modulation", p.amplitude}};
    if (p.frequency_hz > 0.0f) {
      k["frequency_modulation"] = std::lround(p.frequency_hz);
      lo = std::min(lo, p.frequency_hz), hi = std::max(hi, p.frequency_hz);
    }
    frames.push_back(k);
  }
  if (hi < lo) lo = hi = 0.0f;
  return {{"band_type", "VectorialWave"}, {"lower_frequency_limit", std::lround(std::floor(lo))},
          {"upper_frequency_limit", std::lround(std::ceil(hi))},
          {"effects", json::array({{{"id", 0}, {"position", 0}, {"effect_type", "Basis"}, {"base_signal", "Sine"},
                                    {"phase", 0.0}, {"keyframes", frames}}})}};
}

}  // namespace

std::string writeHjif(const HapticClip& clip) {
  const bool pcm = clip.sampleRate_hz > 0 && std::any_of(clip.channels.begin(), clip.channels.end(),
                                                          [](const ClipChannel& c) { return !c.pcm.empty(); });
  if (pcm && clip.sampleRate_hz > kMaxTimescale) fail("HJIF: sample rate ", clip.sampleRate_hz, " Hz above the Main profile's 48000");
  const std::uint32_t timescale = pcm ? clip.sampleRate_hz : 1000;
  json channels = json::array();
  for (std::size_t i = 0; i < clip.channels.size(); ++i) {
    const ClipChannel& c = clip.channels[i];
    json channel = {{"id", i}, {"description", std::string(actuatorName(c.actuator))}, {"gain", 1.0},
                    {"mixing_coefficient", 1.0}, {"body_part_mask", 0}, {"body_part_target", bodyPartTarget(c.actuator)}};
    if (pcm) {
      channel["frequency_sampling"] = clip.sampleRate_hz;
      channel["sample_count"] = c.pcm.size();
      channel["bands"] = json::array({{{"band_type", "Curve"}, {"curve_type", "Linear"}, {"lower_frequency_limit", 0},
                                       {"upper_frequency_limit", clip.sampleRate_hz / 2},
                                       {"effects", json::array({{{"id", 0}, {"position", 0}, {"effect_type", "Basis"},
                                                                 {"keyframes", pcmKeyframes(c.pcm)}}})}}});
    } else {
      channel["bands"] = json::array({envelopeBand(simplifyEnvelope(c.envelope, 0.002f))});
    }
    channels.push_back(channel);
  }
  const json doc = {
      {"version", "2023"}, {"profile", "Main"}, {"level", 1}, {"date", today()},
      {"description", clip.description.empty() ? "V-Touching haptic clip" : clip.description},
      {"timescale", timescale},
      {"avatars", json::array({{{"id", 1}, {"lod", 0}, {"type", "Vibration"}}})},
      {"perceptions", json::array({{{"id", 0}, {"avatar_id", 1}, {"description", "glove actuators"},
                                    {"perception_modality", "Vibrotactile"}, {"effect_library", json::array()},
                                    {"channels", channels}}})},
      {"syncs", json::array()}};
  return doc.dump(1);
}

HapticClip readHjif(std::string_view textIn, const std::string& source) {
  const json doc = parse(textIn, source);
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
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const json& ch = channels[c];
      const std::string cw = str(pw, ".channels[", c, "]");
      for (const char* key : {"gain", "mixing_coefficient"}) number(ch, key, cw, -1e6, 1e6);
      number(ch, "body_part_mask", cw, 0, 4294967295.0);
      ClipChannel out;
      out.actuator = ActuatorId(std::min<std::size_t>(c, kMaxActuators - 1));
      if (const auto named = actuatorFromName(text(ch, "description", cw))) out.actuator = *named;
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
          const json& keyframes = array(effects[e], "keyframes", ew);
          double last = -1.0;
          for (std::size_t k = 0; k < keyframes.size(); ++k) {
            const std::string kw = str(ew, ".keyframes[", k, "]");
            const double at = position + number(keyframes[k], "relative_position", kw, 0, 4294967295.0);
            if (at / timescale > kMaxClip_s) fail(kw, ": keyframe at ", at / timescale, " s, past the ", kMaxClip_s, " s limit");
            if (at < last) fail(kw, ".relative_position goes backwards");
            const float amplitude = float(number(keyframes[k], "amplitude_modulation", kw, -1, 1)) * gain;
            const float freq = keyframes[k].contains("frequency_modulation")
                                   ? float(number(keyframes[k], "frequency_modulation", kw, 0, 1e5)) : 0.0f;
            if (type == "VectorialWave") {
              out.envelope.push_back({at / timescale, std::clamp(amplitude, 0.0f, 1.0f), freq});
            } else {
              // Curve band: the waveform itself, linear between keyframes, at the channel's rate.
              const double sample = at * rate_hz / timescale;
              const auto index = std::size_t(std::llround(sample));
              if (out.pcm.size() <= index) resizePcm(out, index + 1, kw);
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
