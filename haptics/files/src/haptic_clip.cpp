#include "vt/haptics/files/haptic_clip.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <sstream>

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"

namespace vt::haptics::files {
namespace {

std::uint32_t le(const std::uint8_t* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= std::uint32_t(p[i]) << (8 * i);
  return v;
}

// The 16-bit PCM WAV ActuatorRecorder writes (any RIFF PCM16 file with its chunks in order works).
std::vector<std::vector<float>> readWav(const std::filesystem::path& path, std::uint32_t& rate_hz) {
  const std::string source = "WAV '" + path.string() + "'";
  const std::string file = readInputFile(path, "WAV", budget::kHapticFileBytes);
  const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(file.data()), file.size());
  if (bytes.size() < 12 || std::memcmp(bytes.data(), "RIFF", 4) || std::memcmp(bytes.data() + 8, "WAVE", 4)) {
    fail(source, ": not a RIFF/WAVE file");
  }
  int channels = 0;
  for (std::size_t at = 12; at + 8 <= bytes.size();) {
    const std::uint32_t size = le(bytes.data() + at + 4, 4);
    if (size > bytes.size() - at - 8) fail(source, ": chunk at byte ", at, " runs past the end of the file");
    const std::uint8_t* body = bytes.data() + at + 8;
    if (!std::memcmp(bytes.data() + at, "fmt ", 4)) {
      if (size < 16 || le(body, 2) != 1 || le(body + 14, 2) != 16) fail(source, ": fmt: only 16-bit PCM is read");
      channels = int(le(body + 2, 2));
      rate_hz = le(body + 4, 4);
      if (channels < 1 || channels > kMaxActuators || rate_hz == 0) fail(source, ": fmt: ", channels, " channels at ", rate_hz, " Hz");
    } else if (!std::memcmp(bytes.data() + at, "data", 4)) {
      if (channels == 0) fail(source, ": data chunk before the fmt chunk");
      std::vector<std::vector<float>> out{std::size_t(channels)};
      const std::size_t frames = size / (2u * std::size_t(channels));
      for (auto& c : out) c.resize(frames);
      for (std::size_t f = 0; f < frames; ++f) {
        for (int c = 0; c < channels; ++c) {
          out[std::size_t(c)][f] = float(std::int16_t(le(body + (f * std::size_t(channels) + std::size_t(c)) * 2, 2))) / 32767.0f;
        }
      }
      return out;
    }
    at += 8 + size + (size & 1u);
  }
  fail(source, ": no data chunk");
}

}  // namespace

float normaliseFrequency(float frequency_hz) noexcept {
  return std::clamp((frequency_hz - kMinFrequency_hz) / (kMaxFrequency_hz - kMinFrequency_hz), 0.0f, 1.0f);
}

float frequencyFromNormalised(float normalised) noexcept {
  return kMinFrequency_hz + std::clamp(normalised, 0.0f, 1.0f) * (kMaxFrequency_hz - kMinFrequency_hz);
}

ActuatorId parseActuator(const std::string& name, const std::string& what) {
  for (int i = 0; i < kMaxActuators; ++i) {
    if (actuatorName(ActuatorId(i)) == name) return ActuatorId(i);
  }
  fail(what, ": unknown actuator '", name, "' (thumb, index, middle, ring, pinky, palm-index-up, ...)");
}

ActuatorId actuatorFromFileName(const std::filesystem::path& path, ActuatorId fallback) noexcept {
  const std::string stem = path.stem().string();
  const std::string_view view(stem);
  ActuatorId best = fallback;
  std::size_t bestLength = 0;
  // "palm-index-up" also ends in "-up"-like suffixes of shorter names: the longest match wins.
  for (int i = 0; i < kMaxActuators; ++i) {
    const std::string_view name = actuatorName(ActuatorId(i));
    if (view.size() > name.size() + 1 && view.substr(view.size() - name.size()) == name &&
        view[view.size() - name.size() - 1] == '-' && name.size() > bestLength) {
      best = ActuatorId(i), bestLength = name.size();
    }
  }
  return best;
}

HapticClip loadRecording(const std::filesystem::path& csvPath, const std::filesystem::path& wavPath) {
  if (csvPath.empty() && wavPath.empty()) fail("recording: give the actuator CSV, the WAV, or both");
  HapticClip clip;
  std::vector<ClipChannel> channels(kMaxActuators);
  for (int i = 0; i < kMaxActuators; ++i) channels[std::size_t(i)].actuator = ActuatorId(i);
  std::vector<bool> active(kMaxActuators, false);
  if (!csvPath.empty()) {
    const std::string source = "actuator CSV '" + csvPath.string() + "'";
    std::istringstream in(readInputFile(csvPath, "actuator CSV", budget::kHapticFileBytes));
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header;
    std::stringstream hs(line);
    for (std::string field; std::getline(hs, field, ',');) header.push_back(field);
    if (header.size() < 4 || header[0] != "t_ns" || header[1] != "sequence" || (header.size() - 2) % 2) {
      fail(source, ": line 1: expected t_ns,sequence,<actuators>,<actuators>_hz (as --record-csv writes)");
    }
    const std::size_t n = (header.size() - 2) / 2;
    if (n > std::size_t(kMaxActuators)) fail(source, ": line 1: more than ", kMaxActuators, " actuators");
    std::vector<ActuatorId> ids;
    for (std::size_t i = 0; i < n; ++i) ids.push_back(parseActuator(header[2 + i], source + " line 1"));
    double t0 = NAN;
    for (int number = 2; std::getline(in, line); ++number) {
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
      // Checked before anything is sized by the duration (two rows 10^18 ns apart asked for gigabytes).
      if (t_s > kMaxClip_s) fail(source, " line ", number, ": ", t_s, " s after the first row, past the longest clip of ", kMaxClip_s, " s");
      clip.duration_s = t_s;
      for (std::size_t i = 0; i < n; ++i) {
        ClipChannel& c = channels[std::size_t(ids[i])];
        const float amplitude = std::clamp(float(v[2 + i]), 0.0f, 1.0f);
        c.envelope.push_back({t_s, amplitude, float(std::max(0.0, v[2 + n + i]))});
        active[std::size_t(ids[i])] = active[std::size_t(ids[i])] || amplitude > 0.0f;
      }
    }
  }
  if (!wavPath.empty()) {
    auto pcm = readWav(wavPath, clip.sampleRate_hz);
    for (std::size_t c = 0; c < pcm.size(); ++c) {
      active[c] = active[c] || std::any_of(pcm[c].begin(), pcm[c].end(), [](float x) { return x != 0.0f; });
      clip.duration_s = std::max(clip.duration_s, double(pcm[c].size()) / clip.sampleRate_hz);
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
