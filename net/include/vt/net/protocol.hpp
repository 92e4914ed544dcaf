#pragma once
// The V-Touching wire protocol, version 4 (docs/protocol.md). Two datagram forms:
// - handshake (hello, accept, refuse, challenge): magic "VTNP", version, type, then the body;
//   keyed sessions add a 24-byte random nonce before and a 16-byte tag after the sealed body. A
//   server answers a hello with an accept only when it carries the cookie of a recent challenge
//   to the hello's address (a stateless cookie: replayed hellos get no session);
// - stream (pose, tactile, video, keep-alive, bye): a 4-byte header (kind, session byte, the
//   low 16 bits of the datagram sequence), the body, and a 16-byte tag when keyed, else the
//   session's random 8-byte token (a blind spoofer cannot end or hold a session). Stream
//   bodies are decoded against the session (StreamContext): the stream format agreed at
//   accept, the pose time base and the newest sequences, from which the compact fields expand.
// Encoding and decoding are allocation-free and never throw, so the network threads run them
// on every datagram; decoders reject and count bad input. Authentication: net/auth.hpp.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <variant>

#include "vt/haptics/actuator_frame.hpp"
#include "vt/net/auth.hpp"
#include "vt/scene/hand.hpp"

namespace vt::net {

inline constexpr std::uint32_t kMagic = 0x504E5456;  // bytes "VTNP" on the wire
inline constexpr std::uint8_t kProtocolVersion = 4;
/// Handshake header: magic, version, type (bit 7 set: sealed with the shared key).
inline constexpr std::size_t kHandshakeHeaderSize = 6;
/// Stream header: kind (0xC0 | type, bits 4-5 flags), session byte, sequence (low 16 bits).
inline constexpr std::size_t kStreamHeaderSize = 4;
/// Largest datagram either side sends or accepts: fits a 1500-byte Ethernet MTU with IP/UDP.
inline constexpr std::size_t kMaxDatagram = 1400;
/// IPv4 + UDP headers, counted in the wire accounting (vt_bench net).
inline constexpr std::size_t kIpUdpOverhead = 28;
inline constexpr int kMaxCodecOffers = 8;
inline constexpr std::size_t kMaxRefuseText = 120;
/// Largest encoded tactile block (raw float32 of every actuator fits).
inline constexpr std::size_t kMaxTactileData = 1300;
/// Codec blocks one tactile datagram may carry (ServerConfig/ClientConfig::blocksPerDatagram).
inline constexpr int kMaxBlocksPerDatagram = 8;
/// Frames one codec block may span (a 128 ms block of 4 ms frames).
inline constexpr int kMaxFramesPerBlock = 32;
/// Frames (levels rows) one tactile datagram may carry, over all its blocks.
inline constexpr int kMaxTactileFrames = 64;
inline constexpr std::size_t kMaxVideoData = 1340;
/// Pose positions travel in steps of this (metres); orientations and radii: docs/protocol.md.
inline constexpr float kPoseStep_m = 2e-5f;
/// A server's challenge cookie (keyed BLAKE2b of the client's address and the time).
inline constexpr std::size_t kCookieSize = 16;
/// The session token at the end of every keyless stream datagram.
inline constexpr std::size_t kTokenSize = 8;

using Cookie = std::array<std::uint8_t, kCookieSize>;

enum class MessageType : std::uint8_t { Hello = 1, Accept, Refuse, Pose, Tactile, Video, KeepAlive, Bye, Challenge };

/// Client -> server: asks for a session, offering codecs in preference order.
struct Hello {
  std::uint8_t codecCount = 0;
  std::array<std::uint8_t, kMaxCodecOffers> codecs{};  // vt::haptics::CodecId values
  std::uint8_t quality = 0;                            // requested codec quality 0..100
  std::uint64_t sceneDigest = 0;  // vt::tactileDigest of the client's scene; 0 = no local scene
  std::uint8_t flags = 0;         // kHelloWantsVideo, kHelloRedundancy; other bits must be 0
  std::uint16_t blockLength = 0;  // samples per frame wanted; 0 = the server's
  std::uint8_t block_ms = 0;      // codec block wanted (haptics::kCodecBlockLengths_ms); 0 = the server's
  std::uint8_t blocksPerDatagram = 1;  // 1..kMaxBlocksPerDatagram codec blocks per datagram
  std::int64_t client_t_ns = 0;   // client clock when sent: the session's pose time base
  std::array<float, kHandJointCount> radius_m{};  // the client's joint radii (0.01 mm steps)
  Cookie cookie{};                // the server's latest challenge; all zero = none yet
};
/// Hello flag: the client wants the server's video stream.
inline constexpr std::uint8_t kHelloWantsVideo = 0x01;
/// Hello flag: each tactile datagram also carries the block before its newest one, sent
/// already (a lost datagram's block arrives with the next; at one block per datagram only).
inline constexpr std::uint8_t kHelloRedundancy = 0x02;

/// Server -> client: session granted with the negotiated codec and stream format.
struct Accept {
  std::uint32_t sessionId = 0;
  std::uint8_t codec = 0;
  std::uint8_t quality = 0;
  std::uint8_t actuatorCount = 0;
  std::uint16_t blockLength = 0;  // samples per frame (one pose's worth)
  std::uint8_t block_ms = 4;      // codec block: block_ms * sampleRate_hz / 1000 / blockLength frames
  std::uint32_t sampleRate_hz = 0;
  std::uint16_t timeout_ms = 0;   // the server ends the session after this much silence
  std::uint64_t sceneDigest = 0;  // vt::tactileDigest of the scene the server renders
  std::uint8_t blocksPerDatagram = 1;
  std::int64_t epoch_ns = 0;      // the hello's client_t_ns, echoed: pose times count from it
  std::int64_t server_t_ns = 0;   // server clock when sent
  std::uint64_t token = 0;        // random; ends every stream datagram of a keyless session
};

enum class RefuseReason : std::uint8_t { Busy = 1, Version, NoCommonCodec, BadRequest, SceneMismatch, Unauthorized };

/// Server -> client: no session, with a reason code and printable ASCII text.
struct Refuse {
  RefuseReason reason = RefuseReason::BadRequest;
  std::uint8_t textLength = 0;
  std::array<char, kMaxRefuseText> text{};
  std::string_view message() const noexcept { return {text.data(), textLength}; }
};

/// Client -> server: the hand at one time (client clock), numbered by the pose stream. On the
/// wire: quantised positions of every joint, the palm's orientation, the session's radii.
struct Pose {
  std::uint64_t sequence = 0;
  HandPose hand;  // hand.t_ns: the time it describes; hand.sequence = sequence
};

/// Server -> client: 1..kMaxBlocksPerDatagram consecutive codec blocks, each of the session's
/// StreamContext::framesPerBlock consecutive actuator frames (their levels, then the block).
struct Tactile {
  std::uint64_t firstSequence = 0;  // sequence of the first frame (= the pose sequence it renders)
  std::uint8_t blockCount = 1;
  bool hasFrequency = false;        // frequencies below are sent (else the previous ones hold)
  std::array<std::uint16_t, haptics::kMaxActuators> frequency_hz{};
  /// Levels 0..255 of frame f of the datagram (block f / framesPerBlock).
  std::array<std::array<std::uint8_t, haptics::kMaxActuators>, kMaxTactileFrames> intensity{};
  std::array<std::uint16_t, kMaxBlocksPerDatagram> dataOffset{};  // into data
  std::array<std::uint16_t, kMaxBlocksPerDatagram> dataSize{};
  std::array<std::uint8_t, kMaxDatagram> data{};  // codec blocks, one after another
  std::span<const std::uint8_t> block(int i) const noexcept {
    return {data.data() + dataOffset[std::size_t(i)], dataSize[std::size_t(i)]};
  }
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

/// Either way: liveness and clock exchange (NTP-style). A request carries its sender's time in
/// origin_t_ns; the reply echoes it with the replier's clock at receipt and at sending.
struct KeepAlive {
  bool reply = false;
  std::int64_t origin_t_ns = 0;
  std::int64_t receive_t_ns = 0;   // reply only
  std::int64_t transmit_t_ns = 0;  // reply only
};

enum class ByeReason : std::uint8_t { Normal = 1, Timeout, Shutdown };

/// Either way: the session ends.
struct Bye {
  ByeReason reason = ByeReason::Normal;
};

/// Server -> client: send the hello again with this cookie (proof that the client receives at
/// the address it sends from; valid for 10-20 s, and only until the server restarts).
struct Challenge {
  Cookie cookie{};
};

using Message = std::variant<Hello, Accept, Refuse, Pose, Tactile, Video, KeepAlive, Bye, Challenge>;

/// The type byte of a message.
MessageType typeOf(const Message& message) noexcept;
/// Hello, accept, refuse and challenge travel in handshake datagrams, everything else in stream ones.
bool isHandshake(MessageType type) noexcept;

/// What stream datagrams are decoded against: the session as both ends agreed it.
struct StreamContext {
  std::uint32_t sessionId = 0;     // its low byte is in every stream header
  std::int64_t epoch_ns = 0;       // pose times are microseconds after this (client clock)
  int actuatorCount = 1;
  int framesPerBlock = 1;          // frames per codec block (1..kMaxFramesPerBlock)
  std::array<float, kHandJointCount> radius_m{};
  // Newest sequences received so far: compact sequence fields expand to the nearest value.
  std::uint64_t newestDatagram = 0;
  std::uint64_t newestPose = 0;
  std::uint64_t newestFrame = 0;
  const SessionKeys* keys = nullptr;  // keyed session (seal/open with these), else plain
  std::uint64_t token = 0;            // keyless session: the accept's token, checked on every datagram
  Direction receiving = Direction::ServerToClient;  // which key and nonce space this end opens
};

/// One decoded datagram.
struct Packet {
  std::uint64_t sequence = 0;  // stream datagrams: the expanded datagram sequence
  std::array<std::uint8_t, kNonceSize> nonce{};  // keyed handshake: its own nonce
  int answers = -1;  // keyed accept/refuse: index of the bound hello nonce it answers
  Message message;
};

/// Why a datagram was rejected (Ok = accepted).
enum class DecodeStatus : std::uint8_t {
  Ok = 0, Truncated, Oversized, BadMagic, UnknownVersion, UnknownType, Inconsistent,
  Unauthentic,  // tag or keyless token did not verify (forged, wrong key, corrupted), or keyed/plain mismatch
  Replayed,     // authentic but already received, or older than the replay window
  OtherSession, // a stream datagram of another session (its session byte)
};
inline constexpr int kDecodeStatusCount = 10;
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

/// Writes a handshake datagram (sealed with `key` when given, its nonce drawn at random and
/// returned in `nonce`; `boundNonce`, for an accept or refuse, is the hello's nonce it
/// answers, authenticated with it). Returns the size, or 0 when the message is invalid or
/// out is too small. Any thread.
std::size_t encodeHandshake(const Message& message, std::span<std::uint8_t> out, const Key* key = nullptr,
                            std::array<std::uint8_t, kNonceSize>* nonce = nullptr,
                            const std::array<std::uint8_t, kNonceSize>* boundNonce = nullptr) noexcept;
/// Writes a stream datagram numbered `sequence` for the session `context` (sealed with its
/// sending key when keyed, else ending with its token; `sending` picks the key and nonce space).
/// 0 when invalid. Any thread.
std::size_t encodeStream(const Message& message, std::uint64_t sequence, const StreamContext& context,
                         Direction sending, std::span<std::uint8_t> out) noexcept;

/// Parses a handshake datagram (opened with `key` when given; for an accept or refuse,
/// `boundNonces` are the hello nonces it may answer). On anything but Ok `out` is unspecified
/// and `counters` (if given) counts the reason. Never reads outside `bytes`. Any thread.
DecodeStatus decodeHandshake(std::span<const std::uint8_t> bytes, Packet& out, const Key* key = nullptr,
                             std::span<const std::array<std::uint8_t, kNonceSize>> boundNonces = {},
                             RejectCounters* counters = nullptr) noexcept;
/// Parses a stream datagram of the session `context` (authenticated when it is keyed). The
/// replay window is the caller's (ReplayWindow, after Ok). Any thread.
DecodeStatus decodeStream(std::span<const std::uint8_t> bytes, const StreamContext& context, Packet& out,
                          RejectCounters* counters = nullptr) noexcept;
/// What a session end does with each stream datagram: decodeStream, then the replay window
/// (a sequence already taken or too old: Replayed, counted); on Ok the sequence is recorded
/// and context.newestDatagram advanced. The receiving thread of the session.
DecodeStatus receiveStream(std::span<const std::uint8_t> bytes, StreamContext& context, ReplayWindow& window,
                           Packet& out, RejectCounters* counters = nullptr) noexcept;
/// True when `bytes` starts like a handshake datagram (magic), whatever its version.
bool looksLikeHandshake(std::span<const std::uint8_t> bytes) noexcept;
/// The version byte of a datagram with the handshake magic (any version), or -1.
int handshakeVersion(std::span<const std::uint8_t> bytes) noexcept;
/// A plain refuse (reason: version) with `text` in the layout a client of `version` decodes
/// (version 1 and 2: version 2's; 3: version 3's): how a server tells an older client to
/// update. Returns the size, 0 when out is too small or the version is not 1..3.
std::size_t encodeLegacyRefuse(std::string_view text, std::span<std::uint8_t> out, int version = 2) noexcept;
/// The text of a version-1/2/3 plain refuse (how an older server answers), or empty.
std::string_view legacyRefuseText(std::span<const std::uint8_t> bytes) noexcept;

/// Decodes only a message body of a known type, as decodeHandshake/decodeStream do after the
/// header (and after opening). Stream bodies need the session `context`.
DecodeStatus decodePayload(MessageType type, std::span<const std::uint8_t> payload, const StreamContext& context,
                           Message& out) noexcept;

/// The nearest 64-bit value to `reference` whose low 16 bits are `low` (never below 1).
std::uint64_t expandSequence(std::uint16_t low, std::uint64_t reference) noexcept;

}  // namespace vt::net
