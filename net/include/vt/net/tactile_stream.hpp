#pragma once
// Conversion between ActuatorFrames and tactile messages through the session's block codec
// (haptics/codec/stream_codec.hpp). A codec block spans StreamContext::framesPerBlock
// consecutive frames; its frames' levels travel beside it. The stream format (actuators,
// frame length, block length, rate) is the session's (accept), not carried per message.
// Allocation-free, noexcept; any thread.
#include <span>

#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/codec/stream_codec.hpp"
#include "vt/net/protocol.hpp"

namespace vt::net {

/// Appends one codec block as the next block of `out` (set out.blockCount = 0 for a new
/// message): `packet` is the encoder's output for `frames` (framesPerBlock consecutive frames,
/// following the message's). Levels are quantised to 8 bits, frequencies to 1 Hz
/// (out.frequency_hz: the newest frame's). False when the frames do not follow or the block
/// does not fit the datagram.
bool packBlock(std::span<const haptics::ActuatorFrame> frames, std::span<const std::uint8_t> packet,
               const StreamContext& context, Tactile& out) noexcept;

/// Appends block `index` of `from` (a message of the same session) as the next block of `out`:
/// a block sent already, sent again. False when it does not follow or does not fit.
bool copyBlock(const Tactile& from, int index, const StreamContext& context, Tactile& out) noexcept;

/// Bytes of codec data the next block of `message` may have and still fit the datagram
/// (keyed, with its tag) for the session `context`.
std::size_t tactileRoom(const Tactile& message, const StreamContext& context) noexcept;

/// Decodes block `index` of a message with `decoder` (the session's) and rebuilds its frames
/// into `out` (decoder.frameCount() of them), with the frequencies the receiver holds
/// (`frequency_hz`: the message's when it has them). False (frames silent) when its data does
/// not decode or `out` is too small.
bool unpackBlock(const Tactile& message, int index, haptics::BlockDecoder& decoder,
                 const std::array<std::uint16_t, haptics::kMaxActuators>& frequency_hz,
                 std::span<haptics::ActuatorFrame> out) noexcept;

}  // namespace vt::net
