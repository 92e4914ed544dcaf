#include "vt/net/server.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <utility>

#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/realtime.hpp"
#include "vt/net/tactile_stream.hpp"
#include "vt/net/video_stream.hpp"
#include "pose_wire.hpp"

namespace vt::net {

namespace {

constexpr std::int64_t kIdleWait_ns = 5'000'000;  // receive timeout (real time) with nothing else to do
// Refusals (any reason, to anyone): a bucket of this many, refilled at this rate. Beyond it,
// wrong-version, forged or unwanted hellos get no answer at all: the server cannot be used
// to reflect traffic at a third party.
constexpr double kRefuseBurst = 5.0;
constexpr double kRefusePerSecond = 5.0;
// Refusals are logged one line each, at most one line per this period: a client retrying with
// the wrong key is named at its first try; a flood costs a line a second (the rest counted).
constexpr std::int64_t kRefusalLogPeriod_ns = 1'000'000'000;
// Challenges (a 22- or 62-byte answer, never larger than the hello it answers): a bucket of its
// own, so a flood of refusals does not keep genuine clients from their cookie.
constexpr double kChallengeBurst = 20.0;
constexpr double kChallengePerSecond = 20.0;
// A cookie is valid in the time bucket it was made in and the next: 10 to 20 s.
constexpr std::int64_t kCookiePeriod_ns = 10'000'000'000;
// Hello datagrams remembered (16-byte digests): a replay of any of them gets no answer.
constexpr std::size_t kSeenHellos = 4096;
// Frequencies are resent at least every this many tactile datagrams (a lost change heals).
constexpr int kFrequencyRefresh = 16;

// `prefix` + `name` within a refusal's kMaxRefuseText: whole when it fits (the client adds its
// own scene and the advice), else the name's end, where a path names its folder and the object count.
std::string refusalNaming(std::string_view prefix, std::string_view name) {
  const std::size_t room = kMaxRefuseText - prefix.size();
  if (name.size() <= room) return str(prefix, name);
  return str(prefix, "...", name.substr(name.size() - (room - 3)));
}

std::uint64_t cookieBucket(std::int64_t now_ns) noexcept { return std::uint64_t(now_ns / kCookiePeriod_ns); }

// A token bucket of `burst` refilled at `perSecond`: false (nothing sent) when empty.
bool takeToken(double& tokens, std::int64_t& refill_ns, std::int64_t now_ns, double burst, double perSecond) noexcept {
  tokens = std::min(burst, tokens + double(now_ns - refill_ns) * 1e-9 * perSecond);
  refill_ns = now_ns;
  if (tokens < 1.0) return false;
  tokens -= 1.0;
  return true;
}

}  // namespace

Server::Server(ServerConfig config)
    : m_config(std::move(config)),
      m_clock(m_config.clock ? *m_config.clock : SteadyClock::instance()),
      m_transport([&] {
        if (!m_config.key && !m_config.bind.isLoopback())
          fail("server: --bind ", toString(m_config.bind),
               " reaches beyond this machine, so sessions must be authenticated: give a key with --key FILE "
               "(`vtouching serve --key FILE` writes a new one when FILE does not exist; clients use the same "
               "file or its hex with `client --key`)");
        return m_config.bind;
      }(), m_config.impairment) {
  if (m_config.codecs.empty()) fail("server: no codecs allowed");
  for (auto id : m_config.codecs)
    if (!haptics::isKnownCodec(std::uint8_t(id))) fail("server: unknown codec id ", int(id));
  if (m_config.actuatorCount < 1 || m_config.actuatorCount > haptics::kMaxActuators)
    fail("server: actuatorCount ", m_config.actuatorCount, " not in 1..", haptics::kMaxActuators);
  if (m_config.blockLength < 1 || m_config.blockLength > haptics::kMaxBlockSamples)
    fail("server: blockLength ", m_config.blockLength, " not in 1..", haptics::kMaxBlockSamples);
  if (m_config.block_ms != 0 && std::find(haptics::kCodecBlockLengths_ms.begin(), haptics::kCodecBlockLengths_ms.end(),
                                           m_config.block_ms) == haptics::kCodecBlockLengths_ms.end())
    fail("server: block length ", m_config.block_ms, " ms is not one of 4, 8, 16, 32, 64, 128 (or 0: the client's)");
  if (m_config.timeout_ns <= 0 || m_config.timeout_ns / 1'000'000 > 65535) fail("server: timeout must be 1..65535 ms");
  if (!m_config.frameSource && !m_config.tick) fail("server: needs a frame source (tick or frameSource)");
  if (m_config.tick && !m_config.poses) fail("server: a frame source needs the pose history it reads (ServerConfig::poses)");
  if (m_config.maxGapFill < 0) fail("server: maxGapFill must not be negative");
  if (m_config.poses) {
    m_history = m_config.poses;
  } else {
    m_ownHistory = std::make_unique<PoseHistory>();
    m_history = m_ownHistory.get();
  }
  m_format = {m_config.actuatorCount, m_config.blockLength, m_config.sampleRate_hz};
  m_refuseTokens = kRefuseBurst;
  m_challengeTokens = kChallengeBurst;
  m_seenHellos.resize(kSeenHellos);
  randomBytes(m_cookieSecret);
  // Refusal texts are built here so the network thread never allocates them.
  m_versionText = str("protocol version mismatch: this server speaks version ", int(kProtocolVersion));
  m_legacyVersionText = str("this server speaks protocol version ", int(kProtocolVersion), ", this client version ",
                            int(kProtocolVersion) - 1, " or older: update the client");
  m_sceneMismatchText = refusalNaming("scene mismatch: the server renders ", m_config.sceneName);
  m_keyText = "authentication failed: this server needs its key (client --key FILE|HEX), or the key differs";
  m_plainText = "this server has no key: connect without --key";
}

Server::~Server() { stop(); }

void Server::start() {
  if (m_running.exchange(true)) return;
  m_thread = std::thread([this] { run(); });
  log::info("server: listening on ", toString(endpoint()), m_config.key ? " (authenticated sessions)" : "");
}

void Server::stop() noexcept {
  if (!m_running.exchange(false)) return;
  if (m_thread.joinable()) m_thread.join();
  if (m_active) endSession(ByeReason::Shutdown);
}

ServerStats Server::stats() const noexcept {
  ServerStats s;
  s.sessions = m_sessions.load();
  s.refused = m_refused.load();
  s.refusalsSuppressed = m_suppressed.load();
  s.challenges = m_challenges.load();
  s.timeouts = m_timeouts.load();
  s.posesApplied = m_posesApplied.load();
  s.posesStale = m_posesStale.load();
  s.gapTicks = m_gapTicks.load();
  s.framesSent = m_framesSent.load();
  s.blocksResent = m_blocksResent.load();
  s.codecBytes = m_codecBytes.load();
  s.encodeFailures = m_encodeFailures.load();
  s.strangerPackets = m_strangers.load();
  s.rejected = m_rejects.total();
  s.videoFramesSent = m_videoFramesSent.load();
  s.clockOffset_ns = m_offset_ns.load();
  s.rtt_ns = m_rtt_ns.load();
  s.clientConnected = m_connected.load();
  s.realtime = m_realtime.load();
  s.bytesSent = m_bytesSent.load();
  s.bytesReceived = m_bytesReceived.load();
  s.datagramsSent = m_datagramsSent.load();
  s.datagramsReceived = m_datagramsReceived.load();
  return s;
}

void Server::sendBytes(std::span<const std::uint8_t> bytes, const Endpoint& to) noexcept {
  if (bytes.empty() || !m_transport.send(bytes, to)) return;
  m_bytesSent.fetch_add(bytes.size(), std::memory_order_relaxed);
  m_datagramsSent.fetch_add(1, std::memory_order_relaxed);
}

void Server::sendStream(const Message& message, const Endpoint& to) noexcept {
  std::array<std::uint8_t, kMaxDatagram> bytes{};
  const std::size_t size = encodeStream(message, ++m_sendSequence, m_context, Direction::ServerToClient, bytes);
  sendBytes(std::span(bytes.data(), size), to);
}

void Server::setVideoClient(bool wanted, const Endpoint& client) noexcept {
  if (wanted) m_videoDestination.publish({client, m_context});
  m_videoWanted.store(wanted, std::memory_order_release);
}

bool Server::sendVideo(std::span<const std::uint8_t> jpeg, int width, int height) {
  VideoDestination destination;
  if (!m_videoWanted.load(std::memory_order_acquire) || !m_videoDestination.read(destination)) return false;
  const Endpoint& to = destination.to;
  const StreamContext& context = destination.context;
  const std::uint32_t frameId = m_videoFrameId.fetch_add(1, std::memory_order_relaxed) + 1;
  const bool sent = fragmentVideoFrame(jpeg, frameId, width, height, [&](const Video& fragment) {
    std::array<std::uint8_t, kMaxDatagram> bytes{};
    const std::size_t size = encodeStream(fragment, ++m_sendSequence, context, Direction::ServerToClient, bytes);
    sendBytes(std::span(bytes.data(), size), to);
  });
  if (!sent) return false;
  m_videoFramesSent.fetch_add(1, std::memory_order_relaxed);
  return true;
}

bool Server::mayRefuse(std::int64_t now_ns) noexcept {
  if (takeToken(m_refuseTokens, m_refuseRefill_ns, now_ns, kRefuseBurst, kRefusePerSecond)) return true;
  m_suppressed.fetch_add(1, std::memory_order_relaxed);
  return false;
}

bool Server::firstSight(std::span<const std::uint8_t> hello) noexcept {
  const std::array<std::uint8_t, 16> digest = digest16(m_cookieSecret, hello);
  for (std::size_t i = 0; i < std::min(m_seenHelloCount, m_seenHellos.size()); ++i) {
    if (m_seenHellos[i] == digest) {
      m_rejects.count(DecodeStatus::Replayed);
      return false;
    }
  }
  m_seenHellos[m_seenHelloCount++ % m_seenHellos.size()] = digest;
  return true;
}

void Server::logRefusal(const Endpoint& from, std::string_view why, std::int64_t now_ns) noexcept {
  if (m_refusalsLogged > 0 && now_ns < m_nextRefusalLog_ns) {
    ++m_refusalsUnlogged;
    return;
  }
  ++m_refusalsLogged;
  m_nextRefusalLog_ns = now_ns + kRefusalLogPeriod_ns;
  const std::uint64_t unlogged = std::exchange(m_refusalsUnlogged, 0);
  log::warn("server: refused ", toString(from), ": ", why,
            unlogged ? str(" (", unlogged, " other refusal", unlogged == 1 ? "" : "s", " since the last line)") : "");
}

Cookie Server::cookieFor(const Endpoint& from, std::uint64_t bucket) const noexcept {
  std::array<std::uint8_t, 8 + 8 + 16 + 2> input{'V', 'T', 'N', 'P', '4', 'c', 'k', 'y'};
  for (int i = 0; i < 8; ++i) input[8 + std::size_t(i)] = std::uint8_t(bucket >> (8 * i));
  for (std::size_t i = 0; i < from.address.size(); ++i) input[16 + i] = from.address[i];
  for (int i = 0; i < 2; ++i) input[32 + std::size_t(i)] = std::uint8_t(from.port >> (8 * i));
  return digest16(m_cookieSecret, input);
}

bool Server::validCookie(const Cookie& cookie, const Endpoint& from, std::int64_t now_ns) const noexcept {
  const std::uint64_t bucket = cookieBucket(now_ns);
  return cookie == cookieFor(from, bucket) || cookie == cookieFor(from, bucket - 1);
}

void Server::challenge(const Endpoint& to, const Packet& hello, std::int64_t now_ns) noexcept {
  if (!takeToken(m_challengeTokens, m_challengeRefill_ns, now_ns, kChallengeBurst, kChallengePerSecond)) {
    m_suppressed.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  std::array<std::uint8_t, kMaxDatagram> bytes{};
  const Key* key = m_config.key ? &*m_config.key : nullptr;
  const std::size_t size =
      encodeHandshake(Challenge{cookieFor(to, cookieBucket(now_ns))}, bytes, key, nullptr, key ? &hello.nonce : nullptr);
  m_challenges.fetch_add(1, std::memory_order_relaxed);
  sendBytes(std::span(bytes.data(), size), to);
}

void Server::refuse(const Endpoint& to, RefuseReason reason, std::string_view text, std::int64_t now_ns,
                    const Packet* hello) noexcept {
  logRefusal(to, text, now_ns);
  if (!mayRefuse(now_ns)) return;
  Refuse message;
  message.reason = reason;
  message.textLength = std::uint8_t(std::min(text.size(), kMaxRefuseText));
  std::memcpy(message.text.data(), text.data(), message.textLength);
  m_refused.fetch_add(1, std::memory_order_relaxed);  // before the reply: whoever reads it sees the count
  std::array<std::uint8_t, kMaxDatagram> bytes{};
  // An authenticated hello gets an authenticated answer; anything else a plain one.
  const bool sealed = m_config.key && hello;
  const std::size_t size = encodeHandshake(message, bytes, sealed ? &*m_config.key : nullptr, nullptr,
                                           sealed ? &hello->nonce : nullptr);
  sendBytes(std::span(bytes.data(), size), to);
}

void Server::closeSession() noexcept {
  flushFrames();
  m_active = false;
  m_encoder.reset();
  m_connected.store(false);
  setVideoClient(false, {});
}

void Server::endSession(ByeReason reason) noexcept {
  // State and counters first: whoever reacts to the bye sees the session already over.
  closeSession();
  if (reason == ByeReason::Timeout) m_timeouts.fetch_add(1, std::memory_order_relaxed);
  sendStream(Bye{reason}, m_client);
}

void Server::handleHello(const Packet& packet, std::span<const std::uint8_t> bytes, const Endpoint& from,
                         std::int64_t now_ns) noexcept {
  const Hello& hello = std::get<Hello>(packet.message);
  // A hello is taken once: a replayed datagram gets no answer. Then the address must prove it
  // receives: a hello without a cookie gets a challenge (no state kept), one with a cookie this
  // process did not make in the last 10-20 s (a replay, or from before a restart) nothing.
  if (!firstSight(bytes)) return;
  if (hello.cookie == Cookie{}) {
    challenge(from, packet, now_ns);
    return;
  }
  if (!validCookie(hello.cookie, from, now_ns)) {
    m_rejects.count(DecodeStatus::Replayed);
    return;
  }
  if (m_active && from == m_client && m_acceptSize) {  // the same client again (its accept was lost)
    sendBytes(std::span(m_acceptBytes.data(), m_acceptSize), from);
    m_lastHeard_ns = now_ns;
    return;
  }
  // A session nobody has used yet (its accept lost, or a replayed old hello) yields to a new one.
  if (m_active && m_confirmed) {
    refuse(from, RefuseReason::Busy, "busy: another client is connected", now_ns, &packet);
    return;
  }
  if (hello.sceneDigest != 0 && m_config.sceneDigest != 0 && hello.sceneDigest != m_config.sceneDigest) {
    // What the client shows would not be what the server lets it touch.
    refuse(from, RefuseReason::SceneMismatch, m_sceneMismatchText, now_ns, &packet);
    return;
  }
  if (hello.blockLength != 0 && hello.blockLength != m_config.blockLength) {
    refuse(from, RefuseReason::BadRequest, "frame length not offered: this server renders its own (ask for 0)", now_ns,
           &packet);
    return;
  }
  haptics::CodecConfig format;
  const char* refusal = "no common codec";
  RefuseReason reason = RefuseReason::NoCommonCodec;
  if (!chooseFormat(hello, format, refusal, reason)) {
    refuse(from, reason, refusal, now_ns, &packet);
    return;
  }
  const haptics::CodecId wanted = format.id;
  if (m_active) closeSession();
  try {
    m_encoder = haptics::makeBlockEncoder(format);
  } catch (const std::exception&) {  // allocation failure: refuse rather than die
    refuse(from, RefuseReason::BadRequest, "server could not create the codec", now_ns, &packet);
    return;
  }
  const int frames = haptics::framesPerBlock(format);
  m_accept = {m_nextSessionId++,
              std::uint8_t(wanted),
              hello.quality,
              std::uint8_t(m_config.actuatorCount),
              std::uint16_t(m_config.blockLength),
              std::uint8_t(format.block_ms),
              std::uint32_t(m_config.sampleRate_hz),
              std::uint16_t(m_config.timeout_ns / 1'000'000),
              m_config.sceneDigest,
              std::uint8_t(std::min(int(hello.blocksPerDatagram), kMaxTactileFrames / frames)),
              hello.client_t_ns,
              now_ns,
              0};
  std::array<std::uint8_t, kTokenSize> token{};
  randomBytes(token);
  for (std::size_t i = 0; i < kTokenSize; ++i) m_accept.token |= std::uint64_t(token[i]) << (8 * i);
  std::array<std::uint8_t, kNonceSize> acceptNonce{};
  m_acceptSize = encodeHandshake(m_accept, m_acceptBytes, m_config.key ? &*m_config.key : nullptr, &acceptNonce,
                                 m_config.key ? &packet.nonce : nullptr);
  m_context = StreamContext{};
  m_context.sessionId = m_accept.sessionId;
  m_context.epoch_ns = hello.client_t_ns;
  m_context.actuatorCount = m_config.actuatorCount;
  m_context.framesPerBlock = frames;
  m_context.radius_m = pose_wire::quantisedRadii(hello.radius_m);
  m_context.receiving = Direction::ClientToServer;
  m_context.token = m_accept.token;
  if (m_config.key) {
    SessionKeys& keys = m_keys[m_accept.sessionId % 2];
    keys = deriveSessionKeys(*m_config.key, m_accept.sessionId, packet.nonce, acceptNonce);
    m_context.keys = &keys;
  }
  m_receive = m_context;
  m_replay.reset();
  m_sendSequence.store(0);
  m_offset.reset();
  m_offset.addOneWay(hello.client_t_ns, now_ns);
  m_active = true;
  m_confirmed = false;
  m_client = from;
  m_lastHeard_ns = now_ns;
  m_nextKeepAlive_ns = now_ns;
  m_havePose = false;
  m_pending.blockCount = 0;
  m_pendingResent = 0;
  m_sent.blockCount = 0;
  m_redundant = (hello.flags & kHelloRedundancy) != 0 && m_accept.blocksPerDatagram == 1;
  m_nextFrame = 0;
  m_sinceFrequency = kFrequencyRefresh;  // the first datagram carries them
  m_connected.store(true);
  setVideoClient((hello.flags & kHelloWantsVideo) != 0, from);
  m_sessions.fetch_add(1, std::memory_order_relaxed);
  sendBytes(std::span(m_acceptBytes.data(), m_acceptSize), from);
  log::info("server: session ", m_accept.sessionId, " with ", toString(from), " codec ",
            haptics::codecName(wanted), " quality ", int(hello.quality), ", ", format.block_ms, " ms blocks",
            m_config.key ? ", authenticated" : "");
}

bool Server::chooseFormat(const Hello& hello, haptics::CodecConfig& out, const char*& refusal,
                          RefuseReason& reason) noexcept {
  const int fallback = m_config.block_ms ? m_config.block_ms : haptics::kCodecBlockLengths_ms[0];
  const int block_ms = hello.block_ms ? hello.block_ms : fallback;
  const auto say = [&](auto... parts) {
    std::snprintf(m_refuseText.data(), m_refuseText.size(), parts...);
    refusal = m_refuseText.data();
    reason = RefuseReason::BadRequest;
  };
  if (m_config.block_ms != 0 && block_ms != m_config.block_ms) {
    say("block length %d ms asked, this server streams %d ms blocks (client --block-ms %d)", block_ms,
        m_config.block_ms, m_config.block_ms);
    return false;
  }
  // The server's preference among the client's offers, skipping codecs whose block cannot travel.
  for (auto wanted : m_config.codecs) {
    if (std::find(hello.codecs.begin(), hello.codecs.begin() + hello.codecCount, std::uint8_t(wanted)) ==
        hello.codecs.begin() + hello.codecCount)
      continue;
    const haptics::CodecConfig c{wanted, hello.quality, m_config.actuatorCount, m_config.sampleRate_hz,
                                 m_config.blockLength, block_ms};
    if (const std::string_view why = haptics::checkCodecConfig(c); !why.empty()) {
      say("%d ms blocks: %.*s", block_ms, int(why.size()), why.data());
      continue;
    }
    const int frames = haptics::framesPerBlock(c);
    if (frames > kMaxFramesPerBlock) {
      say("%d ms blocks span %d frames of %d samples, more than %d", block_ms, frames, c.frameLength, kMaxFramesPerBlock);
      continue;
    }
    StreamContext context;
    context.actuatorCount = c.channels;
    context.framesPerBlock = frames;
    Tactile empty;
    empty.blockCount = 0;
    // Raw and PCM blocks have a fixed size; a perceptual block only overflows at extreme settings (counted).
    if (const std::size_t room = tactileRoom(empty, context); wanted != haptics::CodecId::Perceptual && maxPacketBytes(c) > room) {
      const std::string_view name = haptics::codecName(wanted);
      say("%.*s blocks of %d ms for %d actuators take %zu bytes, a datagram holds %zu: use perceptual or shorter blocks",
          int(name.size()), name.data(), block_ms, c.channels, maxPacketBytes(c), room);
      continue;
    }
    out = c;
    return true;
  }
  return false;
}

void Server::render(std::uint64_t sequence, std::int64_t t_ns, const HandPose* received, bool send) noexcept {
  haptics::ActuatorFrame frame;
  if (m_config.tick) {
    m_config.tick(t_ns, frame);
  } else {
    // At a pose's own time the frame source gets that very hand; in a gap, the history's.
    m_config.frameSource(received ? *received : m_history->sample(t_ns, m_config.sampling).pose, frame);
  }
  frame.sequence = sequence;  // one frame per pose: the client's pose clock paces playout
  frame.t_ns = t_ns;
  if (send) sendFrame(frame);
}

void Server::applyPose(const Pose& pose, std::int64_t now_ns) noexcept {
  if (m_havePose && pose.sequence <= m_lastPoseSequence) {
    m_posesStale.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  m_offset.addOneWay(pose.hand.t_ns, now_ns);  // until round trips refine it
  m_offset_ns.store(m_offset.offset_ns(), std::memory_order_relaxed);
  // The time the pose describes, on this clock (kept increasing if the offset estimate moves).
  std::int64_t t = m_offset.toLocal(pose.hand.t_ns);
  if (m_havePose) t = std::max(t, m_lastPose_t_ns + 1);
  HandPose local = pose.hand;
  local.t_ns = t;
  m_history->publish(local);
  // Lost poses: the loop ticks at each missing sequence's time, the hand interpolated across the
  // gap, so the texture keeps its phase. Those frames reach the client a period after their slot:
  // sent on their own they would only widen its playout delay for every frame (the client conceals
  // the slot instead), so they travel only inside a longer codec block that needs them, or, with
  // redundancy (whose playout delay has that period already), in the datagram of the pose after them.
  const std::uint64_t missing = m_havePose ? pose.sequence - m_lastPoseSequence - 1 : 0;
  if (missing > 0 && missing <= std::uint64_t(m_config.maxGapFill)) {
    const bool sendFilled = m_context.framesPerBlock > 1 || m_redundant;
    m_fillingGap = m_redundant;
    for (std::uint64_t k = 1; k <= missing; ++k) {
      const std::int64_t tk = m_lastPose_t_ns + (t - m_lastPose_t_ns) * std::int64_t(k) / std::int64_t(missing + 1);
      render(m_lastPoseSequence + k, tk, nullptr, sendFilled);
      m_gapTicks.fetch_add(1, std::memory_order_relaxed);
    }
    m_fillingGap = false;
  }
  m_havePose = true;
  m_lastPoseSequence = pose.sequence;
  m_lastPose_t_ns = t;
  render(pose.sequence, t, &local, true);
  m_posesApplied.fetch_add(1, std::memory_order_relaxed);  // after its frame: a reader sees both
}

void Server::flushFrames() noexcept {
  if (m_pending.blockCount == 0) return;
  // Frequencies travel when they change, and at least every kFrequencyRefresh datagrams.
  m_pending.hasFrequency = ++m_sinceFrequency >= kFrequencyRefresh || m_pending.frequency_hz != m_sentFrequency;
  if (m_pending.hasFrequency) m_sentFrequency = m_pending.frequency_hz, m_sinceFrequency = 0;
  const int fresh = m_pending.blockCount - m_pendingResent;
  m_framesSent.fetch_add(std::uint64_t(fresh) * std::uint64_t(m_context.framesPerBlock), std::memory_order_relaxed);
  m_blocksResent.fetch_add(std::uint64_t(m_pendingResent), std::memory_order_relaxed);
  for (int b = 0; b < m_pending.blockCount; ++b) m_codecBytes.fetch_add(m_pending.dataSize[std::size_t(b)], std::memory_order_relaxed);
  sendStream(m_pending, m_client);
  if (m_redundant) m_sent = m_pending;
  m_pending.blockCount = 0;
  m_pendingResent = 0;
}

void Server::sendFrame(const haptics::ActuatorFrame& frame) noexcept {
  if (!m_encoder) return;
  // A block covers consecutive frames: frames missing inside it (poses lost beyond the gap
  // fill) are silence, and a frame past the block's end starts a new block.
  while (m_encoder->pending() > 0 && m_nextFrame < frame.sequence) {
    haptics::ActuatorFrame silence = haptics::ActuatorFrame::silent(std::uint8_t(m_format.channels), frame.t_ns);
    silence.blockLength = std::uint16_t(m_format.length);
    silence.sampleRate_hz = std::uint32_t(m_format.sampleRate_hz);
    silence.sequence = m_nextFrame;
    encodeFrame(silence);
  }
  encodeFrame(frame);
}

void Server::encodeFrame(const haptics::ActuatorFrame& frame) noexcept {
  const int index = m_encoder->pending();
  haptics::ActuatorFrame& kept = m_blockFrames[std::size_t(index)];
  kept = frame;
  if (frame.actuatorCount != m_format.channels || frame.blockLength != m_format.length ||
      int(frame.sampleRate_hz) != m_format.sampleRate_hz) {  // not the session's shape: silence in its place
    m_encodeFailures.fetch_add(1, std::memory_order_relaxed);
    kept = haptics::ActuatorFrame::silent(std::uint8_t(m_format.channels), frame.t_ns);
    kept.sequence = frame.sequence;
  }
  m_nextFrame = frame.sequence + 1;
  if (m_encoder->push(kept.block)) sendBlock();
}

void Server::sendBlock() noexcept {
  const auto frames = std::span(m_blockFrames.data(), std::size_t(m_context.framesPerBlock));
  const auto packet = m_encoder->packet();
  // A block that does not follow the pending ones, or does not fit beside them, starts a datagram of its own.
  if (m_pending.blockCount > 0 &&
      frames[0].sequence != m_pending.firstSequence + std::uint64_t(m_pending.blockCount) * frames.size())
    flushFrames();
  // Redundancy: a datagram that starts with a new pose's block carries the block sent before it
  // first (when it is the one just before and both fit), so a lost datagram's block comes with the next.
  if (m_redundant && !m_fillingGap && m_pending.blockCount == 0 && m_sent.blockCount > 0 &&
      copyBlock(m_sent, m_sent.blockCount - 1, m_context, m_pending)) {
    m_pendingResent = 1;
    if (m_pending.firstSequence + frames.size() != frames[0].sequence) m_pending.blockCount = 0, m_pendingResent = 0;
  }
  bool packed = packBlock(frames, packet, m_context, m_pending);
  if (!packed && m_pendingResent > 0 && m_pendingResent == m_pending.blockCount) {  // only the copy is there: send the new block alone
    m_pending.blockCount = 0;
    m_pendingResent = 0;
    packed = packBlock(frames, packet, m_context, m_pending);
  }
  if (!packed && m_pending.blockCount > 0) {
    flushFrames();
    packed = packBlock(frames, packet, m_context, m_pending);
  }
  if (!packed) {
    m_encodeFailures.fetch_add(frames.size(), std::memory_order_relaxed);
    return;
  }
  // Full when the session's count is reached, or when another block this size would not fit;
  // a lost pose's block waits for the pose after it (redundancy).
  if (m_fillingGap) return;
  if (m_pending.blockCount - m_pendingResent >= m_accept.blocksPerDatagram || tactileRoom(m_pending, m_context) < packet.size())
    flushFrames();
}

void Server::handleStream(const Packet& packet, std::int64_t now_ns) noexcept {
  m_lastHeard_ns = now_ns;
  m_confirmed = true;
  if (const auto* pose = std::get_if<Pose>(&packet.message)) {
    m_receive.newestPose = std::max(m_receive.newestPose, pose->sequence);
    applyPose(*pose, now_ns);
  } else if (const auto* keepAlive = std::get_if<KeepAlive>(&packet.message)) {
    if (keepAlive->reply) {
      m_offset.addRoundTrip(keepAlive->origin_t_ns, keepAlive->receive_t_ns, keepAlive->transmit_t_ns, now_ns);
      m_offset_ns.store(m_offset.offset_ns(), std::memory_order_relaxed);
      m_rtt_ns.store(m_offset.rtt_ns(), std::memory_order_relaxed);
    } else {
      sendStream(KeepAlive{true, keepAlive->origin_t_ns, now_ns, m_clock.now_ns()}, m_client);
    }
  } else if (std::holds_alternative<Bye>(packet.message)) {
    log::info("server: client ", toString(m_client), " said bye");
    closeSession();
  }
}

void Server::receive(std::span<const std::uint8_t> bytes, const Endpoint& from, std::int64_t now_ns) noexcept {
  Packet packet;
  if (looksLikeHandshake(bytes)) {
    const int version = handshakeVersion(bytes);
    if (version != kProtocolVersion) {
      m_rejects.count(DecodeStatus::UnknownVersion);
      // An older client decodes only its own layout: answer in it, naming both versions.
      if (version >= 1 && version < kProtocolVersion) {
        logRefusal(from, m_legacyVersionText, now_ns);
        if (mayRefuse(now_ns)) {
          std::array<std::uint8_t, kMaxDatagram> reply{};
          m_refused.fetch_add(1, std::memory_order_relaxed);
          sendBytes(std::span(reply.data(), encodeLegacyRefuse(m_legacyVersionText, reply, std::min(version, 3))), from);
        }
      } else {
        refuse(from, RefuseReason::Version, m_versionText, now_ns);
      }
      return;
    }
    const Key* key = m_config.key ? &*m_config.key : nullptr;
    const DecodeStatus status = decodeHandshake(bytes, packet, key, {}, &m_rejects);
    if (status == DecodeStatus::Unauthentic) refuse(from, RefuseReason::Unauthorized, key ? m_keyText : m_plainText, now_ns);
    if (status != DecodeStatus::Ok) return;
    if (std::holds_alternative<Hello>(packet.message)) handleHello(packet, bytes, from, now_ns);
    return;
  }
  if (!m_active || !(from == m_client)) {
    m_strangers.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (receiveStream(bytes, m_receive, m_replay, packet, &m_rejects) == DecodeStatus::Ok) handleStream(packet, now_ns);
}

void Server::run() noexcept {
  // Pose-driven rendering runs on this thread: its wake-up delay is part of the latency.
  if (m_config.realtimePriority > 0) m_realtime.store(requestRealtime("server network", m_config.realtimePriority).granted());
  std::array<std::uint8_t, kMaxDatagram + 1> buffer{};
  while (m_running.load(std::memory_order_acquire)) {
    Endpoint from;
    const std::size_t size = m_transport.receive(buffer, from, SteadyClock::instance().now_ns() + kIdleWait_ns);
    const std::int64_t t = m_clock.now_ns();
    if (size) {
      m_bytesReceived.fetch_add(size, std::memory_order_relaxed);
      m_datagramsReceived.fetch_add(1, std::memory_order_relaxed);
      if (size > kMaxDatagram) m_rejects.count(DecodeStatus::Oversized);
      else receive(std::span(buffer.data(), size), from, t);
    }
    if (!m_active) continue;
    if (t - m_lastHeard_ns > m_config.timeout_ns) {
      log::warn("server: client ", toString(m_client), " silent for ", m_config.timeout_ns / 1'000'000,
                " ms: session ", m_accept.sessionId, " ended");
      endSession(ByeReason::Timeout);
    } else if (m_confirmed && t >= m_nextKeepAlive_ns) {
      sendStream(KeepAlive{false, t, 0, 0}, m_client);  // the client answers: a clock-offset sample
      m_nextKeepAlive_ns = t + m_config.keepAlive_ns;
    }
  }
}

}  // namespace vt::net
