#include "vt/net/protocol.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "pose_wire.hpp"
#include "vt/core/budgets.hpp"
#include "vt/haptics/codec/stream_codec.hpp"
#include "wire.hpp"

namespace vt::net {

namespace {

constexpr std::uint32_t kMaxSampleRate_hz = 96000;
constexpr std::uint8_t kKeyedBit = 0x80;      // handshake type byte: sealed with the shared key
constexpr std::uint8_t kStreamMark = 0xC0;    // stream kind byte: 0xC0 | flags | type
constexpr std::uint8_t kFlagA = 0x10, kFlagB = 0x20;
// Tactile flags: A = frequencies present, B = several blocks. Keep-alive: A = reply.
constexpr std::uint8_t kPoseValid = 0x01, kPoseRadii = 0x02;
constexpr std::uint8_t kLegacyHeaderSize = 20;
constexpr std::int64_t kMaxPoseOffset_us = std::int64_t(1) << 50;  // ~35 years from the session's epoch
using Nonce = std::array<std::uint8_t, kNonceSize>;

// Clock readings a peer sends: far from overflow when offsets and deltas are added to them.
bool saneTime(std::int64_t t_ns) noexcept { return t_ns >= -budget::kStampTime_ns && t_ns <= budget::kStampTime_ns; }

bool knownBlockLength(int block_ms) noexcept {
  const auto& lengths = haptics::kCodecBlockLengths_ms;
  return std::find(lengths.begin(), lengths.end(), block_ms) != lengths.end();
}

std::int64_t zigzagDecode(std::uint64_t v) noexcept { return std::int64_t(v >> 1) ^ -std::int64_t(v & 1); }
std::uint64_t zigzagEncode(std::int64_t v) noexcept { return (std::uint64_t(v) << 1) ^ std::uint64_t(v >> 63); }

// ---- handshake bodies ----

void write(wire::Writer& w, const Hello& m) {
  w.u8(m.codecCount);
  for (int i = 0; i < m.codecCount && i < kMaxCodecOffers; ++i) w.u8(m.codecs[std::size_t(i)]);
  w.u8(m.quality);
  w.u64(m.sceneDigest);
  w.u8(m.flags);
  w.u16(m.blockLength);
  w.u8(m.block_ms);
  w.u8(m.blocksPerDatagram);
  w.i64(m.client_t_ns);
  if (!pose_wire::writeRadii(w, m.radius_m)) w.fail();
  w.bytes(m.cookie);
}
void write(wire::Writer& w, const Accept& m) {
  w.u32(m.sessionId);
  w.u8(m.codec);
  w.u8(m.quality);
  w.u8(m.actuatorCount);
  w.u16(m.blockLength);
  w.u8(m.block_ms);
  w.u32(m.sampleRate_hz);
  w.u16(m.timeout_ms);
  w.u64(m.sceneDigest);
  w.u8(m.blocksPerDatagram);
  w.i64(m.epoch_ns);
  w.i64(m.server_t_ns);
  w.u64(m.token);
}
void write(wire::Writer& w, const Challenge& m) { w.bytes(m.cookie); }
void write(wire::Writer& w, const Refuse& m) {
  w.u8(std::uint8_t(m.reason));
  w.u8(m.textLength);
  w.bytes({reinterpret_cast<const std::uint8_t*>(m.text.data()), std::min<std::size_t>(m.textLength, kMaxRefuseText)});
}

DecodeStatus read(wire::Reader& r, Hello& m) {
  m.codecCount = r.u8();
  if (m.codecCount == 0 || m.codecCount > kMaxCodecOffers) return DecodeStatus::Inconsistent;
  for (int i = 0; i < m.codecCount; ++i) m.codecs[std::size_t(i)] = r.u8();
  m.quality = r.u8();
  m.sceneDigest = r.u64();
  m.flags = r.u8();
  m.blockLength = r.u16();
  m.block_ms = r.u8();
  m.blocksPerDatagram = r.u8();
  m.client_t_ns = r.i64();
  pose_wire::readRadii(r, m.radius_m);
  r.bytes(m.cookie.data(), m.cookie.size());
  const bool good = m.quality <= 100 && (m.block_ms == 0 || knownBlockLength(m.block_ms)) && (m.flags & ~(kHelloWantsVideo | kHelloRedundancy)) == 0 && m.blocksPerDatagram >= 1 &&
                    m.blocksPerDatagram <= kMaxBlocksPerDatagram && saneTime(m.client_t_ns);
  return good ? DecodeStatus::Ok : DecodeStatus::Inconsistent;
}
DecodeStatus read(wire::Reader& r, Accept& m) {
  m.sessionId = r.u32();
  m.codec = r.u8();
  m.quality = r.u8();
  m.actuatorCount = r.u8();
  m.blockLength = r.u16();
  m.block_ms = r.u8();
  m.sampleRate_hz = r.u32();
  m.timeout_ms = r.u16();
  m.sceneDigest = r.u64();
  m.blocksPerDatagram = r.u8();
  m.epoch_ns = r.i64();
  m.server_t_ns = r.i64();
  m.token = r.u64();
  const bool good = m.codec != 0 && m.quality <= 100 && m.actuatorCount >= 1 &&
                    m.actuatorCount <= haptics::kMaxActuators && m.blockLength >= 1 &&
                    m.blockLength <= haptics::kMaxBlockSamples && knownBlockLength(m.block_ms) && m.sampleRate_hz >= 1 &&
                    m.sampleRate_hz <= kMaxSampleRate_hz && m.timeout_ms > 0 && m.blocksPerDatagram >= 1 &&
                    m.blocksPerDatagram <= kMaxBlocksPerDatagram && saneTime(m.epoch_ns) && saneTime(m.server_t_ns);
  return good ? DecodeStatus::Ok : DecodeStatus::Inconsistent;
}
DecodeStatus read(wire::Reader& r, Challenge& m) {
  r.bytes(m.cookie.data(), m.cookie.size());
  return DecodeStatus::Ok;
}
DecodeStatus read(wire::Reader& r, Refuse& m) {
  const std::uint8_t reason = r.u8();
  m.reason = RefuseReason(reason);
  m.textLength = r.u8();
  if (reason < 1 || reason > std::uint8_t(RefuseReason::Unauthorized) || m.textLength > kMaxRefuseText)
    return DecodeStatus::Inconsistent;
  r.bytes(reinterpret_cast<std::uint8_t*>(m.text.data()), m.textLength);
  for (int i = 0; i < m.textLength && r.ok(); ++i) {
    const char c = m.text[std::size_t(i)];
    if (c < 0x20 || c > 0x7e) return DecodeStatus::Inconsistent;
  }
  return DecodeStatus::Ok;
}

// ---- stream bodies (the kind byte's flags are returned/taken separately) ----

std::uint8_t write(wire::Writer& w, const Pose& m, const StreamContext& c) {
  w.u16(std::uint16_t(m.sequence));
  w.varint(zigzagEncode((m.hand.t_ns - c.epoch_ns) / 1000));
  const bool sendRadii = m.hand.valid && pose_wire::quantisedRadii(m.hand.radius_m) != pose_wire::quantisedRadii(c.radius_m);
  w.u8(std::uint8_t((m.hand.valid ? kPoseValid : 0) | (sendRadii ? kPoseRadii : 0)));
  if (m.hand.valid && !pose_wire::writeJoints(w, m.hand)) w.fail();
  if (sendRadii && !pose_wire::writeRadii(w, m.hand.radius_m)) w.fail();
  return 0;
}
std::uint8_t write(wire::Writer& w, const Tactile& m, const StreamContext& c) {
  const int n = std::clamp(c.actuatorCount, 1, haptics::kMaxActuators);
  const int frames = std::clamp(c.framesPerBlock, 1, kMaxFramesPerBlock);
  const int blocks = std::clamp<int>(m.blockCount, 1, kMaxBlocksPerDatagram);
  if (blocks * frames > kMaxTactileFrames) w.fail();
  w.u16(std::uint16_t(m.firstSequence));
  if (blocks > 1) w.u8(std::uint8_t(blocks));
  if (m.hasFrequency)
    for (int i = 0; i < n; ++i) w.u16(m.frequency_hz[std::size_t(i)]);
  for (int b = 0; b < blocks && w.ok(); ++b) {
    for (int f = b * frames; f < (b + 1) * frames; ++f)
      for (int i = 0; i < n; ++i) w.u8(m.intensity[std::size_t(f)][std::size_t(i)]);
    const auto data = m.block(b);
    if (b + 1 < blocks) w.varint(data.size());
    w.bytes(data);
  }
  return std::uint8_t((m.hasFrequency ? kFlagA : 0) | (blocks > 1 ? kFlagB : 0));
}
std::uint8_t write(wire::Writer& w, const Video& m, const StreamContext&) {
  w.u32(m.frameId);
  w.u16(m.width);
  w.u16(m.height);
  w.u8(std::uint8_t(m.format));
  w.u16(m.fragmentIndex);
  w.u16(m.fragmentCount);
  w.u16(m.dataSize);
  w.bytes({m.data.data(), std::min<std::size_t>(m.dataSize, kMaxVideoData)});
  return 0;
}
std::uint8_t write(wire::Writer& w, const KeepAlive& m, const StreamContext&) {
  w.i64(m.origin_t_ns);
  if (m.reply) {
    w.i64(m.receive_t_ns);
    w.varint(std::uint64_t(m.transmit_t_ns - m.receive_t_ns));  // the replier's hold time
  }
  return m.reply ? kFlagA : 0;
}
std::uint8_t write(wire::Writer& w, const Bye& m, const StreamContext&) {
  w.u8(std::uint8_t(m.reason));
  return 0;
}

DecodeStatus read(wire::Reader& r, std::uint8_t flags, const StreamContext& c, Pose& m) {
  if (flags) return DecodeStatus::Inconsistent;
  m.sequence = expandSequence(r.u16(), c.newestPose);
  m.hand = HandPose{};
  m.hand.sequence = m.sequence;
  const std::int64_t us = zigzagDecode(r.varint());
  if (us > kMaxPoseOffset_us || us < -kMaxPoseOffset_us) return DecodeStatus::Inconsistent;
  m.hand.t_ns = c.epoch_ns + us * 1000;
  const std::uint8_t poseFlags = r.u8();
  if (poseFlags & ~(kPoseValid | kPoseRadii) || (poseFlags & kPoseRadii && !(poseFlags & kPoseValid)))
    return DecodeStatus::Inconsistent;
  m.hand.valid = poseFlags & kPoseValid;
  m.hand.radius_m = c.radius_m;
  if (m.hand.valid && !pose_wire::readJoints(r, m.hand)) return DecodeStatus::Inconsistent;
  if (poseFlags & kPoseRadii) pose_wire::readRadii(r, m.hand.radius_m);
  return DecodeStatus::Ok;
}
DecodeStatus read(wire::Reader& r, std::uint8_t flags, const StreamContext& c, Tactile& m) {
  if (c.actuatorCount < 1 || c.actuatorCount > haptics::kMaxActuators || c.framesPerBlock < 1 ||
      c.framesPerBlock > kMaxFramesPerBlock)
    return DecodeStatus::Inconsistent;
  const int n = c.actuatorCount;
  const int frames = c.framesPerBlock;
  m.firstSequence = expandSequence(r.u16(), c.newestFrame);
  m.blockCount = flags & kFlagB ? r.u8() : 1;
  if (m.blockCount < 1 || m.blockCount > kMaxBlocksPerDatagram || (flags & kFlagB && m.blockCount < 2) ||
      m.blockCount * frames > kMaxTactileFrames)
    return DecodeStatus::Inconsistent;
  m.hasFrequency = flags & kFlagA;
  m.frequency_hz.fill(0);
  if (m.hasFrequency)
    for (int i = 0; i < n; ++i) m.frequency_hz[std::size_t(i)] = r.u16();
  std::size_t offset = 0;
  for (int b = 0; b < m.blockCount; ++b) {
    for (int f = b * frames; f < (b + 1) * frames; ++f) {
      auto& levels = m.intensity[std::size_t(f)];
      levels.fill(0);
      for (int i = 0; i < n; ++i) levels[std::size_t(i)] = r.u8();
    }
    const std::uint64_t size = b + 1 < m.blockCount ? r.varint() : r.remaining();
    if (size > kMaxTactileData || offset + size > m.data.size()) return DecodeStatus::Inconsistent;
    m.dataOffset[std::size_t(b)] = std::uint16_t(offset);
    m.dataSize[std::size_t(b)] = std::uint16_t(size);
    r.bytes(m.data.data() + offset, std::size_t(size));
    offset += std::size_t(size);
  }
  return DecodeStatus::Ok;
}
DecodeStatus read(wire::Reader& r, std::uint8_t flags, const StreamContext&, Video& m) {
  m.frameId = r.u32();
  m.width = r.u16();
  m.height = r.u16();
  const std::uint8_t format = r.u8();
  m.format = VideoFormat(format);
  m.fragmentIndex = r.u16();
  m.fragmentCount = r.u16();
  m.dataSize = r.u16();
  if (flags || m.width == 0 || m.height == 0 || format != std::uint8_t(VideoFormat::Jpeg) || m.fragmentCount == 0 ||
      m.fragmentIndex >= m.fragmentCount || m.dataSize > kMaxVideoData)
    return DecodeStatus::Inconsistent;
  r.bytes(m.data.data(), m.dataSize);
  return DecodeStatus::Ok;
}
DecodeStatus read(wire::Reader& r, std::uint8_t flags, const StreamContext&, KeepAlive& m) {
  if (flags & ~kFlagA) return DecodeStatus::Inconsistent;
  m.reply = flags & kFlagA;
  m.origin_t_ns = r.i64();
  m.receive_t_ns = m.transmit_t_ns = 0;
  if (m.reply) {
    m.receive_t_ns = r.i64();
    const std::uint64_t hold = r.varint();
    if (hold > std::uint64_t(1) << 61 || !saneTime(m.receive_t_ns)) return DecodeStatus::Inconsistent;
    m.transmit_t_ns = m.receive_t_ns + std::int64_t(hold);
  }
  return saneTime(m.origin_t_ns) ? DecodeStatus::Ok : DecodeStatus::Inconsistent;
}
DecodeStatus read(wire::Reader& r, std::uint8_t flags, const StreamContext&, Bye& m) {
  const std::uint8_t reason = r.u8();
  m.reason = ByeReason(reason);
  return flags == 0 && reason >= 1 && reason <= 3 ? DecodeStatus::Ok : DecodeStatus::Inconsistent;
}

template <class T>
DecodeStatus finish(wire::Reader& r, DecodeStatus status) noexcept {
  if (!r.ok()) return DecodeStatus::Truncated;
  if (status != DecodeStatus::Ok) return status;
  return r.remaining() == 0 ? DecodeStatus::Ok : DecodeStatus::Inconsistent;  // trailing bytes
}

template <class T>
DecodeStatus readHandshakeBody(std::span<const std::uint8_t> payload, Message& out) noexcept {
  wire::Reader r(payload);
  T& body = out.emplace<T>();
  const DecodeStatus status = read(r, body);
  return finish<T>(r, status);
}

template <class T>
DecodeStatus readStreamBody(std::span<const std::uint8_t> payload, std::uint8_t flags, const StreamContext& c,
                            Message& out) noexcept {
  wire::Reader r(payload);
  T& body = out.emplace<T>();
  const DecodeStatus status = read(r, flags, c, body);
  return finish<T>(r, status);
}

DecodeStatus decodeBody(MessageType type, std::uint8_t flags, std::span<const std::uint8_t> payload,
                        const StreamContext& c, Message& out) noexcept {
  switch (type) {
    case MessageType::Hello: return flags ? DecodeStatus::Inconsistent : readHandshakeBody<Hello>(payload, out);
    case MessageType::Accept: return flags ? DecodeStatus::Inconsistent : readHandshakeBody<Accept>(payload, out);
    case MessageType::Refuse: return flags ? DecodeStatus::Inconsistent : readHandshakeBody<Refuse>(payload, out);
    case MessageType::Pose: return readStreamBody<Pose>(payload, flags, c, out);
    case MessageType::Tactile: return readStreamBody<Tactile>(payload, flags, c, out);
    case MessageType::Video: return readStreamBody<Video>(payload, flags, c, out);
    case MessageType::KeepAlive: return readStreamBody<KeepAlive>(payload, flags, c, out);
    case MessageType::Bye: return readStreamBody<Bye>(payload, flags, c, out);
    case MessageType::Challenge: return flags ? DecodeStatus::Inconsistent : readHandshakeBody<Challenge>(payload, out);
  }
  return DecodeStatus::UnknownType;
}

/// The stream context an encoder checks its own output against: references at the values sent.
StreamContext selfContext(const Message& message, const StreamContext& c) noexcept {
  StreamContext self = c;
  self.keys = nullptr;
  if (const auto* pose = std::get_if<Pose>(&message)) self.newestPose = pose->sequence;
  if (const auto* tactile = std::get_if<Tactile>(&message)) self.newestFrame = tactile->firstSequence;
  return self;
}

DecodeStatus counted(DecodeStatus status, RejectCounters* counters) noexcept {
  if (status != DecodeStatus::Ok && counters) counters->count(status);
  return status;
}

}  // namespace

std::string_view statusName(DecodeStatus status) noexcept {
  static constexpr std::string_view kNames[kDecodeStatusCount] = {
      "ok",           "truncated", "oversized", "bad-magic",   "unknown-version",
      "unknown-type", "inconsistent", "unauthentic", "replayed", "other-session"};
  const auto i = std::size_t(status);
  return i < std::size(kNames) ? kNames[i] : std::string_view("unknown");
}

void RejectCounters::count(DecodeStatus status) noexcept {
  const auto i = std::size_t(status);
  if (i < m_counts.size()) m_counts[i].fetch_add(1, std::memory_order_relaxed);
}
std::uint64_t RejectCounters::of(DecodeStatus status) const noexcept {
  const auto i = std::size_t(status);
  return i < m_counts.size() ? m_counts[i].load(std::memory_order_relaxed) : 0;
}
std::uint64_t RejectCounters::total() const noexcept {
  std::uint64_t sum = 0;
  for (std::size_t i = 1; i < m_counts.size(); ++i) sum += m_counts[i].load(std::memory_order_relaxed);
  return sum;
}

MessageType typeOf(const Message& message) noexcept { return MessageType(message.index() + 1); }

bool isHandshake(MessageType type) noexcept { return type <= MessageType::Refuse || type == MessageType::Challenge; }

std::uint64_t expandSequence(std::uint16_t low, std::uint64_t reference) noexcept {
  // The candidate in reference's 2^16 window, moved by one window when that is nearer.
  const std::uint64_t base = reference & ~std::uint64_t(0xffff);
  std::uint64_t v = base | low;
  if (v + 0x8000 < reference && v + 0x10000 > v) v += 0x10000;
  else if (v > reference + 0x8000 && v >= 0x10000) v -= 0x10000;
  return v == 0 ? 0x10000 : v;
}

std::size_t encodeHandshake(const Message& message, std::span<std::uint8_t> out, const Key* key, Nonce* nonce,
                            const Nonce* boundNonce) noexcept {
  const MessageType type = typeOf(message);
  if (!isHandshake(type)) return 0;
  const std::size_t capacity = std::min(out.size(), kMaxDatagram);
  const std::size_t bodyAt = kHandshakeHeaderSize + (key ? kNonceSize : 0);
  const std::size_t tail = key ? kTagSize : 0;
  if (capacity < bodyAt + tail) return 0;
  wire::Writer body(out.subspan(bodyAt, capacity - bodyAt - tail));
  std::visit(
      [&](const auto& m) {
        if constexpr (requires { write(body, m); }) write(body, m);
      },
      message);
  if (!body.ok()) return 0;
  // Validate by decoding what was written: encoder and decoder can never disagree.
  Message check;
  if (decodeBody(type, 0, out.subspan(bodyAt, body.size()), StreamContext{}, check) != DecodeStatus::Ok) return 0;
  wire::Writer header(out.first(kHandshakeHeaderSize));
  header.u32(kMagic);
  header.u8(kProtocolVersion);
  header.u8(std::uint8_t(std::uint8_t(type) | (key ? kKeyedBit : 0)));
  if (!key) return bodyAt + body.size();
  Nonce n;
  randomBytes(n);
  std::copy(n.begin(), n.end(), out.begin() + kHandshakeHeaderSize);
  if (nonce) *nonce = n;
  // Associated data: the header, and for an answer the hello nonce it answers (not sent).
  std::array<std::uint8_t, kHandshakeHeaderSize + kNonceSize> ad{};
  std::copy_n(out.begin(), kHandshakeHeaderSize, ad.begin());
  if (boundNonce) std::copy(boundNonce->begin(), boundNonce->end(), ad.begin() + kHandshakeHeaderSize);
  seal(*key, n, ad, out.subspan(bodyAt, body.size()), out.subspan(bodyAt + body.size()).first<kTagSize>());
  return bodyAt + body.size() + kTagSize;
}

std::size_t encodeStream(const Message& message, std::uint64_t sequence, const StreamContext& context,
                         Direction sending, std::span<std::uint8_t> out) noexcept {
  const MessageType type = typeOf(message);
  if (isHandshake(type) || sequence == 0) return 0;
  const std::size_t capacity = std::min(out.size(), kMaxDatagram);
  const std::size_t tail = context.keys ? kTagSize : kTokenSize;
  if (capacity < kStreamHeaderSize + tail) return 0;
  wire::Writer body(out.subspan(kStreamHeaderSize, capacity - kStreamHeaderSize - tail));
  std::uint8_t flags = 0;
  std::visit(
      [&](const auto& m) {
        if constexpr (requires { write(body, m, context); }) flags = write(body, m, context);
      },
      message);
  if (!body.ok()) return 0;
  Message check;
  if (decodeBody(type, flags, out.subspan(kStreamHeaderSize, body.size()), selfContext(message, context), check) !=
      DecodeStatus::Ok)
    return 0;
  wire::Writer header(out.first(kStreamHeaderSize));
  header.u8(std::uint8_t(kStreamMark | flags | std::uint8_t(type)));
  header.u8(std::uint8_t(context.sessionId));
  header.u16(std::uint16_t(sequence));
  if (!context.keys) {
    wire::Writer token(out.subspan(kStreamHeaderSize + body.size(), kTokenSize));
    token.u64(context.token);
    return kStreamHeaderSize + body.size() + kTokenSize;
  }
  seal(context.keys->of(sending), streamNonce(context.sessionId, sending, sequence), out.first(kStreamHeaderSize),
       out.subspan(kStreamHeaderSize, body.size()), out.subspan(kStreamHeaderSize + body.size()).first<kTagSize>());
  return kStreamHeaderSize + body.size() + kTagSize;
}

bool looksLikeHandshake(std::span<const std::uint8_t> bytes) noexcept {
  wire::Reader r(bytes);
  return r.u32() == kMagic && r.ok();
}

int handshakeVersion(std::span<const std::uint8_t> bytes) noexcept {
  wire::Reader r(bytes);
  if (r.u32() != kMagic) return -1;
  const std::uint8_t version = r.u8();
  return r.ok() ? version : -1;
}

DecodeStatus decodeHandshake(std::span<const std::uint8_t> bytes, Packet& out, const Key* key,
                             std::span<const Nonce> boundNonces, RejectCounters* counters) noexcept {
  if (bytes.size() < kHandshakeHeaderSize) return counted(DecodeStatus::Truncated, counters);
  if (bytes.size() > kMaxDatagram) return counted(DecodeStatus::Oversized, counters);
  wire::Reader r(bytes);
  if (r.u32() != kMagic) return counted(DecodeStatus::BadMagic, counters);
  if (r.u8() != kProtocolVersion) return counted(DecodeStatus::UnknownVersion, counters);
  const std::uint8_t typeByte = r.u8();
  const std::uint8_t type = typeByte & ~kKeyedBit;
  if (type < 1 || !isHandshake(MessageType(type))) return counted(DecodeStatus::UnknownType, counters);
  const bool keyed = typeByte & kKeyedBit;
  out.sequence = 0;
  out.answers = -1;
  if (!keyed) {
    if (key) return counted(DecodeStatus::Unauthentic, counters);  // a keyed end trusts no plain handshake
    return counted(decodeBody(MessageType(type), 0, bytes.subspan(kHandshakeHeaderSize), StreamContext{}, out.message),
                   counters);
  }
  if (!key) return counted(DecodeStatus::Unauthentic, counters);
  if (bytes.size() < kHandshakeHeaderSize + kNonceSize + kTagSize) return counted(DecodeStatus::Truncated, counters);
  std::copy_n(bytes.begin() + kHandshakeHeaderSize, kNonceSize, out.nonce.begin());
  const std::size_t bodyAt = kHandshakeHeaderSize + kNonceSize;
  const std::size_t bodySize = bytes.size() - bodyAt - kTagSize;
  std::array<std::uint8_t, kMaxDatagram> text{};
  std::array<std::uint8_t, kHandshakeHeaderSize + kNonceSize> ad{};
  std::copy_n(bytes.begin(), kHandshakeHeaderSize, ad.begin());
  const auto tag = bytes.subspan(bodyAt + bodySize).first<kTagSize>();
  const bool answer = type != std::uint8_t(MessageType::Hello);
  bool opened = false;
  // An answer is bound to one of the hellos it may answer: try each (a handful at most).
  for (std::size_t i = 0; i < (answer ? boundNonces.size() : 1) && !opened; ++i) {
    if (answer) std::copy(boundNonces[i].begin(), boundNonces[i].end(), ad.begin() + kHandshakeHeaderSize);
    std::copy_n(bytes.begin() + bodyAt, bodySize, text.begin());
    opened = open(*key, out.nonce, ad, std::span(text.data(), bodySize), tag);
    if (opened && answer) out.answers = int(i);
  }
  if (!opened) return counted(DecodeStatus::Unauthentic, counters);
  return counted(decodeBody(MessageType(type), 0, std::span(text.data(), bodySize), StreamContext{}, out.message),
                 counters);
}

DecodeStatus decodeStream(std::span<const std::uint8_t> bytes, const StreamContext& context, Packet& out,
                          RejectCounters* counters) noexcept {
  const std::size_t tail = context.keys ? kTagSize : kTokenSize;
  if (bytes.size() < kStreamHeaderSize + tail) return counted(DecodeStatus::Truncated, counters);
  if (bytes.size() > kMaxDatagram) return counted(DecodeStatus::Oversized, counters);
  wire::Reader r(bytes);
  const std::uint8_t kind = r.u8();
  if ((kind & kStreamMark) != kStreamMark) return counted(DecodeStatus::BadMagic, counters);
  const std::uint8_t type = kind & 0x0f, flags = kind & (kFlagA | kFlagB);
  if (type < std::uint8_t(MessageType::Pose) || type > std::uint8_t(MessageType::Bye))
    return counted(DecodeStatus::UnknownType, counters);
  if (r.u8() != std::uint8_t(context.sessionId)) return counted(DecodeStatus::OtherSession, counters);
  out.sequence = expandSequence(r.u16(), context.newestDatagram);
  const std::size_t bodySize = bytes.size() - kStreamHeaderSize - tail;
  if (!context.keys) {
    wire::Reader token(bytes.subspan(kStreamHeaderSize + bodySize));
    if (token.u64() != context.token) return counted(DecodeStatus::Unauthentic, counters);
    return counted(decodeBody(MessageType(type), flags, bytes.subspan(kStreamHeaderSize, bodySize), context, out.message),
                   counters);
  }
  std::array<std::uint8_t, kMaxDatagram> text{};
  std::copy_n(bytes.begin() + kStreamHeaderSize, bodySize, text.begin());
  if (!open(context.keys->of(context.receiving), streamNonce(context.sessionId, context.receiving, out.sequence),
            bytes.first(kStreamHeaderSize), std::span(text.data(), bodySize),
            bytes.subspan(kStreamHeaderSize + bodySize).first<kTagSize>()))
    return counted(DecodeStatus::Unauthentic, counters);
  return counted(decodeBody(MessageType(type), flags, std::span(text.data(), bodySize), context, out.message), counters);
}

DecodeStatus receiveStream(std::span<const std::uint8_t> bytes, StreamContext& context, ReplayWindow& window,
                           Packet& out, RejectCounters* counters) noexcept {
  const DecodeStatus status = decodeStream(bytes, context, out, counters);
  if (status != DecodeStatus::Ok) return status;
  if (!window.fresh(out.sequence)) return counted(DecodeStatus::Replayed, counters);
  window.accept(out.sequence);
  context.newestDatagram = window.newest();
  return DecodeStatus::Ok;
}

DecodeStatus decodePayload(MessageType type, std::span<const std::uint8_t> payload, const StreamContext& context,
                           Message& out) noexcept {
  if (std::uint8_t(type) < 1 || type > MessageType::Bye) return DecodeStatus::UnknownType;
  // Stream flags live in the kind byte; a bare body is taken with none (fuzzing and tests).
  return decodeBody(type, 0, payload, context, out);
}

std::size_t encodeLegacyRefuse(std::string_view text, std::span<std::uint8_t> out, int version) noexcept {
  const std::size_t length = std::min(text.size(), kMaxRefuseText);
  if (version == 3) {  // version 3's plain handshake: magic, version, type, then the refuse body
    const std::size_t size = kHandshakeHeaderSize + 2 + length;
    if (out.size() < size) return 0;
    wire::Writer w(out);
    w.u32(kMagic);
    w.u8(3);
    w.u8(std::uint8_t(MessageType::Refuse));
    w.u8(std::uint8_t(RefuseReason::Version));
    w.u8(std::uint8_t(length));
    w.bytes({reinterpret_cast<const std::uint8_t*>(text.data()), length});
    return w.ok() ? size : 0;
  }
  const std::size_t size = kLegacyHeaderSize + 2 + length;
  if (version < 1 || version > 2 || out.size() < size) return 0;
  wire::Writer w(out);
  w.u32(kMagic);
  w.u8(2);  // the layout of versions 1 and 2: magic, version, type, u16 length, u32 sequence, i64 time
  w.u8(std::uint8_t(MessageType::Refuse));
  w.u16(std::uint16_t(2 + length));
  w.u32(1);
  w.i64(1);
  w.u8(std::uint8_t(RefuseReason::Version));
  w.u8(std::uint8_t(length));
  w.bytes({reinterpret_cast<const std::uint8_t*>(text.data()), length});
  return w.ok() ? size : 0;
}

std::string_view legacyRefuseText(std::span<const std::uint8_t> bytes) noexcept {
  wire::Reader r(bytes);
  if (r.u32() != kMagic) return {};
  const std::uint8_t version = r.u8();
  if (version < 1 || version > 3 || r.u8() != std::uint8_t(MessageType::Refuse)) return {};
  r.skip(version == 3 ? 1 : 2 + 4 + 8 + 1);  // version 3: reason; before: length, sequence, time, reason
  const std::uint8_t length = r.u8();
  const auto rest = r.rest();
  if (!r.ok() || rest.size() < length) return {};
  for (std::size_t i = 0; i < length; ++i)
    if (rest[i] < 0x20 || rest[i] > 0x7e) return {};
  return {reinterpret_cast<const char*>(rest.data()), length};
}

}  // namespace vt::net
