#include "vt/net/client.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/realtime.hpp"
#include "vt/net/tactile_stream.hpp"
#include "pose_wire.hpp"

namespace vt::net {

namespace {

constexpr std::int64_t kHelloRetry_ns = 100'000'000;
constexpr std::int64_t kMaxWait_ns = 5'000'000;  // network thread wakes at least this often (real time)

std::int64_t periodOf(const Accept& accept) noexcept {
  return std::int64_t(accept.blockLength) * 1'000'000'000 / std::int64_t(std::max<std::uint32_t>(accept.sampleRate_hz, 1));
}

}  // namespace

std::array<float, kHandJointCount> defaultHandRadii() noexcept {
  return poseHand(glm::mat4(1.0f), FingerCurls{}).radius_m;
}

Client::Client(ClientConfig config)
    : m_config(std::move(config)),
      m_clock(m_config.clock ? *m_config.clock : SteadyClock::instance()),
      m_transport(m_config.bind.value_or(localEndpointFor(m_config.server)), m_config.impairment) {
  if (m_config.codecs.empty() || m_config.codecs.size() > std::size_t(kMaxCodecOffers))
    fail("client: offer 1..", kMaxCodecOffers, " codecs");
  if (m_config.quality < 0 || m_config.quality > 100) fail("client: quality ", m_config.quality, " not in 0..100");
  if (std::find(haptics::kCodecBlockLengths_ms.begin(), haptics::kCodecBlockLengths_ms.end(), m_config.block_ms) ==
      haptics::kCodecBlockLengths_ms.end())
    fail("client: block length ", m_config.block_ms, " ms is not one of 4, 8, 16, 32, 64, 128");
  if (m_config.blocksPerDatagram < 1 || m_config.blocksPerDatagram > kMaxBlocksPerDatagram)
    fail("client: blocks per datagram ", m_config.blocksPerDatagram, " not in 1..", kMaxBlocksPerDatagram);
  if (!m_config.key && !m_config.server.isLoopback())
    fail("client: server ", toString(m_config.server),
         " is not on this machine: a session across the network needs the server's key (--key FILE|HEX; "
         "`vtouching serve --key FILE` writes one)");
  m_latencies.resize(m_config.latencyCapacity);
  if (m_config.wantVideo) m_videoReassembler = std::make_unique<VideoReassembler>();
  m_hello.codecCount = std::uint8_t(m_config.codecs.size());
  for (std::size_t i = 0; i < m_config.codecs.size(); ++i) m_hello.codecs[i] = std::uint8_t(m_config.codecs[i]);
  m_hello.quality = std::uint8_t(m_config.quality);
  m_hello.sceneDigest = m_config.sceneDigest;
  m_hello.flags = std::uint8_t((m_config.wantVideo ? kHelloWantsVideo : 0) | (m_config.redundancy ? kHelloRedundancy : 0));
  m_hello.blockLength = m_config.blockLength;
  m_hello.block_ms = std::uint8_t(m_config.block_ms);
  m_hello.blocksPerDatagram = std::uint8_t(m_config.blocksPerDatagram);
  m_hello.radius_m = defaultHandRadii();
}

void Client::makeDecoders(const Accept& accept) {
  m_decoders.clear();
  for (auto id : m_config.codecs) {
    const haptics::CodecConfig format{id, m_config.quality, accept.actuatorCount, int(accept.sampleRate_hz),
                                      accept.blockLength, accept.block_ms};
    if (const std::string_view why = haptics::checkCodecConfig(format); !why.empty())
      fail("server ", toString(m_config.server), " streams ", int(accept.block_ms), " ms blocks of ", accept.blockLength,
           "-sample frames at ", accept.sampleRate_hz, " Hz, which this client cannot decode: ", why);
    if (haptics::framesPerBlock(format) > kMaxFramesPerBlock)
      fail("server ", toString(m_config.server), " streams blocks of more than ", kMaxFramesPerBlock, " frames");
    m_decoders.push_back(haptics::makeBlockDecoder(format));
  }
}

Client::~Client() { disconnect(); }

Accept Client::session() const noexcept {
  Accept accept = m_accept;
  accept.sessionId = m_sessionId.load(std::memory_order_relaxed);
  accept.codec = m_codecId.load(std::memory_order_relaxed);
  return accept;
}

bool Client::sendBytes(std::span<const std::uint8_t> bytes) noexcept {
  if (bytes.empty() || !m_transport.send(bytes, m_config.server)) return false;
  m_bytesSent.fetch_add(bytes.size(), std::memory_order_relaxed);
  m_datagramsSent.fetch_add(1, std::memory_order_relaxed);
  return true;
}

bool Client::sendHello() noexcept {
  std::array<std::uint8_t, kMaxDatagram> bytes{};
  Hello hello = m_hello;
  hello.client_t_ns = now();
  hello.cookie = m_cookie;
  std::array<std::uint8_t, kNonceSize> nonce{};
  const std::size_t size = encodeHandshake(hello, bytes, m_config.key ? &*m_config.key : nullptr, &nonce);
  if (m_config.key) {
    const int i = m_helloCount.load(std::memory_order_relaxed);
    m_helloNonces[std::size_t(i) % m_helloNonces.size()] = nonce;
    m_helloCount.store(i + 1, std::memory_order_relaxed);
  }
  return sendBytes(std::span(bytes.data(), size));
}

std::size_t Client::sendStream(const Message& message, std::size_t* body) noexcept {
  StreamContext context;
  if (!m_context.read(context)) return 0;
  std::array<std::uint8_t, kMaxDatagram> bytes{};
  const std::size_t size = encodeStream(message, m_sendSequence.fetch_add(1) + 1, context, Direction::ClientToServer, bytes);
  if (!sendBytes(std::span(bytes.data(), size))) return 0;
  if (body) *body = size - kStreamHeaderSize - (context.keys ? kTagSize : 0);
  return size;
}

bool Client::resume(const Accept& accept, const Packet& packet, std::int64_t now_ns, const char*& why) noexcept {
  haptics::BlockDecoder* decoder = nullptr;
  for (const auto& d : m_decoders)
    if (std::uint8_t(d->config().id) == accept.codec) decoder = d.get();
  if (!decoder) {
    why = "chose a codec that was not offered";
    return false;
  }
  if (accept.quality != m_config.quality) {
    why = "changed the codec quality";
    return false;
  }
  if (m_config.blockLength != 0 && accept.blockLength != m_config.blockLength) {
    why = "streams another frame length than the one asked for";
    return false;
  }
  if (accept.block_ms != m_config.block_ms) {
    why = "streams another codec block length than the one asked for (client --block-ms)";
    return false;
  }
  // A reconnection must keep the stream format the jitter buffer and the sinks were set up for.
  // The decoders were made for it too.
  if (m_jitter && (accept.actuatorCount != m_accept.actuatorCount || accept.blockLength != m_accept.blockLength ||
                   accept.sampleRate_hz != m_accept.sampleRate_hz)) {
    why = "offers another stream format (actuators, block length or sample rate)";
    return false;
  }
  if (m_config.key && packet.answers < 0) {
    why = "sent an accept that answers none of this client's hellos";
    return false;
  }
  m_decoder = decoder;
  m_frequency_hz.fill(0);
  StreamContext context;
  context.sessionId = accept.sessionId;
  context.epoch_ns = accept.epoch_ns;
  context.actuatorCount = accept.actuatorCount;
  context.framesPerBlock = decoder->frameCount();
  context.receiving = Direction::ServerToClient;
  context.token = accept.token;
  // The radii the server holds for this session: those of the hello it answered.
  context.radius_m = pose_wire::quantisedRadii(m_hello.radius_m);
  if (m_config.key) {
    SessionKeys& keys = m_keys[accept.sessionId % 2];
    keys = deriveSessionKeys(*m_config.key, accept.sessionId,
                             m_helloNonces[std::size_t(packet.answers) % m_helloNonces.size()], packet.nonce);
    context.keys = &keys;
  }
  m_receive = context;
  m_replay.reset();
  m_sendSequence.store(0);
  m_context.publish(context);
  m_sessionId.store(accept.sessionId, std::memory_order_relaxed);
  m_codecId.store(accept.codec, std::memory_order_relaxed);
  m_lastHeard_ns.store(now_ns);
  m_nextKeepAlive_ns = now_ns;
  m_bye.store(false);
  m_connected.store(true, std::memory_order_release);
  return true;
}

void Client::connect() {
  if (m_running.load()) return;
  std::array<std::uint8_t, kMaxDatagram + 1> buffer{};
  Packet packet;
  std::string unauthenticated;  // a plain refusal a keyed client cannot trust, shown if nothing else comes
  const std::int64_t giveUp = now() + m_config.connectTimeout_ns;
  const auto nonces = [&] {
    return std::span(m_helloNonces.data(), std::min<std::size_t>(std::size_t(m_helloCount.load()), m_helloNonces.size()));
  };
  const std::string server = toString(m_config.server);
  // The session's radii: the hand's when there is one already, else the hand model's.
  if (HandPose newest; m_config.poses && m_config.poses->newest(newest) && newest.valid) m_hello.radius_m = newest.radius_m;
  while (now() < giveUp) {
    if (!m_helloAnswered) m_cookie = {};  // a stale cookie (a restarted server) gets no answer: ask anew
    m_helloAnswered = false;
    sendHello();
    const std::int64_t retry = std::min(giveUp, now() + kHelloRetry_ns);
    for (;;) {
      Endpoint from;
      const std::int64_t wait = std::min(retry - now(), kHelloRetry_ns);
      if (wait <= 0) break;
      const std::size_t size = m_transport.receive(buffer, from, SteadyClock::instance().now_ns() + wait);
      if (size == 0) continue;
      if (!(from == m_config.server)) continue;
      const auto bytes = std::span(buffer.data(), std::min(size, buffer.size()));
      if (const int version = handshakeVersion(bytes); version >= 1 && version < kProtocolVersion)
        fail("server ", server, " speaks protocol version ", version, ", this client version ", int(kProtocolVersion),
             ": use the same vtouching release on both sides (", legacyRefuseText(bytes), ")");
      const Key* key = m_config.key ? &*m_config.key : nullptr;
      if (decodeHandshake(bytes, packet, key, nonces(), &m_rejects) != DecodeStatus::Ok) {
        // A keyed client may still read a plain refusal, but only to explain a failure later.
        if (key && decodeHandshake(bytes, packet) == DecodeStatus::Ok && std::holds_alternative<Refuse>(packet.message))
          unauthenticated = std::string(std::get<Refuse>(packet.message).message());
        continue;
      }
      m_helloAnswered = true;
      if (const auto* refuse = std::get_if<Refuse>(&packet.message)) {
        if (refuse->reason == RefuseReason::SceneMismatch && !m_config.sceneName.empty())
          fail("server ", server, " refused the session: ", refuse->message(), "; this client renders ", m_config.sceneName,
               ": load the same scene on both sides (the same --dataset, --scene or --builtin)");
        fail("server ", server, " refused the session: ", refuse->message());
      }
      if (const auto* challenge = std::get_if<Challenge>(&packet.message)) {
        m_cookie = challenge->cookie;  // proof that this client receives here: ask again with it
        sendHello();
        continue;
      }
      const auto* accept = std::get_if<Accept>(&packet.message);
      if (!accept) continue;
      const char* why = "";
      makeDecoders(*accept);
      if (!resume(*accept, packet, now(), why)) fail("server ", server, " ", why);
      m_accept = *accept;
      JitterConfig jitter = m_config.jitter;
      jitter.period_ns = periodOf(*accept);
      m_jitter = std::make_unique<JitterBuffer>(jitter);
      // The accept answers a hello: its round trip is the first RTT sample.
      m_rtt_ns.store(std::max<std::int64_t>(now() - accept->epoch_ns, 0));
      m_running.store(true);
      m_thread = std::thread([this] { run(); });
      if (m_config.poses && m_config.pacePoses) m_sender = std::thread([this] { sendLoop(); });
      log::info("client: session ", accept->sessionId, " with ", server, " codec ",
                haptics::codecName(haptics::CodecId(accept->codec)), ", ", int(accept->actuatorCount), " actuators x ",
                accept->blockLength, " samples at ", accept->sampleRate_hz, " Hz in ", int(accept->block_ms), " ms blocks",
                m_config.key ? ", authenticated" : "");
      return;
    }
  }
  if (!unauthenticated.empty())
    fail("no authenticated answer from server ", server, " within ", m_config.connectTimeout_ns / 1'000'000,
         " ms; an unauthenticated refusal said: ", unauthenticated);
  fail("no answer from server ", server, " within ", m_config.connectTimeout_ns / 1'000'000, " ms",
       m_config.key ? " (is it using the same key?)" : "");
}

std::pair<std::int64_t, std::int64_t> Client::poseTimes(std::uint64_t sequence) const noexcept {
  const std::uint64_t key = sequence << 32 | m_sessionId.load(std::memory_order_relaxed);
  const SentPose& slot = m_sentPoses[sequence % kSentPoses];
  const std::int64_t t = slot.t_ns.load(std::memory_order_acquire);
  const std::int64_t hand = slot.hand_t_ns.load(std::memory_order_acquire);
  if (slot.key.load(std::memory_order_acquire) != key) return {0, 0};
  return {t, hand};
}

bool Client::sendPoseAt(std::int64_t t_ns) noexcept {
  if (!m_connected.load(std::memory_order_acquire) || !m_config.poses) return false;
  const std::int64_t hand_t_ns = t_ns + m_handLead.advance(t_ns, m_handLeadTarget_ns.load(std::memory_order_relaxed));
  const PoseSample sample = m_config.poses->sample(hand_t_ns, m_config.sampling);
  if (!sample.pose.valid && sample.newest_t_ns == 0) return false;  // no hand yet
  const std::uint32_t session = m_sessionId.load(std::memory_order_relaxed);
  if (session != m_poseSession) m_poseSession = session, m_poseSequence = 0;
  Pose pose{++m_poseSequence, sample.pose};
  pose.hand.t_ns = hand_t_ns;  // the time it describes, on this clock
  pose.hand.sequence = pose.sequence;
  // Noted before sending: the frame rendered from it may come back before sendStream returns.
  SentPose& slot = m_sentPoses[pose.sequence % kSentPoses];
  slot.key.store(0, std::memory_order_release);
  slot.t_ns.store(t_ns, std::memory_order_release);
  slot.hand_t_ns.store(hand_t_ns, std::memory_order_release);
  slot.key.store(pose.sequence << 32 | session, std::memory_order_release);
  std::size_t body = 0;
  if (!sendStream(pose, &body)) return false;
  m_posesSent.fetch_add(1, std::memory_order_relaxed);
  m_poseBytes.fetch_add(body, std::memory_order_relaxed);
  return true;
}

void Client::sendLoop() noexcept {
  // Poses leave at the stream's block rate whatever the input rate (a window or a headset runs
  // at its display rate): the server renders one block per pose, so the stream never starves.
  if (m_config.realtimePriority > 0) requestRealtime("pose sender", m_config.realtimePriority);
  const std::int64_t period_ns = periodOf(m_accept);
  std::int64_t next = now();
  while (m_running.load(std::memory_order_acquire)) {
    next += period_ns;
    m_clock.sleepUntil(next);
    const std::int64_t t = now();
    // Fell behind (a stall): the missed slots are skipped, no burst to catch up; the grid keeps
    // its phase, so every pose still describes a slot's time.
    if (t - next > period_ns) next += (t - next) / period_ns * period_ns;
    // Stamped with its slot's time, not the wake-up's: a late wake-up then changes when the
    // pose leaves but not the hand it describes, so the frames played on the playout grid keep
    // a steady lag behind the hand (the stream delay the felt side is aligned with).
    sendPoseAt(next);  // false while disconnected: the HUD says so
  }
}

void Client::disconnect() noexcept {
  if (!m_running.exchange(false)) return;
  if (m_sender.joinable()) m_sender.join();
  if (m_thread.joinable()) m_thread.join();
  if (m_connected.exchange(false)) sendStream(Bye{ByeReason::Normal});
  // Whatever was playing stops here.
  emit(haptics::ActuatorFrame::silent(m_accept.actuatorCount, now()));
}

void Client::emit(const haptics::ActuatorFrame& frame) noexcept { m_config.outputs.emit(frame); }

void Client::playTactile(const Tactile& tactile, std::int64_t now_ns) noexcept {
  if (tactile.hasFrequency) m_frequency_hz = tactile.frequency_hz;
  const int frames = m_decoder->frameCount();
  const auto out = std::span(m_blockFrames.data(), std::size_t(frames));
  for (int b = 0; b < tactile.blockCount; ++b) {
    m_framesReceived.fetch_add(std::uint64_t(frames), std::memory_order_relaxed);
    if (!unpackBlock(tactile, b, *m_decoder, m_frequency_hz, out)) {
      m_decodeFailures.fetch_add(1, std::memory_order_relaxed);
      continue;
    }
    for (int f = 0; f < frames; ++f) {
      haptics::ActuatorFrame& frame = out[std::size_t(f)];
      frame.t_ns = now_ns;
      std::tie(frame.pose_t_ns, frame.hand_t_ns) = poseTimes(frame.sequence);
      // A block's frames arrive together but play one period apart: each counts as arriving
      // when it is to play, so the burst is not taken for network jitter (no extra playout delay).
      m_jitter->push(frame, now_ns + std::int64_t(b * frames + f) * m_jitter->period_ns());
    }
  }
}

void Client::handleHandshake(std::span<const std::uint8_t> bytes, std::int64_t now_ns) noexcept {
  Packet packet;
  const auto nonces = std::span(m_helloNonces.data(), std::min<std::size_t>(std::size_t(m_helloCount.load()), m_helloNonces.size()));
  if (decodeHandshake(bytes, packet, m_config.key ? &*m_config.key : nullptr, nonces, &m_rejects) != DecodeStatus::Ok)
    return;
  m_helloAnswered = true;
  if (const auto* challenge = std::get_if<Challenge>(&packet.message)) {
    if (m_connected.load(std::memory_order_relaxed) || !m_config.reconnect) return;
    m_cookie = challenge->cookie;
    sendHello();
    return;
  }
  const auto* accept = std::get_if<Accept>(&packet.message);
  if (!accept || m_connected.load(std::memory_order_relaxed) || !m_config.reconnect) return;  // a duplicate accept
  m_lastHeard_ns.store(now_ns, std::memory_order_relaxed);
  const char* why = "";
  if (resume(*accept, packet, now_ns, why)) {
    m_reconnects.fetch_add(1, std::memory_order_relaxed);
    m_resumeRefused = false;
    log::info("client: resumed with session ", accept->sessionId, " of ", toString(m_config.server));
  } else if (!m_resumeRefused) {  // once, not at every retry
    m_resumeRefused = true;
    log::warn("client: server ", toString(m_config.server), " ", why, "; not resuming");
  }
}

void Client::handleStream(std::span<const std::uint8_t> bytes, std::int64_t now_ns) noexcept {
  Packet packet;
  if (!m_connected.load(std::memory_order_relaxed)) return;
  if (receiveStream(bytes, m_receive, m_replay, packet, &m_rejects) != DecodeStatus::Ok) return;
  m_lastHeard_ns.store(now_ns, std::memory_order_relaxed);
  if (const auto* tactile = std::get_if<Tactile>(&packet.message)) {
    m_receive.newestFrame = std::max(m_receive.newestFrame,
                                     tactile->firstSequence + std::uint64_t(tactile->blockCount * m_receive.framesPerBlock) - 1);
    playTactile(*tactile, now_ns);
  } else if (const auto* keepAlive = std::get_if<KeepAlive>(&packet.message)) {
    m_keepAlives.fetch_add(1, std::memory_order_relaxed);
    if (keepAlive->reply) {
      const std::int64_t rtt = (now_ns - keepAlive->origin_t_ns) - (keepAlive->transmit_t_ns - keepAlive->receive_t_ns);
      if (rtt >= 0) m_rtt_ns.store(rtt, std::memory_order_relaxed);
    } else {
      // The server measures the clock offset with these: answer at once, with this clock's times.
      const std::int64_t t = now();
      sendStream(KeepAlive{true, keepAlive->origin_t_ns, now_ns, t});
    }
  } else if (const auto* video = std::get_if<Video>(&packet.message)) {
    m_video.fetch_add(1, std::memory_order_relaxed);
    // Buffers are swapped, not copied: the network thread only memcpys fragments.
    if (m_videoReassembler && m_videoReassembler->push(*video)) m_latestVideo.publish(m_videoReassembler->completed());
  } else if (std::holds_alternative<Bye>(packet.message)) {
    log::warn("client: server ", toString(m_config.server), " ended the session",
              m_config.reconnect ? "; reconnecting" : "");
    m_bye.store(true);
    m_connected.store(false);
  }
}

void Client::run() noexcept {
  // Playout happens on this thread: its wake-up delay is part of the motion-to-vibration latency.
  if (m_config.realtimePriority > 0) m_realtime.store(requestRealtime("client network", m_config.realtimePriority).granted());
  std::array<std::uint8_t, kMaxDatagram + 1> buffer{};
  while (m_running.load(std::memory_order_acquire)) {
    const std::int64_t t0 = now();
    // Waits in real time up to the next due slot on this clock (a manual clock: a short poll).
    const std::int64_t wait = std::clamp<std::int64_t>(m_jitter->nextDue_ns() - t0, 0, kMaxWait_ns);
    Endpoint from;
    const std::size_t size = m_transport.receive(buffer, from, SteadyClock::instance().now_ns() + wait);
    std::int64_t t = now();
    if (size) {
      m_bytesReceived.fetch_add(size, std::memory_order_relaxed);
      m_datagramsReceived.fetch_add(1, std::memory_order_relaxed);
      const auto bytes = std::span(buffer.data(), std::min(size, buffer.size()));
      if (!(from == m_config.server)) m_strangers.fetch_add(1, std::memory_order_relaxed);
      else if (looksLikeHandshake(bytes)) handleHandshake(bytes, t);
      else handleStream(bytes, t);
    }
    haptics::ActuatorFrame frame;
    bool concealed = false;
    while (m_jitter->pop(t, frame, concealed)) {
      frame.t_ns = t;  // played now: the sinks' latency counts from here
      emit(frame);
      if (!concealed && frame.pose_t_ns != 0) {
        t = now();
        const std::size_t i = m_latencyCount.load(std::memory_order_relaxed);
        if (i < m_latencies.size()) {
          m_latencies[i] = t - frame.pose_t_ns;
          m_latencyCount.store(i + 1, std::memory_order_release);
        }
      }
    }
    m_jitterStats.publish(m_jitter->stats());
    m_playedThrough_ns.store(t, std::memory_order_release);
    if (m_connected.load(std::memory_order_relaxed)) {
      if (t >= m_nextKeepAlive_ns) {
        // Also while poses flow: the round trip is measured, and the server hears the client.
        sendStream(KeepAlive{false, t, 0, 0});
        m_nextKeepAlive_ns = t + m_config.keepAlive_ns;
      }
      if (t - m_lastHeard_ns.load(std::memory_order_relaxed) > m_config.timeout_ns) {
        log::warn("client: server ", toString(m_config.server), " silent for ", m_config.timeout_ns / 1'000'000, " ms");
        m_connected.store(false);
      }
    } else if (m_config.reconnect && t >= m_nextHello_ns) {
      if (!m_helloAnswered) m_cookie = {};
      m_helloAnswered = false;
      sendHello();
      m_nextHello_ns = t + m_config.reconnectInterval_ns;
    }
  }
}

ClientStats Client::stats() const {
  ClientStats s;
  s.posesSent = m_posesSent.load();
  s.poseBytes = m_poseBytes.load();
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
  s.playedThrough_ns = m_playedThrough_ns.load(std::memory_order_acquire);
  s.connected = m_connected.load();
  s.serverSaidBye = m_bye.load();
  s.bytesSent = m_bytesSent.load();
  s.bytesReceived = m_bytesReceived.load();
  s.datagramsSent = m_datagramsSent.load();
  s.datagramsReceived = m_datagramsReceived.load();
  s.datagramsDropped = m_transport.stats().impairedDrops;
  return s;
}

std::vector<std::int64_t> Client::latencies() const {
  const std::size_t n = m_latencyCount.load(std::memory_order_acquire);
  return {m_latencies.begin(), m_latencies.begin() + std::ptrdiff_t(n)};
}

}  // namespace vt::net
