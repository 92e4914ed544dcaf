#include <catch2/catch.hpp>

#include <array>
#include <cstring>
#include <limits>
#include <vector>

#include "vt/net/protocol.hpp"

using namespace vt::net;

namespace {

std::vector<std::uint8_t> encode(const Message& message, std::uint32_t sequence = 7) {
  std::vector<std::uint8_t> bytes(kMaxDatagram);
  const std::size_t size = encodePacket({sequence, 123456789, message}, bytes);
  bytes.resize(size);
  return bytes;
}

vt::HandPose samplePose() {
  vt::HandPose pose;
  pose.t_ns = 42'000'000;
  pose.sequence = 99;
  pose.valid = true;
  for (int j = 0; j < vt::kHandJointCount; ++j) {
    pose.position[std::size_t(j)] = {0.01f * float(j), -0.5f, 1.25f};
    pose.orientation[std::size_t(j)] = glm::quat(0.5f, 0.5f, -0.5f, 0.5f);
    pose.radius_m[std::size_t(j)] = 0.008f;
  }
  return pose;
}

}  // namespace

TEST_CASE("Every message type survives an encode-decode round trip") {
  Hello hello;
  hello.codecCount = 3;
  hello.codecs = {3, 2, 1};
  hello.quality = 60;
  hello.sceneDigest = 0x0123456789abcdefull;
  hello.flags = kHelloWantsVideo;
  Accept accept{77, 3, 60, 5, 32, 8000, 1000, 0xfedcba9876543210ull};
  Refuse refuse;
  refuse.reason = RefuseReason::Busy;
  const std::string_view text = "busy: another client is connected";
  refuse.textLength = std::uint8_t(text.size());
  std::memcpy(refuse.text.data(), text.data(), text.size());
  Tactile tactile;
  tactile.frameSequence = 1234567890123ull;
  tactile.frame_t_ns = 5;
  tactile.pose_t_ns = 4;
  tactile.codec = 2;
  tactile.actuatorCount = 5;
  tactile.blockLength = 32;
  tactile.sampleRate_hz = 8000;
  tactile.intensity = {10, 20, 30, 40, 255};
  tactile.frequency_hz = {250, 0, 100, 65535, 1};
  tactile.dataSize = 320;
  for (int i = 0; i < 320; ++i) tactile.data[std::size_t(i)] = std::uint8_t(i * 7);
  Video video;
  video.frameId = 9;
  video.width = 480;
  video.height = 480;
  video.fragmentIndex = 2;
  video.fragmentCount = 3;
  video.dataSize = 1000;
  video.data[999] = 0xd9;

  const std::vector<Message> messages = {hello, accept, refuse, samplePose(), tactile, video,
                                         KeepAlive{31337}, Bye{ByeReason::Timeout}};
  for (const Message& message : messages) {
    const auto bytes = encode(message);
    REQUIRE(bytes.size() >= kHeaderSize);
    REQUIRE(bytes.size() <= kMaxDatagram);
    Packet packet;
    RejectCounters counters;
    REQUIRE(decodePacket(bytes, packet, &counters) == DecodeStatus::Ok);
    CHECK(counters.total() == 0);
    CHECK(packet.sequence == 7);
    CHECK(packet.sender_t_ns == 123456789);
    REQUIRE(packet.message.index() == message.index());
    // Re-encoding the decoded message gives identical bytes: nothing lost or invented.
    CHECK(encode(packet.message) == bytes);
  }
  Packet packet;
  REQUIRE(decodePacket(encode(samplePose()), packet) == DecodeStatus::Ok);
  const auto& pose = std::get<vt::HandPose>(packet.message);
  CHECK(pose.sequence == 99);
  CHECK(pose.t_ns == 42'000'000);
  CHECK(pose.position[25].x == Approx(0.25f));
  CHECK(pose.orientation[3].w == 0.5f);
  REQUIRE(decodePacket(encode(refuse), packet) == DecodeStatus::Ok);
  CHECK(std::get<Refuse>(packet.message).message() == text);
}

TEST_CASE("The header is little-endian with magic version type and length") {
  const auto bytes = encode(KeepAlive{0x0102030405060708}, 0xA1B2C3D4);
  REQUIRE(bytes.size() == kHeaderSize + 8);
  CHECK(std::memcmp(bytes.data(), "VTNP", 4) == 0);
  CHECK(bytes[4] == kProtocolVersion);
  CHECK(bytes[5] == std::uint8_t(MessageType::KeepAlive));
  CHECK(bytes[6] == 8);
  CHECK(bytes[7] == 0);
  CHECK(bytes[8] == 0xD4);
  CHECK(bytes[11] == 0xA1);
  CHECK(bytes[kHeaderSize] == 0x08);
}

TEST_CASE("Malformed datagrams are rejected with the right reason and counted") {
  RejectCounters counters;
  Packet packet;
  const auto good = encode(samplePose());

  // Every truncation of a valid datagram is rejected.
  for (std::size_t n = 0; n < good.size(); ++n) {
    const auto status = decodePacket(std::span(good.data(), n), packet, &counters);
    CHECK(status != DecodeStatus::Ok);
  }
  CHECK(counters.of(DecodeStatus::Truncated) == good.size());

  std::vector<std::uint8_t> big(kMaxDatagram + 1, 0);
  CHECK(decodePacket(big, packet, &counters) == DecodeStatus::Oversized);

  auto bad = good;
  bad[0] ^= 0xff;
  CHECK(decodePacket(bad, packet, &counters) == DecodeStatus::BadMagic);
  bad = good;
  bad[4] = kProtocolVersion + 1;
  CHECK(decodePacket(bad, packet, &counters) == DecodeStatus::UnknownVersion);
  bad = good;
  bad[5] = 0;
  CHECK(decodePacket(bad, packet, &counters) == DecodeStatus::UnknownType);
  bad[5] = 9;
  CHECK(decodePacket(bad, packet, &counters) == DecodeStatus::UnknownType);

  bad = good;
  bad.push_back(0);  // trailing byte the length field does not cover
  CHECK(decodePacket(bad, packet, &counters) == DecodeStatus::Inconsistent);

  // A NaN joint position is inconsistent, not a pose.
  bad = good;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(bad.data() + kHeaderSize + 17, &nan, 4);
  CHECK(decodePacket(bad, packet, &counters) == DecodeStatus::Inconsistent);

  // Tactile with an actuator count beyond the glove, and a data size beyond the datagram.
  Tactile tactile;
  tactile.codec = 1;
  tactile.actuatorCount = 1;
  tactile.blockLength = 8;
  tactile.sampleRate_hz = 8000;
  tactile.dataSize = 4;
  auto t = encode(tactile);
  REQUIRE(!t.empty());
  t[kHeaderSize + 25] = 11;
  CHECK(decodePacket(t, packet, &counters) == DecodeStatus::Inconsistent);
  t = encode(tactile);
  t[t.size() - 6] = 0xff;  // dataSize low byte
  t[t.size() - 5] = 0x00;
  CHECK(decodePacket(t, packet, &counters) == DecodeStatus::Truncated);

  CHECK(counters.of(DecodeStatus::Inconsistent) == 3);
  CHECK(counters.of(DecodeStatus::UnknownType) == 2);
  CHECK(counters.total() == good.size() + 9);
}

TEST_CASE("The encoder refuses messages the decoder would reject") {
  std::array<std::uint8_t, kMaxDatagram> out{};
  Hello noCodecs;
  CHECK(encodePacket({1, 0, noCodecs}, out) == 0);
  Hello unknownFlag;
  unknownFlag.codecCount = 1;
  unknownFlag.codecs[0] = 1;
  unknownFlag.flags = 0x80;
  CHECK(encodePacket({1, 0, unknownFlag}, out) == 0);
  Accept zeroActuators{1, 3, 50, 0, 32, 8000, 1000};
  CHECK(encodePacket({1, 0, zeroActuators}, out) == 0);
  std::array<std::uint8_t, 10> tiny{};
  CHECK(encodePacket({1, 0, KeepAlive{}}, tiny) == 0);
}
