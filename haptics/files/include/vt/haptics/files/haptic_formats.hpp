#pragma once
// Reading and writing HJIF, AHAP and Meta .haptic (docs/haptic-files.md). Each reader checks the
// structure its specification defines and throws vt::Error naming the source, the field and the
// problem. Setup thread only.
#include <filesystem>
#include <string>
#include <string_view>

#include "vt/haptics/files/haptic_clip.hpp"

namespace vt::haptics::files {

/// MPEG HJIF (ISO/IEC 23090-31 JSON): one Vibrotactile perception, one channel per actuator with
/// its hand location; PCM as a Linear Curve band at the sample rate, else the envelope as a
/// VectorialWave band (Sine) with amplitude and frequency keyframes.
std::string writeHjif(const HapticClip& clip);
HapticClip readHjif(std::string_view text, const std::string& source);

/// Apple AHAP for one channel: HapticContinuous events (at most 30 s each) shaped by
/// HapticIntensityControl (sqrt of the amplitude) and HapticSharpnessControl (normalised frequency)
/// curves of at most 16 points. The waveform is not carried.
std::string writeAhap(const HapticClip& clip, std::size_t channel);
/// Reads continuous and transient events and the two control curves into one envelope channel.
HapticClip readAhap(std::string_view text, const std::string& source, ActuatorId actuator);

/// Meta .haptic 1.0 for one channel: amplitude and normalised frequency envelopes.
std::string writeMetaHaptic(const HapticClip& clip, std::size_t channel);
HapticClip readMetaHaptic(std::string_view text, const std::string& source, ActuatorId actuator);

/// Writes `clip` by extension (.hjif, .ahap, .haptic). AHAP and .haptic hold one channel: a clip of
/// several channels becomes one file per actuator, STEM-<actuator>.EXT, all appearing together; an
/// existing one is refused (naming --force) unless `replace`. Returns the files written.
std::vector<std::filesystem::path> saveHapticFile(const HapticClip& clip, const std::filesystem::path& path, bool replace);
/// Reads a file by extension (at most budget::kHapticFileBytes); single-channel files play on the
/// actuator their name ends with (STEM-<actuator>), else on `actuator`.
HapticClip loadHapticFile(const std::filesystem::path& path, ActuatorId actuator = ActuatorId::Index);

}  // namespace vt::haptics::files
