#include "vt/net/tactile_stream.hpp"

#include <algorithm>
#include <cmath>

namespace vt::net {

bool packFrame(const haptics::ActuatorFrame& frame, const haptics::TactileCodec& codec, Tactile& out) noexcept {
  if (frame.actuatorCount < 1 || frame.actuatorCount > haptics::kMaxActuators || frame.blockLength < 1 ||
      frame.blockLength > haptics::kMaxBlockSamples || frame.sampleRate_hz < 1)
    return false;
  out.frameSequence = frame.sequence;
  out.frame_t_ns = frame.t_ns;
  out.pose_t_ns = frame.pose_t_ns;
  out.codec = std::uint8_t(codec.id());
  out.actuatorCount = frame.actuatorCount;
  out.blockLength = frame.blockLength;
  out.sampleRate_hz = frame.sampleRate_hz;
  out.intensity.fill(0);
  out.frequency_hz.fill(0);
  for (int i = 0; i < frame.actuatorCount; ++i) {
    const float level = frame.intensity[std::size_t(i)];
    const float f = frame.frequency_hz[std::size_t(i)];
    out.intensity[std::size_t(i)] = std::isfinite(level) ? std::uint8_t(std::lround(std::clamp(level, 0.0f, 1.0f) * 255.0f)) : 0;
    out.frequency_hz[std::size_t(i)] = std::isfinite(f) ? std::uint16_t(std::lround(std::clamp(f, 0.0f, 65535.0f))) : 0;
  }
  const haptics::BlockFormat format{frame.actuatorCount, frame.blockLength, int(frame.sampleRate_hz)};
  const std::size_t size = codec.encode(frame.block, format, out.data);
  // Zero bytes is a valid perceptual block (all channels silent); other codecs never produce it.
  if (size == 0 && codec.id() != haptics::CodecId::Perceptual) return false;
  out.dataSize = std::uint16_t(size);
  return true;
}

bool unpackFrame(const Tactile& message, const haptics::TactileCodec& codec, haptics::ActuatorFrame& out) noexcept {
  out = haptics::ActuatorFrame{};
  if (message.codec != std::uint8_t(codec.id())) return false;
  const haptics::BlockFormat format{message.actuatorCount, message.blockLength, int(message.sampleRate_hz)};
  if (!codec.decode(std::span(message.data.data(), message.dataSize), format, out.block)) {
    out = haptics::ActuatorFrame{};
    return false;
  }
  out.sequence = message.frameSequence;
  out.t_ns = message.frame_t_ns;
  out.pose_t_ns = message.pose_t_ns;
  out.actuatorCount = message.actuatorCount;
  out.blockLength = message.blockLength;
  out.sampleRate_hz = message.sampleRate_hz;
  for (int i = 0; i < message.actuatorCount; ++i) {
    out.intensity[std::size_t(i)] = float(message.intensity[std::size_t(i)]) / 255.0f;
    out.frequency_hz[std::size_t(i)] = float(message.frequency_hz[std::size_t(i)]);
  }
  return true;
}

}  // namespace vt::net
