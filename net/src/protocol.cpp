#include "vt/net/protocol.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "wire.hpp"

namespace vt::net {

namespace {

constexpr std::uint32_t kMaxSampleRate_hz = 96000;

bool finite(float v) noexcept { return std::isfinite(v); }

// ---- message bodies: write ----

void write(wire::Writer& w, const Hello& m) {
  w.u8(m.codecCount);
  for (int i = 0; i < m.codecCount && i < kMaxCodecOffers; ++i) w.u8(m.codecs[std::size_t(i)]);
  w.u8(m.quality);
  w.u64(m.sceneDigest);
  w.u8(m.flags);
}
void write(wire::Writer& w, const Accept& m) {
  w.u32(m.sessionId);
  w.u8(m.codec);
  w.u8(m.quality);
  w.u8(m.actuatorCount);
  w.u16(m.blockLength);
  w.u32(m.sampleRate_hz);
  w.u16(m.timeout_ms);
  w.u64(m.sceneDigest);
}
void write(wire::Writer& w, const Refuse& m) {
  w.u8(std::uint8_t(m.reason));
  w.u8(m.textLength);
  w.bytes({reinterpret_cast<const std::uint8_t*>(m.text.data()), std::min<std::size_t>(m.textLength, kMaxRefuseText)});
}
void write(wire::Writer& w, const HandPose& m) {
  w.i64(m.t_ns);
  w.u64(m.sequence);
  w.u8(m.valid ? 1 : 0);
  for (int j = 0; j < kHandJointCount; ++j) {
    const auto& p = m.position[std::size_t(j)];
    const auto& q = m.orientation[std::size_t(j)];
    w.f32(p.x), w.f32(p.y), w.f32(p.z);
    w.f32(q.w), w.f32(q.x), w.f32(q.y), w.f32(q.z);
    w.f32(m.radius_m[std::size_t(j)]);
  }
}
void write(wire::Writer& w, const Tactile& m) {
  w.u64(m.frameSequence);
  w.i64(m.frame_t_ns);
  w.i64(m.pose_t_ns);
  w.u8(m.codec);
  w.u8(m.actuatorCount);
  w.u16(m.blockLength);
  w.u32(m.sampleRate_hz);
  const int n = std::min<int>(m.actuatorCount, haptics::kMaxActuators);
  for (int i = 0; i < n; ++i) w.u8(m.intensity[std::size_t(i)]);
  for (int i = 0; i < n; ++i) w.u16(m.frequency_hz[std::size_t(i)]);
  w.u16(m.dataSize);
  w.bytes({m.data.data(), std::min<std::size_t>(m.dataSize, kMaxTactileData)});
}
void write(wire::Writer& w, const Video& m) {
  w.u32(m.frameId);
  w.u16(m.width);
  w.u16(m.height);
  w.u8(std::uint8_t(m.format));
  w.u16(m.fragmentIndex);
  w.u16(m.fragmentCount);
  w.u16(m.dataSize);
  w.bytes({m.data.data(), std::min<std::size_t>(m.dataSize, kMaxVideoData)});
}
void write(wire::Writer& w, const KeepAlive& m) { w.i64(m.echo_t_ns); }
void write(wire::Writer& w, const Bye& m) { w.u8(std::uint8_t(m.reason)); }

// ---- message bodies: read + validate. Each returns Ok or Inconsistent; truncation is
// detected afterwards through the reader's ok flag. ----

DecodeStatus read(wire::Reader& r, Hello& m) {
  m.codecCount = r.u8();
  if (m.codecCount == 0 || m.codecCount > kMaxCodecOffers) return DecodeStatus::Inconsistent;
  for (int i = 0; i < m.codecCount; ++i) m.codecs[std::size_t(i)] = r.u8();
  m.quality = r.u8();
  m.sceneDigest = r.u64();
  m.flags = r.u8();
  return m.quality <= 100 && (m.flags & ~kHelloWantsVideo) == 0 ? DecodeStatus::Ok : DecodeStatus::Inconsistent;
}
DecodeStatus read(wire::Reader& r, Accept& m) {
  m.sessionId = r.u32();
  m.codec = r.u8();
  m.quality = r.u8();
  m.actuatorCount = r.u8();
  m.blockLength = r.u16();
  m.sampleRate_hz = r.u32();
  m.timeout_ms = r.u16();
  m.sceneDigest = r.u64();
  const bool good = m.codec != 0 && m.quality <= 100 && m.actuatorCount >= 1 &&
                    m.actuatorCount <= haptics::kMaxActuators && m.blockLength >= 1 &&
                    m.blockLength <= haptics::kMaxBlockSamples && m.sampleRate_hz >= 1 &&
                    m.sampleRate_hz <= kMaxSampleRate_hz && m.timeout_ms > 0;
  return good ? DecodeStatus::Ok : DecodeStatus::Inconsistent;
}
DecodeStatus read(wire::Reader& r, Refuse& m) {
  const std::uint8_t reason = r.u8();
  m.reason = RefuseReason(reason);
  m.textLength = r.u8();
  if (reason < 1 || reason > std::uint8_t(RefuseReason::SceneMismatch) || m.textLength > kMaxRefuseText) return DecodeStatus::Inconsistent;
  r.bytes(reinterpret_cast<std::uint8_t*>(m.text.data()), m.textLength);
  for (int i = 0; i < m.textLength && r.ok(); ++i) {
    const char c = m.text[std::size_t(i)];
    if (c < 0x20 || c > 0x7e) return DecodeStatus::Inconsistent;
  }
  return DecodeStatus::Ok;
}
DecodeStatus read(wire::Reader& r, HandPose& m) {
  m.t_ns = r.i64();
  m.sequence = r.u64();
  const std::uint8_t valid = r.u8();
  m.valid = valid == 1;
  bool good = valid <= 1;
  for (int j = 0; j < kHandJointCount; ++j) {
    auto& p = m.position[std::size_t(j)];
    auto& q = m.orientation[std::size_t(j)];
    p.x = r.f32(), p.y = r.f32(), p.z = r.f32();
    q.w = r.f32(), q.x = r.f32(), q.y = r.f32(), q.z = r.f32();
    const float radius = r.f32();
    m.radius_m[std::size_t(j)] = radius;
    good = good && finite(p.x) && finite(p.y) && finite(p.z) && finite(q.w) && finite(q.x) &&
           finite(q.y) && finite(q.z) && finite(radius) && radius >= 0.0f;
  }
  return good ? DecodeStatus::Ok : DecodeStatus::Inconsistent;
}
DecodeStatus read(wire::Reader& r, Tactile& m) {
  m.frameSequence = r.u64();
  m.frame_t_ns = r.i64();
  m.pose_t_ns = r.i64();
  m.codec = r.u8();
  m.actuatorCount = r.u8();
  m.blockLength = r.u16();
  m.sampleRate_hz = r.u32();
  if (m.codec == 0 || m.actuatorCount < 1 || m.actuatorCount > haptics::kMaxActuators || m.blockLength < 1 ||
      m.blockLength > haptics::kMaxBlockSamples || m.sampleRate_hz < 1 || m.sampleRate_hz > kMaxSampleRate_hz)
    return DecodeStatus::Inconsistent;
  m.intensity.fill(0);
  m.frequency_hz.fill(0);
  for (int i = 0; i < m.actuatorCount; ++i) m.intensity[std::size_t(i)] = r.u8();
  for (int i = 0; i < m.actuatorCount; ++i) m.frequency_hz[std::size_t(i)] = r.u16();
  m.dataSize = r.u16();
  if (m.dataSize > kMaxTactileData) return DecodeStatus::Inconsistent;
  r.bytes(m.data.data(), m.dataSize);
  return DecodeStatus::Ok;
}
DecodeStatus read(wire::Reader& r, Video& m) {
  m.frameId = r.u32();
  m.width = r.u16();
  m.height = r.u16();
  const std::uint8_t format = r.u8();
  m.format = VideoFormat(format);
  m.fragmentIndex = r.u16();
  m.fragmentCount = r.u16();
  m.dataSize = r.u16();
  if (m.width == 0 || m.height == 0 || format != std::uint8_t(VideoFormat::Jpeg) || m.fragmentCount == 0 ||
      m.fragmentIndex >= m.fragmentCount || m.dataSize > kMaxVideoData)
    return DecodeStatus::Inconsistent;
  r.bytes(m.data.data(), m.dataSize);
  return DecodeStatus::Ok;
}
DecodeStatus read(wire::Reader& r, KeepAlive& m) {
  m.echo_t_ns = r.i64();
  return m.echo_t_ns >= 0 ? DecodeStatus::Ok : DecodeStatus::Inconsistent;
}
DecodeStatus read(wire::Reader& r, Bye& m) {
  const std::uint8_t reason = r.u8();
  m.reason = ByeReason(reason);
  return reason >= 1 && reason <= 3 ? DecodeStatus::Ok : DecodeStatus::Inconsistent;
}

template <class T>
DecodeStatus readBody(std::span<const std::uint8_t> payload, Message& out) noexcept {
  wire::Reader r(payload);
  T& body = out.emplace<T>();
  const DecodeStatus status = read(r, body);
  if (!r.ok()) return DecodeStatus::Truncated;
  if (status != DecodeStatus::Ok) return status;
  return r.remaining() == 0 ? DecodeStatus::Ok : DecodeStatus::Inconsistent;  // trailing bytes
}

}  // namespace

std::string_view statusName(DecodeStatus status) noexcept {
  static constexpr std::string_view kNames[kDecodeStatusCount] = {
      "ok", "truncated", "oversized", "bad-magic", "unknown-version", "unknown-type", "inconsistent"};
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

std::size_t encodePacket(const Packet& packet, std::span<std::uint8_t> out) noexcept {
  if (out.size() < kHeaderSize) return 0;
  const std::size_t capacity = std::min(out.size(), kMaxDatagram);
  wire::Writer body(out.subspan(kHeaderSize, capacity - kHeaderSize));
  // Validate by decoding what was written: encoder and decoder can never disagree.
  std::visit([&](const auto& m) { write(body, m); }, packet.message);
  if (!body.ok()) return 0;
  Message check;
  if (decodePayload(typeOf(packet.message), out.subspan(kHeaderSize, body.size()), check) != DecodeStatus::Ok)
    return 0;
  wire::Writer header(out.first(kHeaderSize));
  header.u32(kMagic);
  header.u8(kProtocolVersion);
  header.u8(std::uint8_t(typeOf(packet.message)));
  header.u16(std::uint16_t(body.size()));
  header.u32(packet.sequence);
  header.i64(packet.sender_t_ns);
  return kHeaderSize + body.size();
}

DecodeStatus decodePayload(MessageType type, std::span<const std::uint8_t> payload, Message& out) noexcept {
  switch (type) {
    case MessageType::Hello: return readBody<Hello>(payload, out);
    case MessageType::Accept: return readBody<Accept>(payload, out);
    case MessageType::Refuse: return readBody<Refuse>(payload, out);
    case MessageType::Pose: return readBody<HandPose>(payload, out);
    case MessageType::Tactile: return readBody<Tactile>(payload, out);
    case MessageType::Video: return readBody<Video>(payload, out);
    case MessageType::KeepAlive: return readBody<KeepAlive>(payload, out);
    case MessageType::Bye: return readBody<Bye>(payload, out);
  }
  return DecodeStatus::UnknownType;
}

DecodeStatus decodePacket(std::span<const std::uint8_t> bytes, Packet& out, RejectCounters* counters) noexcept {
  const auto status = [&]() noexcept {
    if (bytes.size() < kHeaderSize) return DecodeStatus::Truncated;
    if (bytes.size() > kMaxDatagram) return DecodeStatus::Oversized;
    wire::Reader r(bytes);
    if (r.u32() != kMagic) return DecodeStatus::BadMagic;
    if (r.u8() != kProtocolVersion) return DecodeStatus::UnknownVersion;
    const std::uint8_t type = r.u8();
    if (type < 1 || type > std::uint8_t(MessageType::Bye)) return DecodeStatus::UnknownType;
    const std::uint16_t length = r.u16();
    out.sequence = r.u32();
    out.sender_t_ns = r.i64();
    const std::size_t available = bytes.size() - kHeaderSize;
    if (length > available) return DecodeStatus::Truncated;
    if (length < available) return DecodeStatus::Inconsistent;
    return decodePayload(MessageType(type), bytes.subspan(kHeaderSize), out.message);
  }();
  if (status != DecodeStatus::Ok && counters) counters->count(status);
  return status;
}

}  // namespace vt::net
