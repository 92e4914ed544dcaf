#include "vt/net/tactile_stream.hpp"

#include <algorithm>
#include <cmath>

namespace vt::net {

std::size_t tactileRoom(const Tactile& message, int channels) noexcept {
  const int b = message.blockCount;
  const std::size_t used = b == 0 ? 0 : std::size_t(message.dataOffset[std::size_t(b - 1)]) + message.dataSize[std::size_t(b - 1)];
  // Header, sequence, block count, frequencies, then per block its levels and a length, and the tag.
  const std::size_t framing = kStreamHeaderSize + 3 + 2 * std::size_t(channels) +
                              std::size_t(b + 1) * (std::size_t(channels) + 2) + kTagSize;
  return b >= kMaxBlocksPerDatagram || framing + used > kMaxDatagram ? 0 : std::min(kMaxDatagram - framing - used, kMaxTactileData);
}

bool packFrame(const haptics::ActuatorFrame& frame, const haptics::TactileCodec& codec,
               const haptics::BlockFormat& format, Tactile& out) noexcept {
  if (frame.actuatorCount != format.channels || frame.blockLength != format.length ||
      int(frame.sampleRate_hz) != format.sampleRate_hz || out.blockCount >= kMaxBlocksPerDatagram)
    return false;
  const int b = out.blockCount;
  if (b == 0) out.firstSequence = frame.sequence;
  else if (frame.sequence != out.firstSequence + std::uint64_t(b)) return false;
  const std::size_t offset = b == 0 ? 0 : std::size_t(out.dataOffset[std::size_t(b - 1)]) + out.dataSize[std::size_t(b - 1)];
  auto& levels = out.intensity[std::size_t(b)];
  levels.fill(0);
  for (int i = 0; i < frame.actuatorCount; ++i) {
    const float level = frame.intensity[std::size_t(i)];
    const float f = frame.frequency_hz[std::size_t(i)];
    levels[std::size_t(i)] = std::isfinite(level) ? std::uint8_t(std::lround(std::clamp(level, 0.0f, 1.0f) * 255.0f)) : 0;
    out.frequency_hz[std::size_t(i)] = std::isfinite(f) ? std::uint16_t(std::lround(std::clamp(f, 0.0f, 65535.0f))) : 0;
  }
  const auto space = std::span(out.data).subspan(offset);
  std::array<std::uint8_t, haptics::kMaxEncodedBlock> coded{};
  const std::size_t size = codec.encode(frame.block, format, coded);
  // Zero bytes is a valid perceptual block (all channels silent); other codecs never produce it.
  if ((size == 0 && codec.id() != haptics::CodecId::Perceptual) || size > space.size() ||
      size > tactileRoom(out, format.channels))
    return false;
  std::copy_n(coded.begin(), size, space.begin());
  out.dataOffset[std::size_t(b)] = std::uint16_t(offset);
  out.dataSize[std::size_t(b)] = std::uint16_t(size);
  out.blockCount = std::uint8_t(b + 1);
  return true;
}

bool unpackFrame(const Tactile& message, int index, const haptics::TactileCodec& codec,
                 const haptics::BlockFormat& format,
                 const std::array<std::uint16_t, haptics::kMaxActuators>& frequency_hz,
                 haptics::ActuatorFrame& out) noexcept {
  out = haptics::ActuatorFrame{};
  if (index < 0 || index >= message.blockCount || !codec.decode(message.block(index), format, out.block)) {
    out = haptics::ActuatorFrame{};
    return false;
  }
  out.sequence = message.firstSequence + std::uint64_t(index);
  out.actuatorCount = std::uint8_t(format.channels);
  out.blockLength = std::uint16_t(format.length);
  out.sampleRate_hz = std::uint32_t(format.sampleRate_hz);
  for (int i = 0; i < format.channels; ++i) {
    out.intensity[std::size_t(i)] = float(message.intensity[std::size_t(index)][std::size_t(i)]) / 255.0f;
    out.frequency_hz[std::size_t(i)] = float(frequency_hz[std::size_t(i)]);
  }
  return true;
}

}  // namespace vt::net
