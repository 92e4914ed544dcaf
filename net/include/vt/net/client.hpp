#pragma once
// The tactile client: connects to a server (hello with codec offers), sends timestamped,
// sequence-numbered hand poses from the input thread, and on its own network thread receives
// tactile frames, decodes them, plays them out through a jitter buffer with concealment and
// pushes every played frame to its sinks (an SpscRing and/or a LatestValue mailbox). It
// measures motion-to-vibration latency: pose timestamp -> the frame built from that pose
// leaving the jitter buffer for the sinks (both on this machine's SteadyClock).
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "vt/core/latest_value.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/codec/codec.hpp"
#include "vt/net/jitter_buffer.hpp"
#include "vt/net/transport.hpp"
#include "vt/net/video_stream.hpp"

namespace vt::net {

/// Client settings; the server address defaults to loopback.
struct ClientConfig {
  Endpoint server = {0x7F000001, 47800};
  Endpoint bind = {0x7F000001, 0};
  std::vector<haptics::CodecId> codecs = {haptics::CodecId::Perceptual, haptics::CodecId::Pcm16,
                                          haptics::CodecId::RawFloat32};
  int quality = 50;
  std::uint64_t sceneDigest = 0;               // vt::tactileDigest of the scene shown here (0 = none)
  bool wantVideo = false;                      // ask for the server's video stream (see video())
  std::int64_t connectTimeout_ns = 2'000'000'000;
  std::int64_t keepAlive_ns = 200'000'000;     // sent when no pose went out for this long
  std::int64_t timeout_ns = 1'000'000'000;     // server silence that counts as disconnected
  /// After the server ends the session or falls silent, keep asking (a hello every
  /// reconnectInterval_ns) and resume when a server with the same stream format accepts.
  bool reconnect = false;
  std::int64_t reconnectInterval_ns = 500'000'000;
  Impairment impairment;                       // on what the client receives
  int realtimePriority = 0;                    // > 0: network thread real-time at this priority if allowed
  JitterConfig jitter;                         // period_ns is set from the session
  SpscRing<haptics::ActuatorFrame>* framesOut = nullptr;
  LatestValue<haptics::ActuatorFrame>* latestOut = nullptr;
  std::size_t latencyCapacity = 1 << 18;       // latency samples kept
};

/// Counters; a snapshot is safe from any thread.
struct ClientStats {
  std::uint64_t posesSent = 0;
  std::uint64_t framesReceived = 0;
  std::uint64_t framesPlayed = 0;
  std::uint64_t framesConcealed = 0;
  std::uint64_t decodeFailures = 0;  // tactile messages whose codec data did not decode
  std::uint64_t rejected = 0;        // datagrams the decoder refused
  std::uint64_t strangerPackets = 0;
  std::uint64_t keepAlives = 0;
  std::uint64_t videoFragments = 0;
  std::uint64_t reconnects = 0;      // sessions resumed after a disconnection
  VideoStats video;                  // frames completed / abandoned, fragments rejected
  std::int64_t rtt_ns = 0;           // last keep-alive round trip
  bool realtime = false;             // the network thread got real-time priority (SCHED_FIFO or RealtimeKit)
  JitterStats jitter;
  bool connected = false;
  bool serverSaidBye = false;
};

/// The client: connect/disconnect on the owner thread, sendPose on the input thread.
class Client {
 public:
  explicit Client(ClientConfig config);
  ~Client();
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  /// Handshake on the calling thread, then starts the network thread. Throws vt::Error with
  /// the server's reason when refused, or when nothing answers within connectTimeout_ns.
  void connect();
  /// Input thread: sends a pose now. Its t_ns and sequence are sent as given (the sequence
  /// numbers consecutive poses; t_ns is this machine's SteadyClock). False if not connected.
  bool sendPose(const HandPose& pose) noexcept;
  /// Says bye, stops the network thread after a final silent frame to the sinks. Idempotent.
  void disconnect() noexcept;

  /// The session the server granted (valid after connect(); after a reconnection its id and
  /// codec are the new session's). Any thread.
  Accept session() const noexcept;
  ClientStats stats() const;
  /// Latency samples (ns) of frames played so far, in play order. Call after disconnect(),
  /// or accept that the newest samples may be missing.
  std::vector<std::int64_t> latencies() const;
  Endpoint endpoint() const noexcept { return m_transport.localEndpoint(); }
  /// The newest complete video frame (JPEG), when wantVideo was set. Any thread.
  const LatestVideoFrame& video() const noexcept { return m_latestVideo; }

 private:
  void run() noexcept;
  void handle(const Packet& packet, std::int64_t now_ns) noexcept;
  /// Takes a session the server granted (first connect or reconnection); false (with the
  /// reason in `why`) when its format or codec is not one this client can play.
  bool resume(const Accept& accept, std::int64_t now_ns, const char*& why) noexcept;
  void emit(const haptics::ActuatorFrame& frame) noexcept;
  bool send(const Message& message) noexcept;

  ClientConfig m_config;
  Transport m_transport;
  RejectCounters m_rejects;
  Hello m_hello;
  Accept m_accept;  // the stream format; sessionId and codec live in the atomics below
  std::atomic<std::uint32_t> m_sessionId{0};
  std::atomic<std::uint8_t> m_codecId{0};
  // One codec per offer, made up front: a reconnection may pick another without allocating.
  std::vector<std::unique_ptr<haptics::TactileCodec>> m_codecs;
  const haptics::TactileCodec* m_codec = nullptr;  // the session's, network thread
  std::unique_ptr<JitterBuffer> m_jitter;
  std::unique_ptr<VideoReassembler> m_videoReassembler;  // only when wantVideo
  LatestVideoFrame m_latestVideo;
  std::vector<std::int64_t> m_latencies;  // sized at construction, filled by the network thread
  std::atomic<std::size_t> m_latencyCount{0};

  std::atomic<std::uint32_t> m_sendSequence{0};
  std::atomic<std::int64_t> m_lastSent_ns{0};
  std::atomic<std::int64_t> m_lastHeard_ns{0};
  std::atomic<std::uint64_t> m_posesSent{0}, m_framesReceived{0}, m_decodeFailures{0}, m_strangers{0},
      m_keepAlives{0}, m_video{0}, m_reconnects{0};
  std::int64_t m_nextHello_ns = 0;  // network thread, while reconnecting
  bool m_resumeRefused = false;     // network thread: a server's accept was not taken (logged once)
  std::atomic<std::int64_t> m_rtt_ns{0};
  std::atomic<bool> m_connected{false};
  std::atomic<bool> m_realtime{false};
  std::atomic<bool> m_bye{false};
  std::atomic<bool> m_running{false};
  LatestValue<JitterStats> m_jitterStats;  // published by the network thread
  std::thread m_thread;
};

}  // namespace vt::net
