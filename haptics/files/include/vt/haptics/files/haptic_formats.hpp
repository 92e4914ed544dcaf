#pragma once
// Reading and writing HJIF, AHAP and Meta .haptic (docs/haptic-files.md). Each reader checks the
// structure its specification defines and throws vt::Error naming the source, the field and the
// problem. Setup thread only.
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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

/// 16-bit PCM WAV, one channel per glove actuator, channel i = actuator i (as --record-wav
/// writes; silent channels stay silent): the waveform only. Writing
/// quantises to 16 bits and synthesises envelope-only channels (channelWaveform) at 8 kHz unless
/// the clip has its own rate; reading gives each non-silent channel its PCM. A clip silent at 16
/// bits is refused both ways (vt::Error): there is nothing to play.
std::string writeWav(const HapticClip& clip);
HapticClip readWav(std::string_view bytes, const std::string& source);

enum class HapticFormat { Hjif, Ahap, Meta, Wav };
/// The format a path's extension names (.hjif, .ahap, .haptic, .wav); throws vt::Error otherwise.
HapticFormat hapticFormat(const std::filesystem::path& path);
/// How a clip is cut to be written in `format`: [from, to) spans of at most kMaxClip_s each whose
/// files stay within budget::kHapticFileBytes (what `play` reads), checked before writing.
std::vector<std::pair<double, double>> fileParts(const HapticClip& clip, HapticFormat format);

/// Writes `clip` by extension (.hjif, .ahap, .haptic, .wav). A clip longer than one file may hold
/// (fileParts) becomes STEM-part1.EXT, STEM-part2.EXT, ...; AHAP and .haptic hold one channel, so
/// a clip of several channels becomes one file per actuator, STEM[-partN]-<actuator>.EXT. All
/// files appear together; an existing one is refused (naming --force) unless `replace`. Returns
/// the files written. Memory: the clip and one file's text.
std::vector<std::filesystem::path> saveHapticFile(const HapticClip& clip, const std::filesystem::path& path, bool replace);
/// Reads a file by extension (at most budget::kHapticFileBytes); single-channel files play on the
/// actuator their name ends with (STEM-<actuator>), else on `actuator`. Memory: the file, plus
/// about half its size parsed, plus the clip's samples.
HapticClip loadHapticFile(const std::filesystem::path& path, ActuatorId actuator = ActuatorId::Index);

}  // namespace vt::haptics::files

namespace vt::haptics::files {

/// What writing `clip` as `format` loses, one sentence each (empty: nothing beyond float
/// printing). `convert` prints them; docs/haptic-files.md has the same table.
std::vector<std::string> conversionLosses(const HapticClip& clip, HapticFormat format);

}  // namespace vt::haptics::files
