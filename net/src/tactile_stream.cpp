#include "vt/net/tactile_stream.hpp"

#include <algorithm>
#include <cmath>

namespace vt::net {

std::size_t tactileRoom(const Tactile& message, const StreamContext& context) noexcept {
  const int b = message.blockCount;
  const auto channels = std::size_t(context.actuatorCount);
  const auto frames = std::size_t(context.framesPerBlock);
  const std::size_t used = b == 0 ? 0 : std::size_t(message.dataOffset[std::size_t(b - 1)]) + message.dataSize[std::size_t(b - 1)];
  // Header, sequence, block count, frequencies, then per block its frames' levels and a length, and the tag.
  const std::size_t framing = kStreamHeaderSize + 3 + 2 * channels + std::size_t(b + 1) * (frames * channels + 2) + kTagSize;
  const bool full = b >= kMaxBlocksPerDatagram || std::size_t(b + 1) * frames > std::size_t(kMaxTactileFrames);
  return full || framing + used > kMaxDatagram ? 0 : std::min(kMaxDatagram - framing - used, kMaxTactileData);
}

bool packBlock(std::span<const haptics::ActuatorFrame> frames, std::span<const std::uint8_t> packet,
               const StreamContext& context, Tactile& out) noexcept {
  const int b = out.blockCount;
  if (int(frames.size()) != context.framesPerBlock || b >= kMaxBlocksPerDatagram ||
      packet.size() > tactileRoom(out, context))
    return false;
  if (b == 0) out.firstSequence = frames[0].sequence;
  for (std::size_t f = 0; f < frames.size(); ++f)
    if (frames[f].sequence != out.firstSequence + std::uint64_t(b) * frames.size() + f) return false;
  const std::size_t offset = b == 0 ? 0 : std::size_t(out.dataOffset[std::size_t(b - 1)]) + out.dataSize[std::size_t(b - 1)];
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const haptics::ActuatorFrame& frame = frames[f];
    auto& levels = out.intensity[std::size_t(b) * frames.size() + f];
    levels.fill(0);
    for (int i = 0; i < std::min<int>(frame.actuatorCount, context.actuatorCount); ++i) {
      const float level = frame.intensity[std::size_t(i)];
      const float hz = frame.frequency_hz[std::size_t(i)];
      levels[std::size_t(i)] = std::isfinite(level) ? std::uint8_t(std::lround(std::clamp(level, 0.0f, 1.0f) * 255.0f)) : 0;
      out.frequency_hz[std::size_t(i)] = std::isfinite(hz) ? std::uint16_t(std::lround(std::clamp(hz, 0.0f, 65535.0f))) : 0;
    }
  }
  std::copy(packet.begin(), packet.end(), out.data.begin() + std::ptrdiff_t(offset));
  out.dataOffset[std::size_t(b)] = std::uint16_t(offset);
  out.dataSize[std::size_t(b)] = std::uint16_t(packet.size());
  out.blockCount = std::uint8_t(b + 1);
  return true;
}

bool copyBlock(const Tactile& from, int index, const StreamContext& context, Tactile& out) noexcept {
  const int b = out.blockCount;
  const auto frames = std::size_t(context.framesPerBlock);
  if (index < 0 || index >= from.blockCount || b >= kMaxBlocksPerDatagram || from.block(index).size() > tactileRoom(out, context))
    return false;
  const std::uint64_t first = from.firstSequence + std::uint64_t(index) * frames;
  if (b == 0) out.firstSequence = first;
  if (first != out.firstSequence + std::uint64_t(b) * frames) return false;
  const std::size_t offset = b == 0 ? 0 : std::size_t(out.dataOffset[std::size_t(b - 1)]) + out.dataSize[std::size_t(b - 1)];
  for (std::size_t f = 0; f < frames; ++f) out.intensity[std::size_t(b) * frames + f] = from.intensity[std::size_t(index) * frames + f];
  const auto data = from.block(index);
  std::copy(data.begin(), data.end(), out.data.begin() + std::ptrdiff_t(offset));
  out.dataOffset[std::size_t(b)] = std::uint16_t(offset);
  out.dataSize[std::size_t(b)] = std::uint16_t(data.size());
  out.blockCount = std::uint8_t(b + 1);
  return true;
}

bool unpackBlock(const Tactile& message, int index, haptics::BlockDecoder& decoder,
                 const std::array<std::uint16_t, haptics::kMaxActuators>& frequency_hz,
                 std::span<haptics::ActuatorFrame> out) noexcept {
  const int frames = decoder.frameCount();
  const haptics::CodecConfig& format = decoder.config();
  const bool good = index >= 0 && index < message.blockCount && frames <= int(out.size()) &&
                    (index + 1) * frames <= kMaxTactileFrames && decoder.decode(message.block(index));
  for (int f = 0; f < std::min<int>(frames, int(out.size())); ++f) {
    haptics::ActuatorFrame& frame = out[std::size_t(f)];
    frame = haptics::ActuatorFrame{};
    if (!good) continue;
    frame.block = decoder.frame(f);
    frame.sequence = message.firstSequence + std::uint64_t(index * frames + f);
    frame.actuatorCount = std::uint8_t(format.channels);
    frame.blockLength = std::uint16_t(format.frameLength);
    frame.sampleRate_hz = std::uint32_t(format.sampleRate_hz);
    const auto& levels = message.intensity[std::size_t(index * frames + f)];
    for (int i = 0; i < format.channels; ++i) {
      frame.intensity[std::size_t(i)] = float(levels[std::size_t(i)]) / 255.0f;
      frame.frequency_hz[std::size_t(i)] = float(frequency_hz[std::size_t(i)]);
    }
  }
  return good;
}

}  // namespace vt::net
