#include "vt/net/server.hpp"

#include <algorithm>
#include <cstring>

#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/realtime.hpp"
#include "vt/net/tactile_stream.hpp"
#include "vt/net/video_stream.hpp"

namespace vt::net {

namespace {

constexpr std::int64_t kIdleWait_ns = 20'000'000;    // receive timeout with nothing else to do
constexpr std::int64_t kLoopPoll_ns = 500'000;       // loop-driven mode: how often frames are drained

std::int64_t now() noexcept { return SteadyClock::instance().now_ns(); }

}  // namespace

Server::Server(ServerConfig config) : m_config(std::move(config)), m_transport(m_config.bind, m_config.impairment) {
  if (m_config.codecs.empty()) fail("server: no codecs allowed");
  for (auto id : m_config.codecs)
    if (!haptics::isKnownCodec(std::uint8_t(id))) fail("server: unknown codec id ", int(id));
  if (m_config.actuatorCount < 1 || m_config.actuatorCount > haptics::kMaxActuators)
    fail("server: actuatorCount ", m_config.actuatorCount, " not in 1..", haptics::kMaxActuators);
  if (m_config.blockLength < 1 || m_config.blockLength > haptics::kMaxBlockSamples)
    fail("server: blockLength ", m_config.blockLength, " not in 1..", haptics::kMaxBlockSamples);
  if (m_config.timeout_ns <= 0 || m_config.timeout_ns / 1'000'000 > 65535) fail("server: timeout must be 1..65535 ms");
  if (!m_config.renderer && !m_config.framesIn) fail("server: needs a renderer or a frame ring from a haptic loop");
  // Refusal texts are built here so the network thread never allocates them.
  m_versionText = str("unsupported protocol version (server speaks ", int(kProtocolVersion), ")");
  m_sceneMismatchText = str("scene mismatch: the server renders ", m_config.sceneName.substr(0, 60), " (load the same scene)");
}

Server::~Server() { stop(); }

void Server::start() {
  if (m_running.exchange(true)) return;
  m_thread = std::thread([this] { run(); });
  log::info("server: listening on ", toString(endpoint()));
}

void Server::stop() noexcept {
  if (!m_running.exchange(false)) return;
  if (m_thread.joinable()) m_thread.join();
  if (m_active) endSession(ByeReason::Shutdown);
}

ServerStats Server::stats() const noexcept {
  return {m_sessions.load(),     m_refused.load(),    m_timeouts.load(),       m_posesApplied.load(),
          m_posesStale.load(),   m_framesSent.load(), m_encodeFailures.load(), m_strangers.load(),
          m_rejects.total(),     m_videoFramesSent.load(), m_connected.load(), m_realtime.load()};
}

void Server::send(const Message& message, const Endpoint& to) noexcept {
  std::array<std::uint8_t, kMaxDatagram> bytes{};
  const std::size_t size = encodePacket({++m_sendSequence, now(), message}, bytes);
  if (size) m_transport.send(std::span(bytes.data(), size), to);
}

void Server::setVideoClient(bool wanted, const Endpoint& client) noexcept {
  const std::uint64_t word = std::uint64_t(1) << 48 | std::uint64_t(client.port) << 32 | client.address;
  m_videoTo.store(wanted ? word : 0, std::memory_order_release);
}

bool Server::sendVideo(std::span<const std::uint8_t> jpeg, int width, int height) {
  const std::uint64_t word = m_videoTo.load(std::memory_order_acquire);
  if (word == 0) return false;
  const Endpoint to{std::uint32_t(word), std::uint16_t(word >> 32)};
  const std::uint32_t frameId = m_videoFrameId.fetch_add(1, std::memory_order_relaxed) + 1;
  if (!fragmentVideoFrame(jpeg, frameId, width, height, [&](const Video& fragment) { send(fragment, to); })) return false;
  m_videoFramesSent.fetch_add(1, std::memory_order_relaxed);
  return true;
}

void Server::refuse(const Endpoint& to, RefuseReason reason, std::string_view text) noexcept {
  Refuse message;
  message.reason = reason;
  message.textLength = std::uint8_t(std::min(text.size(), kMaxRefuseText));
  std::memcpy(message.text.data(), text.data(), message.textLength);
  m_refused.fetch_add(1, std::memory_order_relaxed);  // before the reply: whoever reads it sees the count
  send(message, to);
}

void Server::closeSession() noexcept {
  m_active = false;
  m_codec.reset();
  m_connected.store(false);
  setVideoClient(false, {});
}

void Server::endSession(ByeReason reason) noexcept {
  // State and counters first: whoever reacts to the bye sees the session already over.
  closeSession();
  if (reason == ByeReason::Timeout) m_timeouts.fetch_add(1, std::memory_order_relaxed);
  send(Bye{reason}, m_client);
}

void Server::handleHello(const Hello& hello, const Endpoint& from, std::int64_t now_ns) noexcept {
  if (m_active && !(from == m_client)) {
    refuse(from, RefuseReason::Busy, "busy: another client is connected");
    return;
  }
  if (hello.sceneDigest != 0 && m_config.sceneDigest != 0 && hello.sceneDigest != m_config.sceneDigest) {
    // What the client shows would not be what the server lets it touch.
    refuse(from, RefuseReason::SceneMismatch, m_sceneMismatchText);
    return;
  }
  if (m_active) {  // the same client again (its accept was lost): answer the same way
    send(m_accept, from);
    m_lastHeard_ns = now_ns;
    return;
  }
  for (auto wanted : m_config.codecs) {
    for (int i = 0; i < hello.codecCount; ++i) {
      if (hello.codecs[std::size_t(i)] != std::uint8_t(wanted)) continue;
      try {
        m_codec = haptics::makeCodec(wanted, hello.quality);
      } catch (const std::exception&) {  // allocation failure: refuse rather than die
        refuse(from, RefuseReason::BadRequest, "server could not create the codec");
        return;
      }
      m_accept = {m_nextSessionId++,
                  std::uint8_t(wanted),
                  hello.quality,
                  std::uint8_t(m_config.actuatorCount),
                  std::uint16_t(m_config.blockLength),
                  std::uint32_t(m_config.sampleRate_hz),
                  std::uint16_t(m_config.timeout_ns / 1'000'000),
                  m_config.sceneDigest};
      m_active = true;
      m_client = from;
      m_lastHeard_ns = now_ns;
      m_havePose = false;
      m_connected.store(true);
      setVideoClient((hello.flags & kHelloWantsVideo) != 0, from);
      m_sessions.fetch_add(1, std::memory_order_relaxed);
      send(m_accept, from);
      log::info("server: session ", m_accept.sessionId, " with ", toString(from), " codec ",
                haptics::codecName(wanted), " quality ", int(hello.quality));
      return;
    }
  }
  refuse(from, RefuseReason::NoCommonCodec, "no common codec");
}

void Server::applyPose(const HandPose& pose, std::int64_t now_ns) noexcept {
  if (m_havePose && pose.sequence <= m_lastPoseSequence) {
    m_posesStale.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  m_havePose = true;
  m_lastPoseSequence = pose.sequence;
  m_posesApplied.fetch_add(1, std::memory_order_relaxed);
  if (m_config.poseOut) m_config.poseOut->publish(pose);
  if (!m_config.renderer) return;
  haptics::ActuatorFrame frame;
  m_config.renderer(pose, frame);
  frame.sequence = pose.sequence;  // one frame per pose: the client's pose clock paces playout
  frame.pose_t_ns = pose.t_ns;
  frame.t_ns = now_ns;
  sendFrame(frame);
}

void Server::sendFrame(const haptics::ActuatorFrame& frame) noexcept {
  Tactile message;
  if (!m_codec || !packFrame(frame, *m_codec, message)) {
    m_encodeFailures.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  m_framesSent.fetch_add(1, std::memory_order_relaxed);
  send(message, m_client);
}

void Server::handle(const Packet& packet, const Endpoint& from, std::int64_t now_ns) noexcept {
  if (const auto* hello = std::get_if<Hello>(&packet.message)) {
    handleHello(*hello, from, now_ns);
    return;
  }
  if (!m_active || !(from == m_client)) {
    m_strangers.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  m_lastHeard_ns = now_ns;
  if (const auto* pose = std::get_if<HandPose>(&packet.message)) {
    applyPose(*pose, now_ns);
  } else if (const auto* keepAlive = std::get_if<KeepAlive>(&packet.message)) {
    if (keepAlive->echo_t_ns == 0) send(KeepAlive{std::max<std::int64_t>(packet.sender_t_ns, 1)}, from);
  } else if (std::holds_alternative<Bye>(packet.message)) {
    log::info("server: client ", toString(from), " said bye");
    closeSession();
  }
}

void Server::run() noexcept {
  // Pose-driven rendering runs on this thread: its wake-up delay is part of the latency.
  if (m_config.realtimePriority > 0) m_realtime.store(requestRealtime("server network", m_config.realtimePriority).granted());
  std::array<std::uint8_t, kMaxDatagram + 1> buffer{};
  Packet packet;
  while (m_running.load(std::memory_order_acquire)) {
    const std::int64_t wait = m_config.framesIn ? kLoopPoll_ns : kIdleWait_ns;
    Endpoint from;
    const std::size_t size = m_transport.receive(buffer, from, now() + wait);
    const std::int64_t t = now();
    if (size) {
      const DecodeStatus status = decodePacket(std::span(buffer.data(), std::min(size, buffer.size())), packet, &m_rejects);
      if (status == DecodeStatus::Ok) {
        handle(packet, from, t);
      } else if (status == DecodeStatus::UnknownVersion) {
        refuse(from, RefuseReason::Version, m_versionText);
      }
    }
    if (m_config.framesIn) {
      haptics::ActuatorFrame frame;
      while (m_config.framesIn->pop(frame))
        if (m_active && m_havePose) sendFrame(frame);
    }
    if (m_active && t - m_lastHeard_ns > m_config.timeout_ns) {
      log::warn("server: client ", toString(m_client), " silent for ", m_config.timeout_ns / 1'000'000,
                " ms: session ", m_accept.sessionId, " ended");
      endSession(ByeReason::Timeout);
    }
  }
}

}  // namespace vt::net
