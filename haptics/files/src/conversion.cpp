// What each format keeps of a clip (docs/haptic-files.md, "Converting").
#include <algorithm>

#include "vt/core/error.hpp"
#include "vt/haptics/files/haptic_formats.hpp"

namespace vt::haptics::files {

std::vector<std::string> conversionLosses(const HapticClip& clip, HapticFormat format) {
  std::vector<std::string> losses;
  const bool pcm = clip.sampleRate_hz > 0 && std::any_of(clip.channels.begin(), clip.channels.end(),
                                                          [](const ClipChannel& c) { return !c.pcm.empty(); });
  bool outOfRange = false, unknown = false;
  for (const ClipChannel& c : clip.channels)
    for (const EnvelopePoint& p : c.envelope) {
      outOfRange = outOfRange || (p.frequency_hz > 0.0f && (p.frequency_hz < kMinFrequency_hz || p.frequency_hz > kMaxFrequency_hz));
      unknown = unknown || !(p.frequency_hz > 0.0f);
    }
  switch (format) {
    case HapticFormat::Hjif:
      if (!pcm) losses.push_back("the envelope is kept within 0.002 of amplitude, frequencies to the whole Hz");
      if (pcm && clip.channels.size() > 1 &&
          std::any_of(clip.channels.begin(), clip.channels.end(), [](const ClipChannel& c) { return c.pcm.empty(); }))
        losses.push_back("channels without a waveform are left silent: HJIF holds either waveforms or envelopes");
      break;
    case HapticFormat::Ahap:
    case HapticFormat::Meta:
      if (pcm)
        losses.push_back(str("the waveform is not carried: the envelope (1 ms peaks) is kept, its frequency ",
                             "unknown (played at the nominal ", kNominalFrequency_hz, " Hz)"));
      losses.push_back("the envelope is kept within 0.002 (amplitude and normalised frequency)");
      if (outOfRange)
        losses.push_back(str("frequencies outside ", kMinFrequency_hz, "..", kMaxFrequency_hz, " Hz are clamped to that range"));
      if (unknown && !pcm) losses.push_back(str("unknown frequencies are written as the nominal ", kNominalFrequency_hz, " Hz"));
      break;
    case HapticFormat::Wav:
      if (pcm) losses.push_back("the waveform is quantised to 16 bits (error at most 1/65534)");
      if (!pcm || std::any_of(clip.channels.begin(), clip.channels.end(), [](const ClipChannel& c) { return c.pcm.empty(); }))
        losses.push_back(str("envelope-only channels become a synthesised sine at their frequency (8 kHz); read back, ",
                             "the envelope is their 1 ms peaks and the frequency unknown"));
      break;
  }
  return losses;
}

}  // namespace vt::haptics::files
