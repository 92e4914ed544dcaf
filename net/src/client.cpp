#include "vt/net/client.hpp"

#include <algorithm>

#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/realtime.hpp"
#include "vt/net/tactile_stream.hpp"

namespace vt::net {

namespace {

constexpr std::int64_t kHelloRetry_ns = 100'000'000;
constexpr std::int64_t kMaxWait_ns = 5'000'000;  // network thread wakes at least this often

std::int64_t now() noexcept { return SteadyClock::instance().now_ns(); }

}  // namespace

Client::Client(ClientConfig config) : m_config(std::move(config)), m_transport(m_config.bind, m_config.impairment) {
  if (m_config.codecs.empty() || m_config.codecs.size() > std::size_t(kMaxCodecOffers))
    fail("client: offer 1..", kMaxCodecOffers, " codecs");
  if (m_config.quality < 0 || m_config.quality > 100) fail("client: quality ", m_config.quality, " not in 0..100");
  m_latencies.resize(m_config.latencyCapacity);
  if (m_config.wantVideo) m_videoReassembler = std::make_unique<VideoReassembler>();
  m_hello.codecCount = std::uint8_t(m_config.codecs.size());
  for (std::size_t i = 0; i < m_config.codecs.size(); ++i) m_hello.codecs[i] = std::uint8_t(m_config.codecs[i]);
  m_hello.quality = std::uint8_t(m_config.quality);
  m_hello.sceneDigest = m_config.sceneDigest;
  m_hello.flags = m_config.wantVideo ? kHelloWantsVideo : 0;
  for (auto id : m_config.codecs) m_codecs.push_back(haptics::makeCodec(id, m_config.quality));
}

Accept Client::session() const noexcept {
  Accept accept = m_accept;
  accept.sessionId = m_sessionId.load(std::memory_order_relaxed);
  accept.codec = m_codecId.load(std::memory_order_relaxed);
  return accept;
}

bool Client::resume(const Accept& accept, std::int64_t now_ns, const char*& why) noexcept {
  const haptics::TactileCodec* codec = nullptr;
  for (const auto& c : m_codecs)
    if (std::uint8_t(c->id()) == accept.codec) codec = c.get();
  if (!codec) {
    why = "chose a codec that was not offered";
    return false;
  }
  if (accept.quality != m_config.quality) {
    why = "changed the codec quality";
    return false;
  }
  // A reconnection must keep the stream format the jitter buffer and the sinks were set up for.
  if (m_jitter && (accept.actuatorCount != m_accept.actuatorCount || accept.blockLength != m_accept.blockLength ||
                   accept.sampleRate_hz != m_accept.sampleRate_hz)) {
    why = "offers another stream format (actuators, block length or sample rate)";
    return false;
  }
  m_codec = codec;
  m_sessionId.store(accept.sessionId, std::memory_order_relaxed);
  m_codecId.store(accept.codec, std::memory_order_relaxed);
  m_lastHeard_ns.store(now_ns);
  m_bye.store(false);
  m_connected.store(true, std::memory_order_release);
  return true;
}

Client::~Client() { disconnect(); }

bool Client::send(const Message& message) noexcept {
  std::array<std::uint8_t, kMaxDatagram> bytes{};
  const std::int64_t t = now();
  const std::size_t size = encodePacket({m_sendSequence.fetch_add(1) + 1, t, message}, bytes);
  if (!size || !m_transport.send(std::span(bytes.data(), size), m_config.server)) return false;
  m_lastSent_ns.store(t, std::memory_order_relaxed);
  return true;
}

void Client::connect() {
  if (m_running.load()) return;
  std::array<std::uint8_t, kMaxDatagram + 1> buffer{};
  Packet packet;
  const std::int64_t giveUp = now() + m_config.connectTimeout_ns;
  while (now() < giveUp) {
    send(m_hello);
    const std::int64_t retry = std::min(giveUp, now() + kHelloRetry_ns);
    for (;;) {
      Endpoint from;
      const std::size_t size = m_transport.receive(buffer, from, retry);
      if (size == 0) break;
      if (!(from == m_config.server)) continue;
      if (decodePacket(std::span(buffer.data(), std::min(size, buffer.size())), packet, &m_rejects) != DecodeStatus::Ok)
        continue;
      if (const auto* refuse = std::get_if<Refuse>(&packet.message))
        fail("server ", toString(m_config.server), " refused the session: ", refuse->message());
      const auto* accept = std::get_if<Accept>(&packet.message);
      if (!accept) continue;
      const char* why = "";
      if (!resume(*accept, now(), why)) fail("server ", toString(m_config.server), " ", why);
      m_accept = *accept;
      JitterConfig jitter = m_config.jitter;
      jitter.period_ns = std::int64_t(accept->blockLength) * 1'000'000'000 / std::int64_t(accept->sampleRate_hz);
      m_jitter = std::make_unique<JitterBuffer>(jitter);
      m_running.store(true);
      m_thread = std::thread([this] { run(); });
      log::info("client: session ", accept->sessionId, " with ", toString(m_config.server), " codec ",
                haptics::codecName(haptics::CodecId(accept->codec)), ", ", int(accept->actuatorCount), " actuators x ",
                accept->blockLength, " samples at ", accept->sampleRate_hz, " Hz");
      return;
    }
  }
  fail("no answer from server ", toString(m_config.server), " within ", m_config.connectTimeout_ns / 1'000'000, " ms");
}

bool Client::sendPose(const HandPose& pose) noexcept {
  if (!m_connected.load(std::memory_order_acquire)) return false;
  if (!send(pose)) return false;
  m_posesSent.fetch_add(1, std::memory_order_relaxed);
  return true;
}

void Client::disconnect() noexcept {
  if (!m_running.exchange(false)) return;
  if (m_thread.joinable()) m_thread.join();
  if (m_connected.exchange(false)) send(Bye{ByeReason::Normal});
  // Whatever was playing stops here.
  emit(haptics::ActuatorFrame::silent(m_accept.actuatorCount, now()));
}

void Client::emit(const haptics::ActuatorFrame& frame) noexcept {
  if (m_config.framesOut) m_config.framesOut->push(frame);
  if (m_config.latestOut) m_config.latestOut->publish(frame);
}

void Client::handle(const Packet& packet, std::int64_t now_ns) noexcept {
  m_lastHeard_ns.store(now_ns, std::memory_order_relaxed);
  if (const auto* tactile = std::get_if<Tactile>(&packet.message)) {
    m_framesReceived.fetch_add(1, std::memory_order_relaxed);
    haptics::ActuatorFrame frame;
    if (!unpackFrame(*tactile, *m_codec, frame)) {
      m_decodeFailures.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    m_jitter->push(frame, now_ns);
  } else if (const auto* keepAlive = std::get_if<KeepAlive>(&packet.message)) {
    m_keepAlives.fetch_add(1, std::memory_order_relaxed);
    if (keepAlive->echo_t_ns > 0) m_rtt_ns.store(now_ns - keepAlive->echo_t_ns, std::memory_order_relaxed);
  } else if (const auto* video = std::get_if<Video>(&packet.message)) {
    m_video.fetch_add(1, std::memory_order_relaxed);
    // Buffers are swapped, not copied: the network thread only memcpys fragments.
    if (m_videoReassembler && m_videoReassembler->push(*video)) m_latestVideo.publish(m_videoReassembler->completed());
  } else if (std::holds_alternative<Bye>(packet.message)) {
    log::warn("client: server ", toString(m_config.server), " ended the session",
              m_config.reconnect ? "; reconnecting" : "");
    m_bye.store(true);
    m_connected.store(false);
  } else if (const auto* accept = std::get_if<Accept>(&packet.message)) {
    if (m_connected.load(std::memory_order_relaxed) || !m_config.reconnect) return;  // a duplicate accept
    const char* why = "";
    if (resume(*accept, now_ns, why)) {
      m_reconnects.fetch_add(1, std::memory_order_relaxed);
      m_resumeRefused = false;
      log::info("client: resumed with session ", accept->sessionId, " of ", toString(m_config.server));
    } else if (!m_resumeRefused) {  // once, not at every retry
      m_resumeRefused = true;
      log::warn("client: server ", toString(m_config.server), " ", why, "; not resuming");
    }
  }
}

void Client::run() noexcept {
  // Playout happens on this thread: its wake-up delay is part of the motion-to-vibration latency.
  if (m_config.realtimePriority > 0) m_realtime.store(requestRealtime("client network", m_config.realtimePriority).granted());
  std::array<std::uint8_t, kMaxDatagram + 1> buffer{};
  Packet packet;
  while (m_running.load(std::memory_order_acquire)) {
    const std::int64_t t0 = now();
    const std::int64_t wake = std::min(m_jitter->nextDue_ns(), t0 + kMaxWait_ns);
    Endpoint from;
    const std::size_t size = m_transport.receive(buffer, from, wake);
    std::int64_t t = now();
    if (size) {
      if (!(from == m_config.server)) {
        m_strangers.fetch_add(1, std::memory_order_relaxed);
      } else if (decodePacket(std::span(buffer.data(), std::min(size, buffer.size())), packet, &m_rejects) ==
                 DecodeStatus::Ok) {
        handle(packet, t);
      }
    }
    haptics::ActuatorFrame frame;
    bool concealed = false;
    while (m_jitter->pop(t, frame, concealed)) {
      emit(frame);
      if (!concealed) {
        t = now();
        const std::size_t i = m_latencyCount.load(std::memory_order_relaxed);
        if (i < m_latencies.size()) {
          m_latencies[i] = t - frame.pose_t_ns;
          m_latencyCount.store(i + 1, std::memory_order_release);
        }
      }
    }
    m_jitterStats.publish(m_jitter->stats());
    if (m_connected.load(std::memory_order_relaxed)) {
      if (t - m_lastSent_ns.load(std::memory_order_relaxed) > m_config.keepAlive_ns) send(KeepAlive{0});
      if (t - m_lastHeard_ns.load(std::memory_order_relaxed) > m_config.timeout_ns) {
        log::warn("client: server ", toString(m_config.server), " silent for ", m_config.timeout_ns / 1'000'000, " ms");
        m_connected.store(false);
      }
    } else if (m_config.reconnect && t >= m_nextHello_ns) {
      send(m_hello);
      m_nextHello_ns = t + m_config.reconnectInterval_ns;
    }
  }
}

ClientStats Client::stats() const {
  ClientStats s;
  s.posesSent = m_posesSent.load();
  s.framesReceived = m_framesReceived.load();
  s.decodeFailures = m_decodeFailures.load();
  s.rejected = m_rejects.total();
  s.strangerPackets = m_strangers.load();
  s.keepAlives = m_keepAlives.load();
  s.videoFragments = m_video.load();
  s.reconnects = m_reconnects.load();
  if (m_videoReassembler) s.video = m_videoReassembler->stats();
  s.rtt_ns = m_rtt_ns.load();
  s.realtime = m_realtime.load();
  m_jitterStats.read(s.jitter);
  s.framesPlayed = s.jitter.played;
  s.framesConcealed = s.jitter.concealed;
  s.connected = m_connected.load();
  s.serverSaidBye = m_bye.load();
  return s;
}

std::vector<std::int64_t> Client::latencies() const {
  const std::size_t n = m_latencyCount.load(std::memory_order_acquire);
  return {m_latencies.begin(), m_latencies.begin() + std::ptrdiff_t(n)};
}

}  // namespace vt::net
