#pragma once
// 16-bit PCM WAV, the waveform file of --record-wav and of `convert`: one channel per actuator
// (channel i = ActuatorId i), little-endian RIFF. Any thread; no shared state.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace vt::haptics {

/// The 44-byte header of a PCM16 WAV of `frames` frames; throws vt::Error past the format's 4 GiB.
std::string wavHeader(int channels, std::uint32_t rate_hz, std::uint64_t frames);
/// A sample -1..1 as the file stores it (clamped, rounded): x * 32767.
std::int16_t wavSample(float x) noexcept;
/// A stored sample as -1..1: q / 32767, and -32768 (which wavSample never writes) as -1.
float wavSampleValue(std::int16_t q) noexcept;

/// The channels of a PCM16 WAV, each -1..1; throws vt::Error naming `source` and the problem.
struct WavData {
  std::uint32_t rate_hz = 0;
  std::vector<std::vector<float>> channels;
};
WavData parseWav(std::string_view bytes, const std::string& source, int maxChannels);

}  // namespace vt::haptics
