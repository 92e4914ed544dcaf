#pragma once
// A recorded or imported haptic signal, one channel per actuator, and its exchange with the
// field's haptic files: MPEG HJIF (ISO/IEC 23090-31, .hjif), Apple AHAP (.ahap) and Meta's
// .haptic (docs/haptic-files.md says what each keeps and loses). Setup/recording threads only;
// loaders throw vt::Error naming the file, the field and the problem.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/frequency_scale.hpp"

namespace vt::haptics::files {

/// One point of a channel's envelope: drive level and dominant frequency from time t_s on.
struct EnvelopePoint {
  double t_s = 0.0;
  float amplitude = 0.0f;     // 0..1
  float frequency_hz = 0.0f;  // 0 = unknown
};

/// One actuator's signal: the envelope (what AHAP and .haptic carry) and, when known, the waveform.
struct ClipChannel {
  ActuatorId actuator = ActuatorId::Index;
  std::vector<EnvelopePoint> envelope;  // sorted by time, linear in between; empty = from the PCM
  std::vector<float> pcm;               // -1..1 at HapticClip::sampleRate_hz; empty = envelope only
};

struct HapticClip {
  std::uint32_t sampleRate_hz = 0;  // of every channel's pcm (0 when none has PCM)
  double duration_s = 0.0;
  std::string description;
  std::vector<ClipChannel> channels;
};

/// Longest clip the readers accept (bounds memory for any input file); export and convert split
/// longer ones into parts of at most this.
inline constexpr double kMaxClip_s = 600.0;
/// Shortest span AHAP and .haptic write (both need one): a clip spanning less, such as a one-line
/// recording, is written as one 1 ms tick of the haptic loop.
inline constexpr double kShortestWrittenClip_s = 0.001;
/// Longest recording export and convert take (six parts of kMaxClip_s).
inline constexpr double kMaxRecording_s = 3600.0;
/// Highest envelope frequency a file may give (far above any actuator's; HJIF keyframes, actuator
/// CSVs).
inline constexpr double kMaxEnvelopeFrequency_hz = 1e5;
/// Most waveform samples a clip holds in all its channels together (10 actuators at 8 kHz for
/// kMaxClip_s, 192 MB of floats): a small file cannot ask for more.
inline constexpr std::size_t kMaxClipSamples = std::size_t(10 * 8000 * 600);

// Frequencies are normalised on vt/haptics/frequency_scale.hpp's scale (unknown = nominal).

/// Reads what ActuatorRecorder wrote (`--record-csv` envelope, `--record-wav` waveform; either
/// path may be empty). Actuators that stay silent in both are left out; recordings longer than
/// kMaxRecording_s are refused.
HapticClip loadRecording(const std::filesystem::path& csvPath, const std::filesystem::path& wavPath);
/// An actuator CSV's text (`--record-csv`), `source` named in errors: one envelope channel per
/// actuator column in the header's order, silent ones included.
HapticClip readActuatorCsv(std::string_view text, const std::string& source);

/// Drops envelope points that linear interpolation between their neighbours reproduces within
/// `tolerance` (amplitude, and normalised frequency).
std::vector<EnvelopePoint> simplifyEnvelope(const std::vector<EnvelopePoint>& points, float tolerance);

/// Envelope value at t (linear; the ends hold; amplitude 0 past the last point of the clip).
EnvelopePoint envelopeAt(const std::vector<EnvelopePoint>& envelope, double t_s) noexcept;

/// The channel's waveform at `rate_hz`, `samples` long: its PCM resampled linearly, or for an
/// envelope-only channel a sine at the envelope's frequency (kNominalFrequency_hz where unknown).
std::vector<float> channelWaveform(const ClipChannel& channel, std::uint32_t clipRate_hz, std::uint32_t rate_hz, std::size_t samples);

/// The part of `clip` in [from_s, to_s), its times starting at 0: envelopes are cut where they
/// cross the ends (by interpolation), waveforms at the nearest samples.
HapticClip clipPart(const HapticClip& clip, double from_s, double to_s);

/// The channel's envelope, computed from its PCM (peak per 1 ms) when it has none.
std::vector<EnvelopePoint> channelEnvelope(const ClipChannel& channel, std::uint32_t sampleRate_hz);

/// The actuator a single-channel file was exported for: a `-<actuator>` suffix on its stem
/// ("session-index.ahap"), else `fallback`.
ActuatorId actuatorFromFileName(const std::filesystem::path& path, ActuatorId fallback) noexcept;

/// Parses an actuator name ("index", "palm-little-down", or a legacy "pinky" one); throws vt::Error naming `what`.
ActuatorId parseActuator(const std::string& name, const std::string& what);

}  // namespace vt::haptics::files
