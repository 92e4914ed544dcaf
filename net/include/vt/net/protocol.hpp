#pragma once
// The V-Touching wire protocol (docs/protocol.md): one UDP datagram = a 20-byte little-endian
// header + one message. Encoding and decoding are allocation-free and never throw, so the
// network threads can run them on every datagram; decoders reject and count bad input.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <variant>

#include "vt/haptics/actuator_frame.hpp"
#include "vt/scene/hand.hpp"

namespace vt::net {

inline constexpr std::uint32_t kMagic = 0x504E5456;  // bytes "VTNP" on the wire
inline constexpr std::uint8_t kProtocolVersion = 2;
inline constexpr std::size_t kHeaderSize = 20;
/// Largest datagram either side sends or accepts: fits a 1500-byte Ethernet MTU with IP/UDP.
inline constexpr std::size_t kMaxDatagram = 1400;
inline constexpr std::size_t kMaxPayload = kMaxDatagram - kHeaderSize;
inline constexpr int kMaxCodecOffers = 8;
inline constexpr std::size_t kMaxRefuseText = 120;
/// Largest encoded tactile block (raw float32 of every actuator fits).
inline constexpr std::size_t kMaxTactileData = 1300;
inline constexpr std::size_t kMaxVideoData = 1340;

enum class MessageType : std::uint8_t { Hello = 1, Accept, Refuse, Pose, Tactile, Video, KeepAlive, Bye };

/// Client -> server: asks for a session, offering codecs in preference order.
struct Hello {
  std::uint8_t codecCount = 0;
  std::array<std::uint8_t, kMaxCodecOffers> codecs{};  // vt::haptics::CodecId values
  std::uint8_t quality = 0;                            // requested codec quality 0..100
  std::uint64_t sceneDigest = 0;  // vt::tactileDigest of the client's scene; 0 = no local scene
  std::uint8_t flags = 0;         // kHelloWantsVideo; other bits must be 0
};
/// Hello flag: the client wants the server's video stream.
inline constexpr std::uint8_t kHelloWantsVideo = 0x01;

/// Server -> client: session granted with the negotiated codec and stream format.
struct Accept {
  std::uint32_t sessionId = 0;
  std::uint8_t codec = 0;
  std::uint8_t quality = 0;
  std::uint8_t actuatorCount = 0;
  std::uint16_t blockLength = 0;
  std::uint32_t sampleRate_hz = 0;
  std::uint16_t timeout_ms = 0;  // the server ends the session after this much silence
  std::uint64_t sceneDigest = 0;  // vt::tactileDigest of the scene the server renders
};

enum class RefuseReason : std::uint8_t { Busy = 1, Version, NoCommonCodec, BadRequest, SceneMismatch };

/// Server -> client: no session, with a reason code and printable ASCII text.
struct Refuse {
  RefuseReason reason = RefuseReason::BadRequest;
  std::uint8_t textLength = 0;
  std::array<char, kMaxRefuseText> text{};
  std::string_view message() const noexcept { return {text.data(), textLength}; }
};

/// Server -> client: one encoded actuator frame.
struct Tactile {
  std::uint64_t frameSequence = 0;
  std::int64_t frame_t_ns = 0;  // server clock, when rendered
  std::int64_t pose_t_ns = 0;   // client clock: timestamp of the pose it was rendered from
  std::uint8_t codec = 0;
  std::uint8_t actuatorCount = 0;
  std::uint16_t blockLength = 0;
  std::uint32_t sampleRate_hz = 0;
  std::array<std::uint8_t, haptics::kMaxActuators> intensity{};  // 0..255 = 0..1
  std::array<std::uint16_t, haptics::kMaxActuators> frequency_hz{};
  std::uint16_t dataSize = 0;
  std::array<std::uint8_t, kMaxTactileData> data{};  // codec payload
};

enum class VideoFormat : std::uint8_t { Jpeg = 1 };

/// Server -> client: one fragment of a compressed video frame (optional stream).
struct Video {
  std::uint32_t frameId = 0;
  std::uint16_t width = 0;
  std::uint16_t height = 0;
  VideoFormat format = VideoFormat::Jpeg;
  std::uint16_t fragmentIndex = 0;
  std::uint16_t fragmentCount = 0;
  std::uint16_t dataSize = 0;
  std::array<std::uint8_t, kMaxVideoData> data{};
};

/// Either way: liveness; a request carries echo_t_ns = 0, the reply echoes the request's time.
struct KeepAlive {
  std::int64_t echo_t_ns = 0;
};

enum class ByeReason : std::uint8_t { Normal = 1, Timeout, Shutdown };

/// Either way: the session ends.
struct Bye {
  ByeReason reason = ByeReason::Normal;
};

using Message = std::variant<Hello, Accept, Refuse, HandPose, Tactile, Video, KeepAlive, Bye>;

/// One datagram: header fields the sender fills plus the message.
struct Packet {
  std::uint32_t sequence = 0;    // per-sender datagram counter
  std::int64_t sender_t_ns = 0;  // sender's SteadyClock when sent
  Message message;
};

/// Why a datagram was rejected (Ok = accepted).
enum class DecodeStatus : std::uint8_t {
  Ok = 0, Truncated, Oversized, BadMagic, UnknownVersion, UnknownType, Inconsistent,
};
inline constexpr int kDecodeStatusCount = 7;
/// "truncated", "oversized", ... for logs and stats.
std::string_view statusName(DecodeStatus status) noexcept;

/// Per-reason rejection counters; any thread may count and read.
class RejectCounters {
 public:
  void count(DecodeStatus status) noexcept;
  std::uint64_t of(DecodeStatus status) const noexcept;
  /// Every rejected datagram (all reasons except Ok).
  std::uint64_t total() const noexcept;

 private:
  std::array<std::atomic<std::uint64_t>, kDecodeStatusCount> m_counts{};
};

/// The type byte of a message.
MessageType typeOf(const Message& message) noexcept;

/// Writes header + message into out; returns the datagram size, or 0 when the message is
/// itself invalid (a field out of range) or out is too small. Any thread.
std::size_t encodePacket(const Packet& packet, std::span<std::uint8_t> out) noexcept;

/// Parses one datagram. On anything but Ok, `out` is unspecified and `counters` (if given)
/// counts the reason. Never reads outside `bytes`. Any thread.
DecodeStatus decodePacket(std::span<const std::uint8_t> bytes, Packet& out,
                          RejectCounters* counters = nullptr) noexcept;

/// Decodes only a message body of a known type (what decodePacket does after the header).
DecodeStatus decodePayload(MessageType type, std::span<const std::uint8_t> payload, Message& out) noexcept;

}  // namespace vt::net
