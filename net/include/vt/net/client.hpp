#pragma once
// The tactile client: connects to a server (hello with codec offers), and then runs two
// threads. The sender samples the client's pose history once per frame period (the session's
// frame length / rate) at the send time and sends that hand, stamped with the time it
// describes (this clock) and numbered by the pose stream. The network thread receives tactile
// codec blocks (one or more frames each: block_ms), decodes them, plays the frames out through
// a jitter buffer with concealment into the sinks (an SpscRing and/or a LatestValue mailbox),
// exchanges keep-alives (round-trip time) and
// reconnects. It measures motion-to-vibration latency: the time a pose describes -> the frame
// rendered for it leaving the jitter buffer (both on this side's clock). Time comes from an
// injectable Clock: timeouts, keep-alives, reconnection and playout run on it.
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "vt/core/clock.hpp"
#include "vt/core/time_alignment.hpp"
#include "vt/core/latest_value.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/actuator_sink.hpp"
#include "vt/haptics/codec/stream_codec.hpp"
#include "vt/net/auth.hpp"
#include "vt/net/jitter_buffer.hpp"
#include "vt/net/transport.hpp"
#include "vt/net/video_stream.hpp"
#include "vt/scene/pose_history.hpp"

namespace vt::net {

/// Client settings; the server address defaults to loopback.
struct ClientConfig {
  /// Perceptual, 16-bit PCM, raw float32.
  static std::vector<haptics::CodecId> defaultCodecs() {
    return {haptics::CodecId::Perceptual, haptics::CodecId::Pcm16, haptics::CodecId::RawFloat32};
  }
  Endpoint server = Endpoint::ipv4(0x7F000001, 47800);
  std::optional<Endpoint> bind;  // empty: localEndpointFor(server)
  std::vector<haptics::CodecId> codecs = defaultCodecs();  // in preference order
  int quality = 50;
  std::uint16_t blockLength = 0;               // samples per frame wanted; 0 = the server's
  int block_ms = 4;                            // codec block (haptics::kCodecBlockLengths_ms): longer = fewer bits, more delay
  int blocksPerDatagram = 1;                   // codec blocks packed per datagram (1..8): fewer bytes, more delay
  std::uint64_t sceneDigest = 0;               // vt::tactileDigest of the scene shown here (0 = none)
  std::string sceneName;                       // names that scene when the server refuses it (another scene)
  bool wantVideo = false;                      // ask for the server's video stream (see video())
  /// Ask for each block again in the next datagram (kHelloRedundancy; one block per datagram only):
  /// a lost datagram's block arrives a period later, so playout waits one period more.
  bool redundancy = false;
  /// The shared key (net/auth.hpp); required unless the server is on loopback.
  std::optional<Key> key;
  /// The hand to send: the sender thread samples it at each send time with `sampling`.
  const PoseHistory* poses = nullptr;
  PoseSamplingConfig sampling;                 // Predict: the hand at the send time itself
  /// Start the sender thread at connect() (else the owner calls sendPoseAt, as tests do).
  bool pacePoses = true;
  const Clock* clock = nullptr;                // null: SteadyClock
  std::int64_t connectTimeout_ns = 2'000'000'000;
  std::int64_t keepAlive_ns = 200'000'000;     // a keep-alive exchange (round-trip time) this often
  std::int64_t timeout_ns = 1'000'000'000;     // server silence that counts as disconnected
  /// After the server ends the session or falls silent, keep asking (a hello every
  /// reconnectInterval_ns) and resume when a server with the same stream format accepts.
  bool reconnect = false;
  std::int64_t reconnectInterval_ns = 500'000'000;
  Impairment impairment;                       // on what the client receives
  int realtimePriority = 0;                    // > 0: network and sender threads real-time at this priority if allowed
  JitterConfig jitter;                         // period_ns is set from the session
  /// Where the played-out frames go: the realtime sinks' ports (the network thread is their producer).
  haptics::FrameFanout outputs;
  std::size_t latencyCapacity = 1 << 18;       // latency samples kept
};

/// Counters; a snapshot is safe from any thread.
struct ClientStats {
  std::uint64_t posesSent = 0;
  std::uint64_t poseBytes = 0;       // pose bodies of the poses sent (the rest is framing: header, tag)
  std::uint64_t framesReceived = 0;
  std::uint64_t framesPlayed = 0;
  std::uint64_t framesConcealed = 0;
  std::uint64_t decodeFailures = 0;  // tactile blocks whose codec data did not decode
  std::uint64_t rejected = 0;        // datagrams the decoder refused (any reason, forged ones too)
  std::uint64_t strangerPackets = 0;
  std::uint64_t keepAlives = 0;
  std::uint64_t videoFragments = 0;
  std::uint64_t reconnects = 0;      // sessions resumed after a disconnection
  VideoStats video;                  // frames completed / abandoned, fragments rejected
  std::int64_t rtt_ns = 0;           // newest keep-alive round trip (sent every keepAlive_ns, poses or not)
  bool realtime = false;             // the network thread got real-time priority (SCHED_FIFO or RealtimeKit)
  JitterStats jitter;
  // The clock time the playout has run up to: every frame due by then has played. With a manual
  // clock, waiting for it before moving time on makes each frame play at its due time.
  std::int64_t playedThrough_ns = 0;
  bool connected = false;
  bool serverSaidBye = false;
  std::uint64_t bytesSent = 0, bytesReceived = 0;  // datagram bytes (without IP/UDP)
  std::uint64_t datagramsSent = 0, datagramsReceived = 0;
  std::uint64_t datagramsDropped = 0;  // by the impairment layer (ClientConfig::impairment)
};

/// The client: connect/disconnect on the owner thread; it runs its own threads.
class Client {
 public:
  explicit Client(ClientConfig config);
  ~Client();
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  /// Handshake on the calling thread, then starts the network thread (and the sender). Throws
  /// vt::Error with the server's reason when refused, or when nothing answers within
  /// connectTimeout_ns.
  void connect();
  /// Samples the pose history at t_ns plus the hand lead and sends that hand, stamped with its
  /// time, as the next pose (what the sender thread does every period). False when not
  /// connected or there is no hand yet. One thread at a time: the sender thread, or the owner
  /// when pacePoses is off.
  bool sendPoseAt(std::int64_t t_ns) noexcept;
  /// How far past the send time the hand is sampled (negative: before it): the frame made from
  /// it is felt that much later than it was sent, so the lead is the stream's delay (round trip,
  /// playout, the felt outputs) less the display's lag (docs/tactile-rendering.md, "Time").
  /// Slewed in (vt/core/time_alignment.hpp). Any thread.
  void setHandLead(std::int64_t lead_ns) noexcept { m_handLeadTarget_ns.store(lead_ns, std::memory_order_relaxed); }
  /// The lead the poses are sent with now (while a new one is slewed in, not yet it). Any thread.
  std::int64_t handLead_ns() const noexcept { return m_handLead.lead_ns(); }
  /// Says bye, stops the threads after a final silent frame to the sinks. Idempotent.
  void disconnect() noexcept;

  /// The session the server granted (valid after connect(); after a reconnection its id and
  /// codec are the new session's). Any thread.
  Accept session() const noexcept;
  ClientStats stats() const;
  /// Per-reason decoder rejections. Any thread.
  const RejectCounters& rejects() const noexcept { return m_rejects; }
  /// Latency samples (ns) of frames played so far, in play order. Call after disconnect(),
  /// or accept that the newest samples may be missing.
  std::vector<std::int64_t> latencies() const;
  Endpoint endpoint() const noexcept { return m_transport.localEndpoint(); }
  /// The newest complete video frame (JPEG), when wantVideo was set. Any thread.
  const LatestVideoFrame& video() const noexcept { return m_latestVideo; }

 private:
  struct SentPose {  // one slot of the pose-time table: which pose of which session, sent when, of when
    std::atomic<std::uint64_t> key{0};
    std::atomic<std::int64_t> t_ns{0};       // sent
    std::atomic<std::int64_t> hand_t_ns{0};  // the time of the hand it carried
  };
  static constexpr std::size_t kSentPoses = 1024;

  void run() noexcept;
  void sendLoop() noexcept;
  void handleHandshake(std::span<const std::uint8_t> bytes, std::int64_t now_ns) noexcept;
  void handleStream(std::span<const std::uint8_t> bytes, std::int64_t now_ns) noexcept;
  void playTactile(const Tactile& tactile, std::int64_t now_ns) noexcept;
  /// Takes a session the server granted (first connect or reconnection); false (with the
  /// reason in `why`) when its format or codec is not one this client can play.
  bool resume(const Accept& accept, const Packet& packet, std::int64_t now_ns, const char*& why) noexcept;
  /// The decoders of every offered codec for the stream format of `accept`; throws vt::Error
  /// when this client cannot decode that format. Owner thread (connect).
  void makeDecoders(const Accept& accept);
  void emit(const haptics::ActuatorFrame& frame) noexcept;
  bool sendHello() noexcept;
  /// Sends a stream datagram; its size (0 = not sent), and the body's in `body` when given.
  std::size_t sendStream(const Message& message, std::size_t* body = nullptr) noexcept;
  bool sendBytes(std::span<const std::uint8_t> bytes) noexcept;
  /// When pose `sequence` of this session was sent and the time of the hand it carried (0, 0: unknown).
  std::pair<std::int64_t, std::int64_t> poseTimes(std::uint64_t sequence) const noexcept;
  std::int64_t now() const noexcept { return m_clock.now_ns(); }

  ClientConfig m_config;
  const Clock& m_clock;
  Transport m_transport;
  RejectCounters m_rejects;
  Hello m_hello;
  Accept m_accept;  // the stream format; sessionId and codec live in the atomics below
  std::atomic<std::uint32_t> m_sessionId{0};
  std::atomic<std::uint8_t> m_codecId{0};
  // One decoder per offer, made at the first accept for its stream format: a reconnection (same
  // format) may pick another codec without allocating.
  std::vector<std::unique_ptr<haptics::BlockDecoder>> m_decoders;
  haptics::BlockDecoder* m_decoder = nullptr;  // the session's, network thread
  std::array<haptics::ActuatorFrame, kMaxFramesPerBlock> m_blockFrames{};  // one decoded block
  std::array<std::uint16_t, haptics::kMaxActuators> m_frequency_hz{};  // the newest the server sent
  // The session as both threads encode/decode it; keys alternate between two slots so the
  // sender's copy of the context stays valid across one reconnection.
  LatestValue<StreamContext> m_context;
  std::array<SessionKeys, 2> m_keys{};
  StreamContext m_receive;  // network thread: the context with the newest received sequences
  ReplayWindow m_replay;
  // Hello nonces recently sent (keyed): an accept is bound to one of them.
  std::array<std::array<std::uint8_t, kNonceSize>, 8> m_helloNonces{};
  std::atomic<int> m_helloCount{0};
  std::unique_ptr<JitterBuffer> m_jitter;
  std::unique_ptr<VideoReassembler> m_videoReassembler;  // only when wantVideo
  LatestVideoFrame m_latestVideo;
  std::vector<std::int64_t> m_latencies;  // sized at construction, filled by the network thread
  std::atomic<std::size_t> m_latencyCount{0};
  std::array<SentPose, kSentPoses> m_sentPoses;
  std::uint64_t m_poseSequence = 0;   // sender: poses of the current session
  std::uint32_t m_poseSession = 0;    // sender: the session they belong to
  LeadSlew m_handLead;                // sender: the hand's time - the send time
  std::atomic<std::int64_t> m_handLeadTarget_ns{0};

  std::atomic<std::uint64_t> m_sendSequence{0};  // datagrams of the current session
  std::atomic<std::int64_t> m_lastHeard_ns{0};
  std::int64_t m_nextKeepAlive_ns = 0;  // network thread
  std::atomic<std::uint64_t> m_posesSent{0}, m_poseBytes{0}, m_framesReceived{0}, m_decodeFailures{0}, m_strangers{0},
      m_keepAlives{0}, m_video{0}, m_reconnects{0}, m_bytesSent{0}, m_bytesReceived{0}, m_datagramsSent{0},
      m_datagramsReceived{0};
  std::int64_t m_nextHello_ns = 0;  // network thread, while reconnecting
  // The server's latest challenge cookie, sent in every hello (all zero: none). Dropped when a
  // hello carrying it went unanswered (the server restarted, or the cookie expired).
  Cookie m_cookie{};
  bool m_helloAnswered = true;
  bool m_resumeRefused = false;     // network thread: a server's accept was not taken (logged once)
  std::atomic<std::int64_t> m_rtt_ns{0};
  std::atomic<std::int64_t> m_playedThrough_ns{0};
  std::atomic<bool> m_connected{false};
  std::atomic<bool> m_realtime{false};
  std::atomic<bool> m_bye{false};
  std::atomic<bool> m_running{false};
  LatestValue<JitterStats> m_jitterStats;  // published by the network thread
  std::thread m_thread;
  std::thread m_sender;
};

/// The joint radii a client announces when it has no pose yet (the kinematic hand model's).
std::array<float, kHandJointCount> defaultHandRadii() noexcept;

}  // namespace vt::net
