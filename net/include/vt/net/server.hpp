#pragma once
// The tactile server: one client session at a time over UDP. It applies the newest pose and
// sends encoded actuator frames back. Rendering is injected: either a callable run once per
// new pose on the server thread (pose-driven: frame sequence = pose sequence, the lowest
// latency), or a haptic loop that reads `poseOut` and writes frames into `framesIn` on its
// own thread (loop-driven). Other clients are refused with a reason; a silent client times out.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "vt/core/latest_value.hpp"
#include "vt/core/spsc_ring.hpp"
#include "vt/haptics/actuator_frame.hpp"
#include "vt/haptics/codec/codec.hpp"
#include "vt/net/transport.hpp"
#include "vt/scene/hand.hpp"
#include "vt/scene/pose_history.hpp"

namespace vt::net {

/// Renders the frame for one pose (shape, waveform, levels). Called on the server thread.
using PoseRenderer = std::function<void(const HandPose& pose, haptics::ActuatorFrame& frame)>;

/// Server settings; bind defaults to loopback.
struct ServerConfig {
  Endpoint bind = {0x7F000001, 47800};
  /// Codecs the server agrees to, in its order of preference among the client's offers.
  std::vector<haptics::CodecId> codecs = {haptics::CodecId::Perceptual, haptics::CodecId::Pcm16,
                                          haptics::CodecId::RawFloat32};
  int actuatorCount = kFingerCount;
  int blockLength = haptics::kMaxBlockSamples;
  int sampleRate_hz = 8000;
  std::int64_t timeout_ns = 1'000'000'000;  // session ends after this much client silence
  Impairment impairment;                    // on what the server receives
  int realtimePriority = 0;                 // > 0: network thread real-time at this priority if allowed
  std::uint64_t sceneDigest = 0;            // vt::tactileDigest of the rendered scene (0 = unchecked)
  std::string sceneName = "its scene";      // named when a client with another scene is refused
  PoseRenderer renderer;                    // pose-driven mode
  PoseHistory* poseOut = nullptr;                     // received poses, for a haptic loop
  SpscRing<haptics::ActuatorFrame>* framesIn = nullptr;  // loop-driven mode: frames to send
};

/// Counters; a snapshot is safe from any thread.
struct ServerStats {
  std::uint64_t sessions = 0;
  std::uint64_t refused = 0;
  std::uint64_t timeouts = 0;
  std::uint64_t posesApplied = 0;
  std::uint64_t posesStale = 0;       // older than one already applied (reordered)
  std::uint64_t framesSent = 0;
  std::uint64_t encodeFailures = 0;
  std::uint64_t strangerPackets = 0;  // session traffic from a non-client address
  std::uint64_t rejected = 0;         // datagrams the decoder refused (all reasons)
  std::uint64_t videoFramesSent = 0;
  bool clientConnected = false;
  bool realtime = false;              // the network thread got real-time priority (SCHED_FIFO or RealtimeKit)
};

/// The server: construct and start/stop on the owner thread; it runs its own network thread.
class Server {
 public:
  /// Binds the socket (throws vt::Error naming the address). Does not start the thread.
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
  /// True while a client that asked for video (hello flag) is connected. Any thread.
  bool videoWanted() const noexcept { return m_videoTo.load(std::memory_order_acquire) != 0; }
  /// Any thread (a video thread): splits one JPEG frame into video datagrams and sends them to
  /// the client when videoWanted(). False when not sent (no such client, or the frame is empty
  /// or over kMaxVideoFrameBytes). Takes as long as ~25 sendto calls.
  bool sendVideo(std::span<const std::uint8_t> jpeg, int width, int height);
  /// Per-reason decoder rejections.
  const RejectCounters& rejects() const noexcept { return m_rejects; }

 private:
  void run() noexcept;
  void handle(const Packet& packet, const Endpoint& from, std::int64_t now_ns) noexcept;
  void handleHello(const Hello& hello, const Endpoint& from, std::int64_t now_ns) noexcept;
  void applyPose(const HandPose& pose, std::int64_t now_ns) noexcept;
  void sendFrame(const haptics::ActuatorFrame& frame) noexcept;
  void refuse(const Endpoint& to, RefuseReason reason, std::string_view text) noexcept;
  void closeSession() noexcept;                // frees the slot (either side ended it)
  void endSession(ByeReason reason) noexcept;  // closes and tells the client why
  void send(const Message& message, const Endpoint& to) noexcept;
  void setVideoClient(bool wanted, const Endpoint& client) noexcept;

  ServerConfig m_config;
  Transport m_transport;
  RejectCounters m_rejects;
  std::string m_versionText, m_sceneMismatchText;

  // Network-thread state.
  bool m_active = false;
  Endpoint m_client;
  Accept m_accept;
  std::unique_ptr<haptics::TactileCodec> m_codec;  // the session's negotiated codec
  std::int64_t m_lastHeard_ns = 0;
  std::uint64_t m_lastPoseSequence = 0;
  bool m_havePose = false;
  std::atomic<std::uint32_t> m_sendSequence{0};  // the video thread sends too
  std::uint32_t m_nextSessionId = 1;

  std::atomic<std::uint64_t> m_sessions{0}, m_refused{0}, m_timeouts{0}, m_posesApplied{0}, m_posesStale{0},
      m_framesSent{0}, m_encodeFailures{0}, m_strangers{0};
  // The video client's address, port and a valid bit in one word, so any thread reads it whole.
  std::atomic<std::uint64_t> m_videoTo{0};
  std::atomic<std::uint32_t> m_videoFrameId{0};
  std::atomic<std::uint64_t> m_videoFramesSent{0};
  std::atomic<bool> m_connected{false};
  std::atomic<bool> m_realtime{false};
  std::atomic<bool> m_running{false};
  std::thread m_thread;
};

}  // namespace vt::net
