#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "vt/net/protocol.hpp"

using namespace vt::net;

namespace {

std::vector<std::uint8_t> handshake(const Message& message, const Key* key = nullptr,
                                    std::array<std::uint8_t, kNonceSize>* nonce = nullptr,
                                    const std::array<std::uint8_t, kNonceSize>* bound = nullptr) {
  std::vector<std::uint8_t> bytes(kMaxDatagram);
  bytes.resize(encodeHandshake(message, bytes, key, nonce, bound));
  return bytes;
}

std::vector<std::uint8_t> stream(const Message& message, std::uint64_t sequence, const StreamContext& context,
                                 Direction direction = Direction::ServerToClient) {
  std::vector<std::uint8_t> bytes(kMaxDatagram);
  bytes.resize(encodeStream(message, sequence, context, direction, bytes));
  return bytes;
}

StreamContext session(int actuators = 5) {
  StreamContext context;
  context.sessionId = 0x1234;
  context.epoch_ns = 1'000'000'000;
  context.actuatorCount = actuators;
  context.radius_m.fill(0.008f);
  return context;
}

/// A hand with every joint in a different place and a tilted palm, near (x, y, z).
vt::HandPose sampleHand(glm::vec3 at, std::int64_t t_ns) {
  vt::HandPose hand = vt::poseHand(glm::translate(glm::mat4(1.0f), at) *
                                       glm::mat4_cast(glm::angleAxis(0.7f, glm::normalize(glm::vec3(0.3f, 1.0f, -0.2f)))),
                                   {0.2f, 0.4f, 0.1f, 0.8f, 0.5f}, false, t_ns);
  hand.valid = true;
  hand.radius_m.fill(0.008f);
  return hand;
}

Tactile sampleTactile(int blocks) {
  Tactile tactile;
  tactile.firstSequence = 70000;
  tactile.blockCount = std::uint8_t(blocks);
  tactile.hasFrequency = true;
  tactile.frequency_hz = {250, 0, 100, 65535, 1};
  std::uint16_t offset = 0;
  for (int b = 0; b < blocks; ++b) {
    tactile.intensity[std::size_t(b)] = {10, 20, 30, 40, std::uint8_t(255 - b)};
    tactile.dataOffset[std::size_t(b)] = offset;
    tactile.dataSize[std::size_t(b)] = std::uint16_t(12 + b);
    for (int i = 0; i < 12 + b; ++i) tactile.data[offset + std::size_t(i)] = std::uint8_t(i * 7 + b);
    offset = std::uint16_t(offset + 12 + b);
  }
  return tactile;
}

}  // namespace

TEST_CASE("Handshake messages survive an encode-decode round trip, plain and keyed") {
  Hello hello;
  hello.codecCount = 3;
  hello.codecs = {3, 2, 1};
  hello.quality = 60;
  hello.sceneDigest = 0x0123456789abcdefull;
  hello.flags = kHelloWantsVideo | kHelloRedundancy;
  hello.blocksPerDatagram = 2;
  hello.block_ms = 64;
  hello.client_t_ns = 5'000'000'123;
  hello.radius_m.fill(0.0085f);
  hello.cookie[0] = 0xA5, hello.cookie[15] = 0x5A;
  Accept accept{77, 3, 60, 5, 32, 16, 8000, 1000, 0xfedcba9876543210ull, 2, 5'000'000'123, 9, 0x0102030405060708ull};
  Challenge challenge;
  challenge.cookie.fill(0x3C);
  const Key key = generateKey();
  for (const Key* k : {static_cast<const Key*>(nullptr), &key}) {
    std::array<std::uint8_t, kNonceSize> helloNonce{};
    const auto helloBytes = handshake(hello, k, &helloNonce);
    REQUIRE(!helloBytes.empty());
    Packet packet;
    REQUIRE(decodeHandshake(helloBytes, packet, k) == DecodeStatus::Ok);
    const Hello& h = std::get<Hello>(packet.message);
    CHECK(h.codecCount == 3);
    CHECK(h.flags == (kHelloWantsVideo | kHelloRedundancy));
    CHECK(h.sceneDigest == hello.sceneDigest);
    CHECK(h.client_t_ns == hello.client_t_ns);
    CHECK(h.blocksPerDatagram == 2);
    CHECK(h.block_ms == 64);
    CHECK(h.radius_m[3] == Approx(0.0085f).margin(5e-6));
    CHECK(h.cookie == hello.cookie);
    // An accept is bound to the hello it answers: only that hello's nonce opens it.
    const auto acceptBytes = handshake(accept, k, nullptr, k ? &helloNonce : nullptr);
    const std::array<std::array<std::uint8_t, kNonceSize>, 2> nonces{std::array<std::uint8_t, kNonceSize>{}, helloNonce};
    REQUIRE(decodeHandshake(acceptBytes, packet, k, nonces) == DecodeStatus::Ok);
    CHECK(std::get<Accept>(packet.message).epoch_ns == accept.epoch_ns);
    CHECK(std::get<Accept>(packet.message).block_ms == 16);
    CHECK(std::get<Accept>(packet.message).token == accept.token);
    // A challenge is an answer too: bound to the hello it answers when keyed.
    const auto challengeBytes = handshake(challenge, k, nullptr, k ? &helloNonce : nullptr);
    REQUIRE(decodeHandshake(challengeBytes, packet, k, nonces) == DecodeStatus::Ok);
    CHECK(std::get<Challenge>(packet.message).cookie == challenge.cookie);
    CHECK(challengeBytes.size() < helloBytes.size());  // no amplification: smaller than the hello
    if (k) {
      CHECK(packet.answers == 1);
      CHECK(decodeHandshake(challengeBytes, packet, k, std::span(nonces).first(1)) == DecodeStatus::Unauthentic);
      CHECK(decodeHandshake(acceptBytes, packet, k, std::span(nonces).first(1)) == DecodeStatus::Unauthentic);
      // A keyed end refuses plain handshakes, a plain end keyed ones.
      CHECK(decodeHandshake(handshake(hello), packet, k) == DecodeStatus::Unauthentic);
      CHECK(decodeHandshake(helloBytes, packet) == DecodeStatus::Unauthentic);
      // Another key does not open it.
      const Key other = generateKey();
      CHECK(decodeHandshake(helloBytes, packet, &other) == DecodeStatus::Unauthentic);
    }
  }
}

TEST_CASE("Stream messages survive an encode-decode round trip within a session, plain and keyed") {
  const Key key = generateKey();
  const std::array<std::uint8_t, kNonceSize> a{1}, b{2};
  const SessionKeys keys = deriveSessionKeys(key, 0x1234, a, b);
  for (const SessionKeys* k : {static_cast<const SessionKeys*>(nullptr), &keys}) {
    StreamContext sender = session();
    sender.keys = k;
    StreamContext receiver = sender;
    receiver.receiving = Direction::ServerToClient;
    receiver.newestFrame = 69990;
    receiver.newestDatagram = 65530;
    for (int blocks : {1, 3}) {
      const Tactile tactile = sampleTactile(blocks);
      const auto bytes = stream(tactile, 65541, sender);
      REQUIRE(!bytes.empty());
      Packet packet;
      REQUIRE(decodeStream(bytes, receiver, packet) == DecodeStatus::Ok);
      CHECK(packet.sequence == 65541);  // expanded from its low 16 bits
      const Tactile& t = std::get<Tactile>(packet.message);
      CHECK(t.firstSequence == 70000);
      CHECK(t.blockCount == blocks);
      CHECK(t.frequency_hz == tactile.frequency_hz);
      for (int i = 0; i < blocks; ++i) {
        CHECK(t.intensity[std::size_t(i)] == tactile.intensity[std::size_t(i)]);
        CHECK(std::equal(t.block(i).begin(), t.block(i).end(), tactile.block(i).begin(), tactile.block(i).end()));
      }
      // Any flipped bit of the tag or token is rejected (a keyless body is not authenticated).
      auto forged = bytes;
      forged[k ? bytes.size() / 2 : bytes.size() - 1] ^= 4;
      CHECK(decodeStream(forged, receiver, packet) == DecodeStatus::Unauthentic);
      if (k) {
        // Another session's key, or the other direction's key: rejected.
        StreamContext wrongWay = receiver;
        wrongWay.receiving = Direction::ClientToServer;
        CHECK(decodeStream(bytes, wrongWay, packet) == DecodeStatus::Unauthentic);
      }
    }
    StreamContext other = receiver;
    other.sessionId = 0x1235;
    Packet packet;
    CHECK(decodeStream(stream(KeepAlive{false, 5, 0, 0}, 65542, sender), other, packet) == DecodeStatus::OtherSession);
    const KeepAlive reply{true, -7, 123456789, 123456999};
    REQUIRE(decodeStream(stream(reply, 65543, sender), receiver, packet) == DecodeStatus::Ok);
    const KeepAlive& r = std::get<KeepAlive>(packet.message);
    CHECK((r.reply && r.origin_t_ns == -7 && r.receive_t_ns == 123456789 && r.transmit_t_ns == 123456999));
    REQUIRE(decodeStream(stream(Bye{ByeReason::Timeout}, 65544, sender), receiver, packet) == DecodeStatus::Ok);
    CHECK(std::get<Bye>(packet.message).reason == ByeReason::Timeout);
  }
}

TEST_CASE("Poses travel quantised within 0.1 mm and 0.1 degree in at most 200 bytes") {
  const StreamContext context = session();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
  double worstPosition_m = 0, worstAngle_deg = 0;
  std::size_t largest = 0;
  for (int i = 0; i < 500; ++i) {
    const Pose pose{std::uint64_t(i + 1), sampleHand({coordinate(rng), coordinate(rng), coordinate(rng)},
                                                     context.epoch_ns + std::int64_t(i) * 4'000'123)};
    const auto bytes = stream(pose, std::uint64_t(i + 1), context, Direction::ClientToServer);
    REQUIRE(!bytes.empty());
    largest = std::max(largest, bytes.size());
    StreamContext receiver = context;
    receiver.receiving = Direction::ClientToServer;
    receiver.newestPose = std::uint64_t(i);
    Packet packet;
    REQUIRE(decodeStream(bytes, receiver, packet) == DecodeStatus::Ok);
    const Pose& got = std::get<Pose>(packet.message);
    CHECK(got.sequence == pose.sequence);
    CHECK(std::abs(got.hand.t_ns - pose.hand.t_ns) < 1000);  // microseconds on the wire
    CHECK(got.hand.valid);
    for (int j = 0; j < vt::kHandJointCount; ++j)
      worstPosition_m = std::max(worstPosition_m, double(glm::length(got.hand.position[std::size_t(j)] - pose.hand.position[std::size_t(j)])));
    const std::size_t palm = std::size_t(vt::HandJoint::Palm);
    const float dot = std::min(1.0f, std::abs(glm::dot(got.hand.orientation[palm], pose.hand.orientation[palm])));
    worstAngle_deg = std::max(worstAngle_deg, 2.0 * std::acos(double(dot)) * 180.0 / 3.14159265);
    CHECK(got.hand.radius_m == context.radius_m);  // the session's radii: not on the wire
  }
  INFO("worst position error " << worstPosition_m * 1e3 << " mm, orientation " << worstAngle_deg << " deg");
  CHECK(worstPosition_m <= 1e-4);
  CHECK(worstAngle_deg <= 0.1);
  CHECK(largest <= 200);
  CHECK(largest - kTokenSize + kTagSize <= 216);
  // Radii that differ from the session's travel with the pose; an absent hand is a few bytes.
  Pose other{1, sampleHand({0, 0, 0}, context.epoch_ns)};
  other.hand.radius_m.fill(0.0101f);
  Packet packet;
  REQUIRE(decodeStream(stream(other, 1, context), context, packet) == DecodeStatus::Ok);
  CHECK(std::get<Pose>(packet.message).hand.radius_m[7] == Approx(0.0101f).margin(5e-6));
  Pose absent{2, vt::HandPose{}};
  absent.hand.t_ns = context.epoch_ns;
  const auto small = stream(absent, 2, context);
  CHECK(small.size() <= 12 + kTokenSize);
  REQUIRE(decodeStream(small, context, packet) == DecodeStatus::Ok);
  CHECK_FALSE(std::get<Pose>(packet.message).hand.valid);
}

TEST_CASE("Decoded hands orient every finger joint along its bone, as the kinematic hand does") {
  // Only the palm's orientation travels: the receiver derives the fingers' (the server video's
  // skinned hand bends with them). Left and right hands, straight to fully curled.
  const StreamContext context = session();
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  double worst_deg = 0, worstThumbTip_deg = 0;
  for (int i = 0; i < 200; ++i) {
    const vt::FingerCurls curls{unit(rng), unit(rng), unit(rng), unit(rng), unit(rng)};
    const glm::mat4 T_world_palm = glm::translate(glm::mat4(1.0f), {unit(rng), 1.0f, -unit(rng)}) *
                                   glm::mat4_cast(glm::angleAxis(6.0f * unit(rng), glm::normalize(glm::vec3(unit(rng), 1.0f, unit(rng) - 0.5f))));
    Pose pose{std::uint64_t(i + 1), vt::poseHand(T_world_palm, curls, i % 2 == 1, context.epoch_ns)};
    pose.hand.radius_m = context.radius_m;
    const auto bytes = stream(pose, std::uint64_t(i + 1), context, Direction::ClientToServer);
    StreamContext receiver = context;
    receiver.receiving = Direction::ClientToServer;
    receiver.newestPose = std::uint64_t(i);
    Packet packet;
    REQUIRE(decodeStream(bytes, receiver, packet) == DecodeStatus::Ok);
    const vt::HandPose& got = std::get<Pose>(packet.message).hand;
    for (int j = 0; j < vt::kHandJointCount; ++j) {
      const float dot = std::min(1.0f, std::abs(glm::dot(got.orientation[std::size_t(j)], pose.hand.orientation[std::size_t(j)])));
      const double angle_deg = 2.0 * std::acos(double(dot)) * 180.0 / 3.14159265;
      // The kinematic thumb tip is bent by its third flexion past the last bone it ends.
      if (vt::HandJoint(j) == vt::HandJoint::ThumbTip) {
        worstThumbTip_deg = std::max(worstThumbTip_deg, angle_deg - double(curls[0]) * 0.8 * 180.0 / 3.14159265);
      } else {
        worst_deg = std::max(worst_deg, angle_deg);
      }
    }
  }
  INFO("worst joint " << worst_deg << " deg, thumb tip beyond its extra bend " << worstThumbTip_deg << " deg");
  CHECK(worst_deg <= 0.2);
  CHECK(worstThumbTip_deg <= 0.2);
}

TEST_CASE("A 4 ms tactile frame for 5 actuators costs at most 12 bytes besides its codec data and token or tag") {
  Tactile one = sampleTactile(1);
  one.hasFrequency = false;
  const StreamContext context = session(5);
  const auto bytes = stream(one, 9, context);
  CHECK(bytes.size() - one.dataSize[0] <= 12 + kTokenSize);
  StreamContext keyed = context;
  const SessionKeys keys{};
  keyed.keys = &keys;
  CHECK(stream(one, 9, keyed).size() == bytes.size() - kTokenSize + kTagSize);
  // Several blocks share one header: each further block costs its levels and a length byte.
  const Tactile four = sampleTactile(4);
  std::size_t data = 0;
  for (int b = 0; b < 4; ++b) data += four.dataSize[std::size_t(b)];
  CHECK(stream(four, 9, context).size() - data <= 4 + 2 + 1 + 10 + 4 * 5 + 3 + kTokenSize);
}

TEST_CASE("A block of several frames carries every frame's levels beside one codec block") {
  StreamContext context = session(3);
  context.framesPerBlock = 4;  // 16 ms blocks of 4 ms frames
  Tactile two = sampleTactile(2);
  for (int f = 0; f < 8; ++f) two.intensity[std::size_t(f)] = {std::uint8_t(f), std::uint8_t(10 + f), std::uint8_t(20 + f)};
  const auto bytes = stream(two, 9, context);
  REQUIRE(!bytes.empty());
  Packet packet;
  REQUIRE(decodeStream(bytes, context, packet) == DecodeStatus::Ok);
  const Tactile& t = std::get<Tactile>(packet.message);
  CHECK(t.blockCount == 2);
  for (int f = 0; f < 8; ++f) CHECK(t.intensity[std::size_t(f)][2] == 20 + f);
  CHECK(std::equal(t.block(1).begin(), t.block(1).end(), two.block(1).begin(), two.block(1).end()));
  // The same bytes read as 1-frame blocks are another layout: not accepted as this message.
  StreamContext single = context;
  single.framesPerBlock = 1;
  Packet other;
  const bool same = decodeStream(bytes, single, other) == DecodeStatus::Ok &&
                    std::get<Tactile>(other.message).intensity[1][2] == 21;
  CHECK_FALSE(same);
  // More frames than a datagram may carry: refused both ways.
  context.framesPerBlock = 32;
  const Tactile three = sampleTactile(3);
  CHECK(stream(three, 9, context).empty());
}

TEST_CASE("Sequence numbers expand from their low 16 bits to the nearest value") {
  CHECK(expandSequence(5, 0) == 5);
  CHECK(expandSequence(0xfffe, 0x10003) == 0xfffe);
  CHECK(expandSequence(0x0002, 0x1fffe) == 0x20002);
  CHECK(expandSequence(0x1234, 0x51230) == 0x51234);
  CHECK(expandSequence(0x1234, 0x51240) == 0x51234);
}

TEST_CASE("The replay window takes each sequence once and nothing older than 64") {
  ReplayWindow window;
  CHECK_FALSE(window.fresh(0));
  for (std::uint64_t s : {1, 2, 5, 4}) {
    REQUIRE(window.fresh(s));
    window.accept(s);
  }
  CHECK_FALSE(window.fresh(4));
  CHECK(window.fresh(3));
  window.accept(100);
  CHECK_FALSE(window.fresh(5));   // older than the window
  CHECK(window.fresh(99));
  CHECK(window.fresh(37));
  CHECK_FALSE(window.fresh(36));
  CHECK_FALSE(window.fresh(100));
  // A session end takes each datagram once.
  StreamContext context = session();
  ReplayWindow taken;
  RejectCounters counters;
  Packet packet;
  const auto bytes = stream(KeepAlive{false, 1, 0, 0}, 7, context);
  REQUIRE(receiveStream(bytes, context, taken, packet, &counters) == DecodeStatus::Ok);
  CHECK(context.newestDatagram == 7);
  CHECK(receiveStream(bytes, context, taken, packet, &counters) == DecodeStatus::Replayed);
  CHECK(counters.of(DecodeStatus::Replayed) == 1);
}

TEST_CASE("Malformed datagrams are rejected with the right reason and counted") {
  RejectCounters counters;
  Packet packet;
  Hello hello;
  hello.codecCount = 1;
  hello.codecs[0] = 3;
  const auto good = handshake(hello);
  for (std::size_t n = 0; n < good.size(); ++n) {
    const auto status = decodeHandshake(std::span(good.data(), n), packet, nullptr, {}, &counters);
    CHECK((status == DecodeStatus::Truncated || status == DecodeStatus::BadMagic));
  }
  auto bad = good;
  bad[4] = 9;
  CHECK(decodeHandshake(bad, packet, nullptr, {}, &counters) == DecodeStatus::UnknownVersion);
  CHECK(handshakeVersion(bad) == 9);
  bad = good;
  bad[5] = 4;  // a stream type in a handshake
  CHECK(decodeHandshake(bad, packet, nullptr, {}, &counters) == DecodeStatus::UnknownType);
  bad = good;
  bad.push_back(0);  // trailing byte
  CHECK(decodeHandshake(bad, packet, nullptr, {}, &counters) == DecodeStatus::Inconsistent);
  // A flag bit that is not defined is refused, not ignored (the flags byte: where the encodings differ).
  Hello flagged = hello;
  flagged.flags = kHelloRedundancy;
  bad = handshake(flagged);
  REQUIRE(bad.size() == good.size());
  const auto flagsAt = std::size_t(std::mismatch(good.begin(), good.end(), bad.begin()).first - good.begin());
  REQUIRE(flagsAt < bad.size());
  CHECK(decodeHandshake(bad, packet, nullptr, {}, &counters) == DecodeStatus::Ok);
  bad[flagsAt] = 0x04;
  CHECK(decodeHandshake(bad, packet, nullptr, {}, &counters) == DecodeStatus::Inconsistent);
  std::vector<std::uint8_t> big(kMaxDatagram + 1, 0);
  CHECK(decodeHandshake(big, packet, nullptr, {}, &counters) == DecodeStatus::Oversized);
  const StreamContext context = session();
  auto keepAlive = stream(KeepAlive{false, 1, 0, 0}, 1, context);
  keepAlive[0] = 0x47;  // not a stream kind
  CHECK(decodeStream(keepAlive, context, packet, &counters) == DecodeStatus::BadMagic);
  keepAlive[0] = 0xC2;  // accept is no stream message
  CHECK(decodeStream(keepAlive, context, packet, &counters) == DecodeStatus::UnknownType);
  CHECK(counters.total() >= good.size() + 5);
}

TEST_CASE("An older peer's datagrams are answered in its own layout, naming both versions") {
  std::array<std::uint8_t, kMaxDatagram> bytes{};
  const std::string text = "this server speaks protocol version 4, this client version 3 or older";
  std::size_t size = encodeLegacyRefuse(text, bytes);
  REQUIRE(size == 20 + 2 + text.size());
  CHECK(handshakeVersion(std::span(bytes.data(), size)) == 2);
  CHECK(bytes[5] == 3);                                 // refuse, in the version-2 header
  CHECK(bytes[6] + bytes[7] * 256 == int(size) - 20);  // its length field
  CHECK(legacyRefuseText(std::span(bytes.data(), size)) == text);
  // Version 3's layout: its plain handshake header, then the refuse body (reason 2: version).
  size = encodeLegacyRefuse(text, bytes, 3);
  REQUIRE(size == 6 + 2 + text.size());
  CHECK(handshakeVersion(std::span(bytes.data(), size)) == 3);
  CHECK((bytes[5] == 3 && bytes[6] == 2 && bytes[7] == text.size()));
  CHECK(legacyRefuseText(std::span(bytes.data(), size)) == text);
  CHECK(encodeLegacyRefuse(text, bytes, 4) == 0);
}

TEST_CASE("The encoder refuses messages the decoder would reject") {
  std::array<std::uint8_t, kMaxDatagram> out{};
  Hello noCodecs;
  CHECK(encodeHandshake(noCodecs, out) == 0);
  Hello badRadius;
  badRadius.codecCount = 1;
  badRadius.codecs[0] = 1;
  badRadius.radius_m[2] = -1.0f;
  CHECK(encodeHandshake(badRadius, out) == 0);
  Accept zeroActuators{1, 3, 50, 0, 32, 4, 8000, 1000, 0};
  CHECK(encodeHandshake(zeroActuators, out) == 0);
  Accept oddBlock{1, 3, 50, 5, 32, 12, 8000, 1000, 0};  // 12 ms is not a codec block length
  CHECK(encodeHandshake(oddBlock, out) == 0);
  CHECK(encodeStream(KeepAlive{}, 0, session(), Direction::ClientToServer, out) == 0);  // sequence 0
  CHECK(encodeStream(Accept{}, 1, session(), Direction::ClientToServer, out) == 0);     // not a stream message
  Pose far{1, sampleHand({500.0f, 0, 0}, 0)};
  CHECK(encodeStream(far, 1, session(), Direction::ClientToServer, out) == 0);  // beyond the palm range
  std::array<std::uint8_t, 3> tiny{};
  CHECK(encodeStream(KeepAlive{}, 1, session(), Direction::ClientToServer, tiny) == 0);
}

TEST_CASE("Keys parse from hex and files and bad ones are named") {
  const Key key = generateKey();
  CHECK(parseKeyHex(keyToHex(key), "test") == key);
  CHECK_THROWS_WITH(parseKeyHex("abc", "--key"), Catch::Contains("--key") && Catch::Contains("64 hex digits"));
  CHECK_THROWS_WITH(parseKeyHex(std::string(63, 'a') + "g", "--key"), Catch::Contains("not a hex digit"));
  const auto path = std::filesystem::path(VT_TEST_OUTPUT_DIR) / "net_key_test.key";
  std::filesystem::create_directories(path.parent_path());
  std::filesystem::remove(path);
  writeKeyFile(path, key);
  CHECK((std::filesystem::status(path).permissions() & std::filesystem::perms::others_read) == std::filesystem::perms::none);
  CHECK(readKeyFile(path) == key);
  CHECK(keyFromArgument(path.string()) == key);
  CHECK(keyFromArgument(keyToHex(key)) == key);
  CHECK_THROWS_WITH(writeKeyFile(path, key), Catch::Contains(path.string()));  // never overwritten
  CHECK_THROWS_WITH(readKeyFile(path.string() + ".missing"), Catch::Contains("not found"));
}

TEST_CASE("Keys others can read, weak keys, keys in another encoding and cut keys are refused as such") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(VT_TEST_OUTPUT_DIR) / "net_key_refusals";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Key key = generateKey();
  const auto writeKey = [&](const char* name, const std::string& text, fs::perms mode) {
    std::ofstream(dir / name, std::ios::binary) << text;
    fs::permissions(dir / name, mode);
    return dir / name;
  };
  const auto owner = fs::perms::owner_read | fs::perms::owner_write;
  CHECK(readKeyFile(writeKey("ok.key", keyToHex(key) + "\n", owner)) == key);
  // As ssh: a key file readable (or writable) by the group or others is refused, with the fix.
  for (const fs::perms extra : {fs::perms::others_read, fs::perms::group_read, fs::perms::others_write}) {
    CHECK_THROWS_WITH(readKeyFile(writeKey("open.key", keyToHex(key), owner | extra)),
                      Catch::Contains("open.key': its permissions 06") && Catch::Contains("chmod 600"));
  }
  CHECK_THROWS_WITH(parseKeyHex(std::string(64, '0'), "--key"), Catch::Contains("--key: the key is all zeros"));
  CHECK_THROWS_WITH(parseKeyHex("000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f", "k"),
                    Catch::Contains("counts by a constant step"));
  CHECK_THROWS_WITH(parseKeyHex(std::string(32, 'a') + std::string(32, 'b'), "k"), Catch::Contains("repeats a few byte values"));
  CHECK_THROWS_WITH(readKeyFile(writeKey("bom.key", "\xEF\xBB\xBF" + keyToHex(key), owner)),
                    Catch::Contains("bom.key'") && Catch::Contains("UTF-8 byte-order mark"));
  std::string utf16 = "\xFF\xFE";
  for (const char c : keyToHex(key)) utf16 += std::string{c, '\0'};
  CHECK_THROWS_WITH(readKeyFile(writeKey("utf16.key", utf16, owner)), Catch::Contains("is UTF-16 text"));
  // A short hex string is a cut key, not the name of a missing file.
  CHECK_THROWS_WITH(keyFromArgument("abcd"), Catch::Contains("--key 'abcd': not a key") && Catch::Contains("this has 4"));
  CHECK_THROWS_WITH(keyFromArgument((dir / "nope.key").string()), Catch::Contains("no such key file"));
  CHECK_THROWS_WITH(readKeyFile(dir), Catch::Contains("is a folder"));
}
