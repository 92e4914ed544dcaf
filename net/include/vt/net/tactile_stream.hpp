#pragma once
// Conversion between ActuatorFrames and tactile messages through a codec. The stream format
// (actuators, block length, rate) is the session's (accept), not carried per frame.
// Allocation-free, noexcept; any thread.
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/codec/codec.hpp"
#include "vt/net/protocol.hpp"

namespace vt::net {

/// Appends `frame` as the next block of `out` (set out.blockCount = 0 for a new message; the
/// first block sets firstSequence, the next must follow it; a block that would not fit the
/// datagram is refused). Levels are quantised to 8 bits,
/// frequencies to 1 Hz (out.frequency_hz: the newest block's). False when the frame's shape is
/// not `format`, the sequence does not follow, or the block does not fit.
bool packFrame(const haptics::ActuatorFrame& frame, const haptics::TactileCodec& codec,
               const haptics::BlockFormat& format, Tactile& out) noexcept;

/// Bytes of codec data the next block of `message` may have and still fit the datagram
/// (keyed, with its tag) for `channels` actuators.
std::size_t tactileRoom(const Tactile& message, int channels) noexcept;

/// Rebuilds block `index` of a message as a frame of the session's `format`, with the
/// frequencies the receiver holds (`frequency_hz`: the message's when it has them). False
/// (frame silent) when its data does not decode.
bool unpackFrame(const Tactile& message, int index, const haptics::TactileCodec& codec,
                 const haptics::BlockFormat& format,
                 const std::array<std::uint16_t, haptics::kMaxActuators>& frequency_hz,
                 haptics::ActuatorFrame& out) noexcept;

}  // namespace vt::net
