#include <algorithm>
#include <cmath>
#include <memory>

#include "ahap_intensity.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/output_file.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace vt::haptics::files {
namespace {

// Most bytes one waveform sample or envelope point takes in each writer's output (numbers in
// their longest shortest form), so parts are sized before anything is written.
constexpr double kHjifBytesPerSample = 80.0;
constexpr double kHjifBytesPerPoint = 96.0;
constexpr double kAhapBytesPerPoint = 160.0;
constexpr double kMetaBytesPerPoint = 120.0;
constexpr double kOverheadBytes = 64.0 * 1024.0;

// Points a part [from_s, to_s) of `envelope` writes (an empty one: a waveform's 1 ms peaks, where
// AHAP inserts none), with the intensity points AHAP inserts.
std::size_t pointsIn(const std::vector<EnvelopePoint>& envelope, HapticFormat format, double from_s, double to_s) {
  if (envelope.empty()) return std::size_t((to_s - from_s) * 1000.0) + 2;
  const auto byTime = [](const EnvelopePoint& p, double t) { return p.t_s < t; };
  const auto a = std::lower_bound(envelope.begin(), envelope.end(), from_s, byTime);
  const auto b = std::lower_bound(envelope.begin(), envelope.end(), to_s, byTime);
  std::size_t points = std::size_t(b - a) + 2;
  if (format == HapticFormat::Ahap) {  // the segments the part's points bound, and the one into its start
    for (auto p = a == envelope.begin() ? a : a - 1; p != b && p + 1 != envelope.end(); ++p) {
      points += std::size_t(ahapIntensityPieces(p->amplitude, (p + 1)->amplitude, (p + 1)->t_s - p->t_s)) - 1;
    }
  }
  return points;
}

// Upper bound of the largest file the part [from_s, to_s) becomes in `format`.
double estimatedBytes(const HapticClip& clip, HapticFormat format, double from_s, double to_s) {
  double largest = 0.0, all = 0.0;
  const bool pcm = format == HapticFormat::Hjif && clip.sampleRate_hz > 0 &&
                   std::any_of(clip.channels.begin(), clip.channels.end(), [](const ClipChannel& c) { return !c.pcm.empty(); });
  for (const ClipChannel& c : clip.channels) {
    double bytes = 0.0;
    if (format == HapticFormat::Wav) bytes = (to_s - from_s) * std::max<std::uint32_t>(clip.sampleRate_hz, 8000) * 2.0 * kMaxActuators;
    else if (pcm) bytes = (to_s - from_s) * clip.sampleRate_hz * kHjifBytesPerSample + kHjifBytesPerSample;
    else {
      const double perPoint = format == HapticFormat::Hjif ? kHjifBytesPerPoint
                              : format == HapticFormat::Ahap ? kAhapBytesPerPoint : kMetaBytesPerPoint;
      bytes = double(pointsIn(c.envelope, format, from_s, to_s)) * perPoint;
    }
    largest = std::max(largest, bytes);
    all += bytes;
  }
  // HJIF and WAV hold every channel in one file (WAV counted above for all ten); AHAP and .haptic
  // one file per channel.
  return (format == HapticFormat::Hjif ? all : largest) + kOverheadBytes;
}

std::string partName(const std::filesystem::path& path, std::size_t part, std::size_t parts) {
  return parts == 1 ? path.stem().string() : str(path.stem().string(), "-part", part + 1);
}

}  // namespace

HapticFormat hapticFormat(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".hjif") return HapticFormat::Hjif;
  if (ext == ".ahap") return HapticFormat::Ahap;
  if (ext == ".haptic") return HapticFormat::Meta;
  if (ext == ".wav") return HapticFormat::Wav;
  fail("haptic file '", path.string(), "': expected .hjif, .ahap, .haptic or .wav");
}

std::vector<std::pair<double, double>> fileParts(const HapticClip& clip, HapticFormat format) {
  std::vector<std::pair<double, double>> parts;
  const double budget = double(budget::kHapticFileBytes);
  for (double from = 0.0; parts.empty() || from < clip.duration_s - 1e-9;) {
    double to = std::min(clip.duration_s, from + kMaxClip_s);
    while (estimatedBytes(clip, format, from, to) > budget) to = from + std::floor((to - from) * 500.0) / 1000.0;  // halve, whole ms
    if (!(to > from)) fail("haptic file: one millisecond of this clip does not fit in a file of ", budget::kHapticFileBytes, " bytes");
    parts.emplace_back(from, to);
    from = to;
  }
  return parts;
}

std::vector<std::filesystem::path> saveHapticFile(const HapticClip& clip, const std::filesystem::path& path, bool replace) {
  const HapticFormat format = hapticFormat(path);
  if (clip.channels.empty()) fail("haptic file '", path.string(), "': the clip has no channel");
  if (clip.duration_s > kMaxRecording_s)
    fail("haptic file '", path.string(), "': a clip of ", clip.duration_s, " s is over the ", kMaxRecording_s, " s limit");
  const auto parts = fileParts(clip, format);
  // Names first: an existing one is refused before anything is written.
  const bool perChannel = (format == HapticFormat::Ahap || format == HapticFormat::Meta) && clip.channels.size() > 1;
  std::vector<std::filesystem::path> paths;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const std::string stem = partName(path, p, parts.size());
    if (!perChannel) paths.push_back(parts.size() == 1 ? path : path.parent_path() / (stem + path.extension().string()));
    for (std::size_t c = 0; perChannel && c < clip.channels.size(); ++c)
      paths.push_back(path.parent_path() / str(stem, "-", actuatorName(clip.channels[c].actuator), path.extension().string()));
  }
  for (const auto& file : paths) refuseExisting(file, replace);
  // One file's text in memory at a time; every file is flushed before the first is renamed, so
  // they appear together (or, on a full disk, none does).
  std::vector<std::unique_ptr<OutputFile>> outputs;
  std::size_t next = 0;
  auto emit = [&](std::string text) {
    if (text.size() > budget::kHapticFileBytes)
      fail("haptic file '", paths[next].string(), "': ", text.size(), " bytes, over the ", budget::kHapticFileBytes, " bytes play reads");
    auto out = std::make_unique<OutputFile>(paths[next++]);
    out->write(text);
    out->flush();
    outputs.push_back(std::move(out));
  };
  for (const auto& [from, to] : parts) {
    const HapticClip part = parts.size() == 1 ? HapticClip{} : clipPart(clip, from, to);
    const HapticClip& source = parts.size() == 1 ? clip : part;
    switch (format) {
      case HapticFormat::Hjif: emit(writeHjif(source) + '\n'); break;
      case HapticFormat::Wav: emit(writeWav(source)); break;
      case HapticFormat::Ahap:
      case HapticFormat::Meta:
        for (std::size_t c = 0; c < source.channels.size(); ++c)
          emit((format == HapticFormat::Ahap ? writeAhap(source, c) : writeMetaHaptic(source, c)) + '\n');
        break;
    }
  }
  for (auto& out : outputs) out->commit();
  return paths;
}

HapticClip loadHapticFile(const std::filesystem::path& path, ActuatorId actuator) {
  const std::string source = "haptic file '" + path.string() + "'";
  const HapticFormat format = hapticFormat(path);
  const std::string text = readInputFile(path, "haptic file", budget::kHapticFileBytes);
  switch (format) {
    case HapticFormat::Hjif: return readHjif(text, source);
    case HapticFormat::Wav: return readWav(text, source);
    case HapticFormat::Ahap: return readAhap(text, source, actuatorFromFileName(path, actuator));
    case HapticFormat::Meta: return readMetaHaptic(text, source, actuatorFromFileName(path, actuator));
  }
  return {};
}

}  // namespace vt::haptics::files
