#pragma once
// Conversion between ActuatorFrames and tactile messages through a codec. Allocation-free,
// noexcept; any thread.
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/codec/codec.hpp"
#include "vt/net/protocol.hpp"

namespace vt::net {

/// Fills a tactile message from a frame (levels quantised to 8 bits, frequencies to 1 Hz).
/// False when the frame's shape is out of range or the block does not fit.
bool packFrame(const haptics::ActuatorFrame& frame, const haptics::TactileCodec& codec, Tactile& out) noexcept;

/// Rebuilds a frame from a decoded tactile message. False (frame silent) when the message
/// names another codec or its data does not decode.
bool unpackFrame(const Tactile& message, const haptics::TactileCodec& codec, haptics::ActuatorFrame& out) noexcept;

}  // namespace vt::net
