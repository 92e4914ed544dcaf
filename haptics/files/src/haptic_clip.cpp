#include "vt/haptics/files/haptic_clip.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <sstream>

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/haptics/wav.hpp"

namespace vt::haptics::files {

ActuatorId parseActuator(const std::string& name, const std::string& what) {
  // Files written before the finger names were unified say "pinky": still read.
  if (const auto id = actuatorFromName(name)) return *id;
  fail(what, ": unknown actuator '", name, "' (thumb, index, middle, ring, little, palm-index-up, ...)");
}

ActuatorId actuatorFromFileName(const std::filesystem::path& path, ActuatorId fallback) noexcept {
  const std::string stem = path.stem().string();
  const std::string_view view(stem);
  ActuatorId best = fallback;
  std::size_t bestLength = 0;
  // "palm-index-up" also ends in "-up"-like suffixes of shorter names: the longest match wins.
  for (int i = 0; i < kMaxActuators; ++i) {
    for (const std::string_view name : {actuatorName(ActuatorId(i)), legacyActuatorName(ActuatorId(i))}) {
      if (view.size() > name.size() + 1 && view.substr(view.size() - name.size()) == name &&
          view[view.size() - name.size() - 1] == '-' && name.size() > bestLength) {
        best = ActuatorId(i), bestLength = name.size();
      }
    }
  }
  return best;
}

HapticClip readActuatorCsv(std::string_view text, const std::string& source) {
  std::size_t at = 0;
  // Lines are read in place (no stream copy of the file).
  auto getline = [&](std::string& line) {
    if (at >= text.size()) return false;
    const std::size_t end = std::min(text.find('\n', at), text.size());
    line.assign(text, at, end - at);
    at = end + 1;
    return true;
  };
  std::string line;
  getline(line);
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string field; std::getline(hs, field, ',');) header.push_back(field);
  if (header.size() < 4 || header[0] != "t_ns" || header[1] != "sequence" || (header.size() - 2) % 2) {
    fail(source, ": line 1: expected t_ns,sequence,<actuators>,<actuators>_hz (as --record-csv writes)");
  }
  const std::size_t n = (header.size() - 2) / 2;
  if (n > std::size_t(kMaxActuators)) fail(source, ": line 1: more than ", kMaxActuators, " actuators");
  HapticClip clip;
  for (std::size_t i = 0; i < n; ++i) {
    const ActuatorId id = parseActuator(header[2 + i], source + " line 1");
    if (std::any_of(clip.channels.begin(), clip.channels.end(), [&](const ClipChannel& c) { return c.actuator == id; })) {
      fail(source, ": line 1: actuator '", header[2 + i], "' twice");
    }
    if (header[2 + n + i] != header[2 + i] + "_hz") {
      fail(source, ": line 1: column ", 3 + n + i, " is '", header[2 + n + i], "', expected '", header[2 + i], "_hz'");
    }
    clip.channels.push_back({.actuator = id});
  }
  double t0 = NAN;
  for (int number = 2; getline(line); ++number) {
    std::stringstream s(line);
    std::vector<double> v;
    for (std::string field; std::getline(s, field, ',');) {
      char* end = nullptr;
      v.push_back(std::strtod(field.c_str(), &end));
      if (end == field.c_str() || !std::isfinite(v.back())) fail(source, " line ", number, ": '", field, "' is not a number");
    }
    if (v.size() != header.size()) fail(source, " line ", number, ": ", v.size(), " fields, expected ", header.size());
    if (std::isnan(t0)) t0 = v[0];
    const double t_s = (v[0] - t0) * 1e-9;
    if (t_s < clip.duration_s) fail(source, " line ", number, ": time goes backwards");
    if (t_s > kMaxRecording_s)
      fail(source, " line ", number, ": ", t_s, " s after the first line, past the ", kMaxRecording_s, " s a recording may last");
    clip.duration_s = t_s;
    for (std::size_t i = 0; i < n; ++i) {
      // Bounded as doubles: a float cannot hold every double a file may give.
      const double frequency_hz = std::max(0.0, v[2 + n + i]);
      if (frequency_hz > kMaxEnvelopeFrequency_hz) {
        fail(source, " line ", number, ": ", header[2 + n + i], " ", frequency_hz, " Hz is over ", kMaxEnvelopeFrequency_hz, " Hz");
      }
      clip.channels[i].envelope.push_back({t_s, float(std::clamp(v[2 + i], 0.0, 1.0)), float(frequency_hz)});
    }
  }
  if (std::isnan(t0)) fail(source, ": no line after the header (the recording holds no tick)");
  return clip;
}

HapticClip loadRecording(const std::filesystem::path& csvPath, const std::filesystem::path& wavPath) {
  if (csvPath.empty() && wavPath.empty()) fail("recording: give the actuator CSV, the WAV, or both");
  HapticClip clip;
  std::vector<ClipChannel> channels(kMaxActuators);
  for (int i = 0; i < kMaxActuators; ++i) channels[std::size_t(i)].actuator = ActuatorId(i);
  std::vector<bool> active(kMaxActuators, false);
  if (!csvPath.empty()) {
    HapticClip envelopes = readActuatorCsv(readInputFile(csvPath, "actuator CSV", budget::kHapticFileBytes),
                                           "actuator CSV '" + csvPath.string() + "'");
    clip.duration_s = envelopes.duration_s;
    for (ClipChannel& c : envelopes.channels) {
      const auto i = std::size_t(c.actuator);
      active[i] = std::any_of(c.envelope.begin(), c.envelope.end(), [](const EnvelopePoint& p) { return p.amplitude > 0.0f; });
      channels[i].envelope = std::move(c.envelope);
    }
  }
  if (!wavPath.empty()) {
    const std::string source = "WAV '" + wavPath.string() + "'";
    WavData wav = parseWav(readInputFile(wavPath, "WAV", budget::kHapticFileBytes), source, kMaxActuators);
    clip.sampleRate_hz = wav.rate_hz;
    auto& pcm = wav.channels;
    for (std::size_t c = 0; c < pcm.size(); ++c) {
      active[c] = active[c] || std::any_of(pcm[c].begin(), pcm[c].end(), [](float x) { return x != 0.0f; });
      clip.duration_s = std::max(clip.duration_s, double(pcm[c].size()) / clip.sampleRate_hz);
      if (clip.duration_s > kMaxRecording_s)
        fail(source, ": ", clip.duration_s, " s long, past the ", kMaxRecording_s, " s a recording may last");
      channels[c].pcm = std::move(pcm[c]);
    }
  }
  clip.description = "V-Touching actuator recording";
  for (int i = 0; i < kMaxActuators; ++i) {
    if (active[std::size_t(i)]) clip.channels.push_back(std::move(channels[std::size_t(i)]));
  }
  if (clip.channels.empty()) fail("recording '", (csvPath.empty() ? wavPath : csvPath).string(), "': every actuator is silent");
  return clip;
}

std::vector<EnvelopePoint> simplifyEnvelope(const std::vector<EnvelopePoint>& points, float tolerance) {
  if (points.size() <= 2) return points;
  constexpr std::size_t kWindow = 256;  // bounds the work per point on long flat stretches
  std::vector<EnvelopePoint> out{points.front()};
  std::size_t anchor = 0;
  auto fits = [&](std::size_t end) {
    const EnvelopePoint& a = points[anchor];
    const EnvelopePoint& b = points[end];
    for (std::size_t k = anchor + 1; k < end; ++k) {
      const double w = b.t_s > a.t_s ? (points[k].t_s - a.t_s) / (b.t_s - a.t_s) : 0.0;
      const float amp = float(a.amplitude + w * (b.amplitude - a.amplitude));
      const float fa = normaliseFrequency(a.frequency_hz), fb = normaliseFrequency(b.frequency_hz);
      const float f = float(fa + w * (fb - fa));
      if (std::fabs(amp - points[k].amplitude) > tolerance || std::fabs(f - normaliseFrequency(points[k].frequency_hz)) > tolerance) {
        return false;
      }
    }
    return true;
  };
  for (std::size_t i = 2; i < points.size(); ++i) {
    if (i - anchor > kWindow || !fits(i)) {
      anchor = i - 1;
      out.push_back(points[anchor]);
    }
  }
  out.push_back(points.back());
  return out;
}

EnvelopePoint envelopeAt(const std::vector<EnvelopePoint>& envelope, double t_s) noexcept {
  if (envelope.empty()) return {t_s, 0.0f, 0.0f};
  if (t_s <= envelope.front().t_s) return {t_s, envelope.front().amplitude, envelope.front().frequency_hz};
  if (t_s >= envelope.back().t_s) return {t_s, envelope.back().amplitude, envelope.back().frequency_hz};
  const auto it = std::upper_bound(envelope.begin(), envelope.end(), t_s,
                                   [](double t, const EnvelopePoint& p) { return t < p.t_s; });
  const EnvelopePoint& b = *it;
  const EnvelopePoint& a = *(it - 1);
  const double w = b.t_s > a.t_s ? (t_s - a.t_s) / (b.t_s - a.t_s) : 1.0;
  return {t_s, float(a.amplitude + w * (b.amplitude - a.amplitude)),
          float(a.frequency_hz + w * (b.frequency_hz - a.frequency_hz))};
}

std::vector<float> channelWaveform(const ClipChannel& channel, std::uint32_t clipRate_hz, std::uint32_t rate_hz, std::size_t samples) {
  std::vector<float> out(samples, 0.0f);
  if (!channel.pcm.empty() && clipRate_hz > 0) {
    for (std::size_t s = 0; s < samples; ++s) {
      const double at = double(s) * clipRate_hz / rate_hz;
      const auto i = std::size_t(at);
      if (i + 1 >= channel.pcm.size()) {
        if (i < channel.pcm.size()) out[s] = channel.pcm[i];
        continue;
      }
      out[s] = float(channel.pcm[i] + (channel.pcm[i + 1] - channel.pcm[i]) * (at - double(i)));
    }
    return out;
  }
  const auto envelope = channelEnvelope(channel, clipRate_hz);
  double phase = 0.0;
  for (std::size_t s = 0; s < samples; ++s) {
    const EnvelopePoint p = envelopeAt(envelope, double(s) / rate_hz);
    out[s] = p.amplitude * float(std::sin(phase));
    phase += 2.0 * std::numbers::pi * (p.frequency_hz > 0.0f ? p.frequency_hz : kNominalFrequency_hz) / rate_hz;
  }
  return out;
}

HapticClip clipPart(const HapticClip& clip, double from_s, double to_s) {
  HapticClip part;
  part.sampleRate_hz = clip.sampleRate_hz;
  part.description = clip.description;
  part.duration_s = std::max(0.0, std::min(to_s, clip.duration_s) - from_s);
  for (const ClipChannel& c : clip.channels) {
    ClipChannel out;
    out.actuator = c.actuator;
    if (!c.envelope.empty()) {
      auto at = [&](double t) {
        EnvelopePoint p = envelopeAt(c.envelope, t);
        p.t_s = t - from_s;
        return p;
      };
      out.envelope.push_back(at(from_s));
      for (const EnvelopePoint& p : c.envelope)
        if (p.t_s > from_s && p.t_s < to_s) out.envelope.push_back({p.t_s - from_s, p.amplitude, p.frequency_hz});
      if (to_s <= c.envelope.back().t_s) out.envelope.push_back(at(to_s));
    }
    if (!c.pcm.empty() && clip.sampleRate_hz > 0) {
      const auto first = std::min(c.pcm.size(), std::size_t(std::llround(from_s * clip.sampleRate_hz)));
      const auto last = std::min(c.pcm.size(), std::size_t(std::llround(to_s * clip.sampleRate_hz)));
      out.pcm.assign(c.pcm.begin() + long(first), c.pcm.begin() + long(std::max(first, last)));
    }
    part.channels.push_back(std::move(out));
  }
  return part;
}

std::vector<EnvelopePoint> channelEnvelope(const ClipChannel& channel, std::uint32_t sampleRate_hz) {
  if (!channel.envelope.empty() || channel.pcm.empty() || sampleRate_hz == 0) return channel.envelope;
  const std::size_t step = std::max<std::size_t>(1, sampleRate_hz / 1000);
  std::vector<EnvelopePoint> out;
  for (std::size_t i = 0; i < channel.pcm.size(); i += step) {
    float peak = 0.0f;
    for (std::size_t k = i; k < std::min(channel.pcm.size(), i + step); ++k) peak = std::max(peak, std::fabs(channel.pcm[k]));
    out.push_back({double(i) / sampleRate_hz, std::min(peak, 1.0f), 0.0f});
  }
  return out;
}

}  // namespace vt::haptics::files
