// A clip as a PCM16 WAV (docs/haptic-files.md, "WAV").
#include <algorithm>
#include <cmath>

#include "vt/core/error.hpp"
#include "vt/haptics/files/haptic_formats.hpp"
#include "vt/haptics/wav.hpp"

namespace vt::haptics::files {

namespace {
constexpr std::uint32_t kSynthesisRate_hz = 8000;  // the haptic loop's waveform rate
}

std::string writeWav(const HapticClip& clip) {
  const bool pcm = clip.sampleRate_hz > 0 && std::any_of(clip.channels.begin(), clip.channels.end(),
                                                          [](const ClipChannel& c) { return !c.pcm.empty(); });
  const std::uint32_t rate = pcm ? clip.sampleRate_hz : kSynthesisRate_hz;
  const auto frames = std::size_t(std::llround(clip.duration_s * rate));
  const int channels = kMaxActuators;  // channel i = actuator i, as --record-wav writes
  std::string out = wavHeader(channels, rate, frames);
  const std::size_t start = out.size();
  out.resize(start + frames * std::size_t(channels) * 2, '\0');
  bool audible = false;
  for (const ClipChannel& c : clip.channels) {
    const std::vector<float> wave = channelWaveform(c, clip.sampleRate_hz, rate, frames);
    for (std::size_t f = 0; f < frames; ++f) {
      const auto v = std::uint16_t(wavSample(wave[f]));
      audible |= v != 0;
      char* at = out.data() + start + (f * std::size_t(channels) + std::size_t(c.actuator)) * 2;
      at[0] = char(v & 0xFF), at[1] = char(v >> 8);
    }
  }
  // readWav refuses a file with nothing to play: such a clip is refused here, before it is written.
  if (!audible) fail("WAV: every channel of the clip is silent at 16 bits (nothing to write)");
  return out;
}

HapticClip readWav(std::string_view bytes, const std::string& source) {
  WavData wav = parseWav(bytes, source, kMaxActuators);
  HapticClip clip;
  clip.sampleRate_hz = wav.rate_hz;
  clip.description = "WAV waveform";
  for (std::size_t c = 0; c < wav.channels.size(); ++c) {
    clip.duration_s = std::max(clip.duration_s, double(wav.channels[c].size()) / wav.rate_hz);
    if (std::all_of(wav.channels[c].begin(), wav.channels[c].end(), [](float x) { return x == 0.0f; })) continue;
    ClipChannel channel;
    channel.actuator = ActuatorId(c);
    channel.pcm = std::move(wav.channels[c]);
    clip.channels.push_back(std::move(channel));
  }
  if (clip.duration_s > kMaxClip_s) fail(source, ": ", clip.duration_s, " s long, past the ", kMaxClip_s, " s a clip may last");
  if (clip.channels.empty()) fail(source, ": every channel is silent");
  return clip;
}

}  // namespace vt::haptics::files
