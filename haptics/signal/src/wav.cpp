#include "vt/haptics/wav.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "vt/core/error.hpp"

namespace vt::haptics {
namespace {

void put(std::string& out, std::uint32_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(char((value >> (8 * i)) & 0xFF));  // RIFF is little-endian
}

std::uint32_t le(const std::uint8_t* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= std::uint32_t(p[i]) << (8 * i);
  return v;
}

}  // namespace

std::string wavHeader(int channels, std::uint32_t rate_hz, std::uint64_t frames) {
  const std::uint32_t blockAlign = std::uint32_t(channels) * 2;
  const std::uint64_t dataBytes = frames * blockAlign;
  if (dataBytes > 0xFFFFFFFFull - 44) fail("WAV: ", dataBytes, " bytes of samples exceed the format's 4 GiB");
  std::string header = "RIFF";
  put(header, std::uint32_t(36 + dataBytes), 4);
  header += "WAVEfmt ";
  put(header, 16, 4);  // PCM fmt chunk size
  put(header, 1, 2);   // PCM
  put(header, std::uint32_t(channels), 2);
  put(header, rate_hz, 4);
  put(header, rate_hz * blockAlign, 4);
  put(header, blockAlign, 2);
  put(header, 16, 2);  // bits per sample
  header += "data";
  put(header, std::uint32_t(dataBytes), 4);
  return header;
}

std::int16_t wavSample(float x) noexcept { return std::int16_t(std::lround(std::clamp(x, -1.0f, 1.0f) * 32767.0f)); }

float wavSampleValue(std::int16_t q) noexcept { return std::max(-1.0f, float(q) / 32767.0f); }

WavData parseWav(std::string_view file, const std::string& source, int maxChannels) {
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(file.data());
  if (file.size() < 12 || std::memcmp(bytes, "RIFF", 4) || std::memcmp(bytes + 8, "WAVE", 4)) fail(source, ": not a RIFF/WAVE file");
  WavData out;
  int channels = 0;
  for (std::size_t at = 12; at + 8 <= file.size();) {
    const std::uint32_t size = le(bytes + at + 4, 4);
    if (size > file.size() - at - 8) fail(source, ": chunk at byte ", at, " runs past the end of the file");
    const std::uint8_t* body = bytes + at + 8;
    if (!std::memcmp(bytes + at, "fmt ", 4)) {
      if (size < 16 || le(body, 2) != 1 || le(body + 14, 2) != 16) fail(source, ": fmt: only 16-bit PCM is read");
      channels = int(le(body + 2, 2));
      out.rate_hz = le(body + 4, 4);
      if (channels < 1 || channels > maxChannels || out.rate_hz == 0) fail(source, ": fmt: ", channels, " channels at ", out.rate_hz, " Hz");
    } else if (!std::memcmp(bytes + at, "data", 4)) {
      if (channels == 0) fail(source, ": data chunk before the fmt chunk");
      out.channels.resize(std::size_t(channels));
      const std::size_t frames = size / (2u * std::size_t(channels));
      for (auto& c : out.channels) c.resize(frames);
      for (std::size_t f = 0; f < frames; ++f)
        for (std::size_t c = 0; c < std::size_t(channels); ++c)
          out.channels[c][f] = wavSampleValue(std::int16_t(le(body + (f * std::size_t(channels) + c) * 2, 2)));
      return out;
    }
    at += 8 + size + (size & 1u);
  }
  fail(source, ": no data chunk");
}

}  // namespace vt::haptics
