#pragma once
// The tactile server: one client session at a time over UDP. Its network thread runs the
// per-pose pipeline: each pose's client timestamp is mapped onto this clock with the measured
// clock offset (ClockOffset: keep-alive round trips, min-filtered), the hand is published into
// the server-side pose history, and the frame source (the touch pipeline's stepped haptic loop,
// or, without a scene, a PoseFrameSource) renders once at the pose's mapped time; when pose sequence numbers skip (loss), it also ticks
// at the missing times (the history interpolates across the gap), so every block covers one
// block period of hand travel. Each frame goes to the session's block encoder; every codec
// block (block_ms: framesPerBlock consecutive frames, a gap filled with silence) is sent back.
// Time comes from an injectable Clock (timeouts, keep-alives, rate limits).
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "vt/core/clock.hpp"
#include "vt/core/latest_value.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/codec/stream_codec.hpp"
#include "vt/net/auth.hpp"
#include "vt/net/clock_sync.hpp"
#include "vt/net/transport.hpp"
#include "vt/scene/hand.hpp"
#include "vt/scene/pose_history.hpp"

namespace vt::net {

/// Renders the frame for the hand at one time (shape, waveform, levels), where no haptic loop
/// is wanted (tests, vt_bench net, MapFrameSource). Called on the server thread.
using PoseFrameSource = std::function<void(const HandPose& pose, haptics::ActuatorFrame& frame)>;
/// One tick of a pose-driven frame source at t_ns (the touch pipeline's stepped haptic loop,
/// which samples `ServerConfig::poses`). Called on the server thread; must not block.
using TickSource = std::function<void(std::int64_t t_ns, haptics::ActuatorFrame& frame)>;

/// Server settings; bind defaults to loopback.
struct ServerConfig {
  Endpoint bind = Endpoint::ipv4(0x7F000001, 47800);
  /// Codecs the server agrees to, in its order of preference among the client's offers.
  std::vector<haptics::CodecId> codecs = {haptics::CodecId::Perceptual, haptics::CodecId::Pcm16,
                                          haptics::CodecId::RawFloat32};
  int actuatorCount = kFingerCount;
  int blockLength = haptics::kMaxBlockSamples;  // samples per frame (one pose's worth)
  int sampleRate_hz = 8000;
  /// Codec block streamed (haptics::kCodecBlockLengths_ms): 0 = whichever the client asks for,
  /// else only this one (a client asking another is refused, both named).
  int block_ms = 0;
  std::int64_t timeout_ns = 1'000'000'000;  // session ends after this much client silence
  std::int64_t keepAlive_ns = 200'000'000;  // clock-offset exchanges with the client this often
  /// The shared key (net/auth.hpp): every datagram authenticated. Required off loopback.
  std::optional<Key> key;
  Impairment impairment;                    // on what the server receives
  int realtimePriority = 0;                 // > 0: network thread real-time at this priority if allowed
  std::uint64_t sceneDigest = 0;            // vt::tactileDigest of the rendered scene (0 = unchecked)
  std::string sceneName = "its scene";      // named when a client with another scene is refused
  /// The frame source ticked at each pose's time (it must read `poses`). Or, without one,
  /// `frameSource` gets the hand sampled from the history.
  TickSource tick;
  PoseFrameSource frameSource;
  PoseSamplingConfig sampling;              // how the frame source's hand is sampled (loop: its own)
  /// The server-side pose history (this server is its only writer; the loop and a video
  /// thread read it). Null: the server keeps its own.
  PoseHistory* poses = nullptr;
  int maxGapFill = 8;                       // missing poses filled by interpolated ticks (more: a new start)
  const Clock* clock = nullptr;             // null: SteadyClock
};

/// Counters; a snapshot is safe from any thread.
struct ServerStats {
  std::uint64_t sessions = 0;
  std::uint64_t refused = 0;            // refusals sent
  std::uint64_t refusalsSuppressed = 0; // refusals and challenges not sent: over the rate limit (no reflection)
  std::uint64_t challenges = 0;         // challenges sent (to hellos without a valid cookie)
  std::uint64_t timeouts = 0;
  std::uint64_t posesApplied = 0;
  std::uint64_t posesStale = 0;         // older than one already applied (reordered)
  std::uint64_t gapTicks = 0;           // blocks rendered for lost poses (interpolated hand)
  std::uint64_t framesSent = 0;         // new frames (a block sent again for redundancy is not counted again)
  std::uint64_t blocksResent = 0;       // blocks sent a second time (hello flag kHelloRedundancy)
  std::uint64_t codecBytes = 0;         // codec payload of the frames sent (the rest is framing)
  std::uint64_t encodeFailures = 0;
  std::uint64_t strangerPackets = 0;    // session traffic from a non-client address
  std::uint64_t rejected = 0;           // datagrams the decoder refused (all reasons, forged ones too)
  std::uint64_t videoFramesSent = 0;
  std::int64_t clockOffset_ns = 0;      // client clock -> server clock (server = client + offset)
  std::int64_t rtt_ns = 0;              // round trip of the exchange the offset comes from
  bool clientConnected = false;
  bool realtime = false;              // the network thread got real-time priority (SCHED_FIFO or RealtimeKit)
  std::uint64_t bytesSent = 0, bytesReceived = 0;  // datagram bytes (without IP/UDP)
  std::uint64_t datagramsSent = 0, datagramsReceived = 0;
};

/// The server: construct and start/stop on the owner thread; it runs its own network thread.
class Server {
 public:
  /// Binds the socket (throws vt::Error naming the address; a non-loopback address without a
  /// key is refused with how to make one). Does not start the thread.
  explicit Server(ServerConfig config);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  /// The bound address (the real port when bound to port 0).
  Endpoint endpoint() const noexcept { return m_transport.localEndpoint(); }
  /// Starts the network thread. Owner thread.
  void start();
  /// Says bye to the client (if any) and joins the thread. Owner thread; idempotent.
  void stop() noexcept;
  ServerStats stats() const noexcept;
  /// The pose history the server publishes client hands into. Any thread may sample it.
  const PoseHistory& poses() const noexcept { return *m_history; }
  /// True while a client that asked for video (hello flag) is connected. Any thread.
  bool videoWanted() const noexcept { return m_videoWanted.load(std::memory_order_acquire); }
  /// Any thread (a video thread): splits one JPEG frame into video datagrams and sends them to
  /// the client when videoWanted(). False when not sent (no such client, or the frame is empty
  /// or over kMaxVideoFrameBytes). Takes as long as ~25 sendto calls.
  bool sendVideo(std::span<const std::uint8_t> jpeg, int width, int height);
  /// Per-reason decoder rejections.
  const RejectCounters& rejects() const noexcept { return m_rejects; }

 private:
  void run() noexcept;
  void receive(std::span<const std::uint8_t> bytes, const Endpoint& from, std::int64_t now_ns) noexcept;
  void handleStream(const Packet& packet, std::int64_t now_ns) noexcept;
  void handleHello(const Packet& packet, std::span<const std::uint8_t> bytes, const Endpoint& from,
                   std::int64_t now_ns) noexcept;
  /// True once per hello datagram (a replay of one already seen is false, and counted).
  bool firstSight(std::span<const std::uint8_t> hello) noexcept;
  /// The cookie `from` must send back, for the time bucket `bucket` (cookieBucket).
  Cookie cookieFor(const Endpoint& from, std::uint64_t bucket) const noexcept;
  bool validCookie(const Cookie& cookie, const Endpoint& from, std::int64_t now_ns) const noexcept;
  void challenge(const Endpoint& to, const Packet& hello, std::int64_t now_ns) noexcept;
  void applyPose(const Pose& pose, std::int64_t now_ns) noexcept;
  void render(std::uint64_t sequence, std::int64_t t_ns, const HandPose* received, bool send) noexcept;
  void sendFrame(const haptics::ActuatorFrame& frame) noexcept;
  void encodeFrame(const haptics::ActuatorFrame& frame) noexcept;
  void sendBlock() noexcept;
  void flushFrames() noexcept;
  /// The session's codec and block length for `hello`, else false with the refusal's text and reason.
  bool chooseFormat(const Hello& hello, haptics::CodecConfig& out, const char*& refusal, RefuseReason& reason) noexcept;
  bool mayRefuse(std::int64_t now_ns) noexcept;
  /// One warning line naming the peer and why, rate-limited (kRefusalLogPeriod_ns in server.cpp).
  void logRefusal(const Endpoint& from, std::string_view why, std::int64_t now_ns) noexcept;
  void refuse(const Endpoint& to, RefuseReason reason, std::string_view text, std::int64_t now_ns,
              const Packet* hello = nullptr) noexcept;
  void closeSession() noexcept;                // frees the slot (either side ended it)
  void endSession(ByeReason reason) noexcept;  // closes and tells the client why
  void sendStream(const Message& message, const Endpoint& to) noexcept;
  void sendBytes(std::span<const std::uint8_t> bytes, const Endpoint& to) noexcept;
  void setVideoClient(bool wanted, const Endpoint& client) noexcept;

  ServerConfig m_config;
  const Clock& m_clock;
  Transport m_transport;
  RejectCounters m_rejects;
  std::string m_versionText, m_legacyVersionText, m_sceneMismatchText, m_keyText, m_plainText;
  std::unique_ptr<PoseHistory> m_ownHistory;
  PoseHistory* m_history = nullptr;

  // Network-thread state.
  bool m_active = false;
  bool m_confirmed = false;  // the client sent stream traffic (a pending session yields to a new hello)
  Endpoint m_client;
  Accept m_accept;
  std::array<std::uint8_t, kMaxDatagram> m_acceptBytes{};  // resent as is when the accept was lost
  std::size_t m_acceptSize = 0;
  std::unique_ptr<haptics::BlockEncoder> m_encoder;  // the session's negotiated codec and block length
  haptics::BlockFormat m_format;                     // the frames the loop or frame source produces
  std::array<haptics::ActuatorFrame, kMaxFramesPerBlock> m_blockFrames{};  // the encoder's pending frames
  std::uint64_t m_nextFrame = 0;                     // sequence the pending block continues with
  std::array<char, kMaxRefuseText> m_refuseText{};   // a refusal worded on the network thread
  StreamContext m_context;  // the session as sent; m_receive also tracks the newest received
  StreamContext m_receive;
  std::array<SessionKeys, 2> m_keys{};  // alternate per session: the video thread's copy stays valid
  ReplayWindow m_replay;
  std::vector<std::array<std::uint8_t, 16>> m_seenHellos;  // digests of the hellos already taken (a ring)
  std::size_t m_seenHelloCount = 0;
  Key m_cookieSecret{};  // random per process: a restart invalidates every cookie
  ClockOffset m_offset;
  std::int64_t m_lastHeard_ns = 0;
  std::int64_t m_nextKeepAlive_ns = 0;
  std::uint64_t m_lastPoseSequence = 0;
  std::int64_t m_lastPose_t_ns = 0;  // server clock
  bool m_havePose = false;
  Tactile m_pending;  // blocks waiting to fill a datagram
  // Redundancy (kHelloRedundancy): the datagram sent last, whose newest block the next one carries
  // again; blocks rendered for lost poses wait for the pose after them instead of going alone.
  bool m_redundant = false;
  bool m_fillingGap = false;
  int m_pendingResent = 0;  // leading blocks of m_pending sent already
  Tactile m_sent;
  std::array<std::uint16_t, haptics::kMaxActuators> m_sentFrequency{};
  int m_sinceFrequency = 0;
  double m_refuseTokens = 0.0, m_challengeTokens = 0.0;
  std::int64_t m_refuseRefill_ns = 0, m_challengeRefill_ns = 0;
  std::int64_t m_nextRefusalLog_ns = 0;
  std::uint64_t m_refusalsLogged = 0, m_refusalsUnlogged = 0;
  std::atomic<std::uint64_t> m_sendSequence{0};  // the video thread sends too
  std::uint32_t m_nextSessionId = 1;

  std::atomic<std::uint64_t> m_sessions{0}, m_refused{0}, m_suppressed{0}, m_challenges{0}, m_timeouts{0}, m_posesApplied{0},
      m_posesStale{0}, m_gapTicks{0}, m_framesSent{0}, m_blocksResent{0}, m_codecBytes{0}, m_encodeFailures{0}, m_strangers{0}, m_bytesSent{0},
      m_bytesReceived{0}, m_datagramsSent{0}, m_datagramsReceived{0};
  std::atomic<std::int64_t> m_offset_ns{0}, m_rtt_ns{0};
  // Where the video thread sends and the session context it encodes with, read whole by any
  // thread; published before m_videoWanted is set.
  struct VideoDestination {
    Endpoint to;
    StreamContext context;
  };
  LatestValue<VideoDestination> m_videoDestination;
  std::atomic<bool> m_videoWanted{false};
  std::atomic<std::uint32_t> m_videoFrameId{0};
  std::atomic<std::uint64_t> m_videoFramesSent{0};
  std::atomic<bool> m_connected{false};
  std::atomic<bool> m_realtime{false};
  std::atomic<bool> m_running{false};
  std::thread m_thread;
};

}  // namespace vt::net
