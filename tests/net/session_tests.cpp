#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <thread>

#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/net/client.hpp"
#include "vt/net/map_renderer.hpp"
#include "vt/net/server.hpp"
#include "test_support.hpp"

using namespace vt::net;
using vt::test::eventually;
using vt::haptics::ActuatorFrame;
using vt::haptics::CodecId;

namespace {

constexpr std::int64_t kPeriod = 4'000'000;  // 32 samples at 8 kHz
const Endpoint kAnyPort = parseEndpoint("127.0.0.1:0");

std::int64_t now() { return vt::SteadyClock::instance().now_ns(); }

ServerConfig mapServer() {
  ServerConfig config;
  config.bind = kAnyPort;
  auto renderer = std::make_shared<MapRenderer>();
  config.renderer = [renderer](const vt::HandPose& pose, ActuatorFrame& frame) { renderer->render(pose, frame); };
  return config;
}

ClientConfig clientOf(const Server& server, CodecId codec) {
  ClientConfig config;
  config.server = server.endpoint();
  config.codecs = {codec};
  return config;
}

/// The scripted slide: 0.1 m/s along x, one pose per frame period, paced in real time.
vt::HandPose slidePose(std::uint64_t sequence) {
  return slidingHand(0.0004f * float(sequence), 0.01f, now(), sequence);
}

void slide(Client& client, std::uint64_t first, int count) {
  std::int64_t next = now();
  for (int i = 0; i < count; ++i, next += kPeriod) {
    vt::SteadyClock::instance().sleepUntil(next);
    client.sendPose(slidePose(first + std::uint64_t(i)));
  }
}

bool silent(const ActuatorFrame& frame) {
  for (const auto& block : frame.block)
    for (float v : block)
      if (v != 0.0f) return false;
  return true;
}

}  // namespace

TEST_CASE("A loopback session reproduces the single-process actuator signal") {
  for (CodecId codec : {CodecId::RawFloat32, CodecId::Perceptual}) {
    Server server(mapServer());
    server.start();
    vt::SpscRing<ActuatorFrame> recorded(1024);
    ClientConfig config = clientOf(server, codec);
    config.framesOut = &recorded;
    // A generous playout margin: this test checks the signal, not timing (CI machines stall).
    config.jitter.minDelay_ns = 8'000'000;
    Client client(config);
    client.connect();
    CHECK(client.session().codec == std::uint8_t(codec));
    constexpr int kPoses = 150;
    slide(client, 1, kPoses);
    REQUIRE(eventually([&] { return client.stats().framesReceived >= kPoses - 2; }));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    client.disconnect();

    // The single-process run: the same renderer on the same poses.
    MapRenderer reference;
    std::map<std::uint64_t, ActuatorFrame> expected;
    for (std::uint64_t s = 1; s <= kPoses; ++s) reference.render(slidePose(s), expected[s]);

    ActuatorFrame frame;
    int compared = 0, matched = 0;
    double signal = 0, noise = 0;
    while (recorded.pop(frame)) {
      const auto it = expected.find(frame.sequence);
      if (it == expected.end() || frame.pose_t_ns == 0) continue;  // concealment (late or lost)
      ++compared;
      double frameSignal = 0, frameNoise = 0;
      for (int a = 0; a < 5; ++a)
        for (int i = 0; i < 32; ++i) {
          const double ref = it->second.block[std::size_t(a)][std::size_t(i)];
          const double d = ref - frame.block[std::size_t(a)][std::size_t(i)];
          frameSignal += ref * ref;
          frameNoise += d * d;
        }
      const bool ok = codec == CodecId::RawFloat32 ? frameNoise == 0.0 : frameNoise <= frameSignal * 0.1;
      matched += ok ? 1 : 0;
      signal += frameSignal;
      noise += frameNoise;
    }
    const auto stats = client.stats();
    INFO("codec " << vt::haptics::codecName(codec) << ": compared " << compared << " matched " << matched
                  << " concealed " << stats.framesConcealed << " late " << stats.jitter.late);
    // Every frame played from the stream matches; how many were played on time depends on
    // the machine's load (late ones are concealed), so only a majority is required.
    CHECK(compared >= kPoses / 2);
    CHECK(matched == compared);
    if (codec == CodecId::Perceptual) CHECK(10.0 * std::log10(signal / std::max(noise, 1e-30)) >= 20.0);
    CHECK(stats.decodeFailures == 0);
    CHECK(server.stats().posesApplied == kPoses);
    const auto latencies = client.latencies();
    REQUIRE(!latencies.empty());
    for (auto l : latencies) CHECK(l > 0);
  }
}

TEST_CASE("A second client is refused with a reason while the first is connected") {
  Server server(mapServer());
  server.start();
  Client first(clientOf(server, CodecId::Pcm16));
  first.connect();
  Client second(clientOf(server, CodecId::Pcm16));
  CHECK_THROWS_WITH(second.connect(), Catch::Contains("busy"));
  CHECK(server.stats().refused >= 1);
  first.disconnect();
  // The slot is free again after the first client's bye.
  REQUIRE(eventually([&] { return !server.stats().clientConnected; }));
  Client third(clientOf(server, CodecId::Pcm16));
  CHECK_NOTHROW(third.connect());
  CHECK(server.stats().sessions == 2);
}

TEST_CASE("A client showing another scene is refused and one without a scene is accepted") {
  ServerConfig config = mapServer();
  config.sceneDigest = 0xaaaa;
  config.sceneName = "dataset assets/dataset (8 objects)";
  Server server(config);
  server.start();
  ClientConfig other = clientOf(server, CodecId::Pcm16);
  other.sceneDigest = 0xbbbb;
  Client mismatched(other);
  CHECK_THROWS_WITH(mismatched.connect(), Catch::Contains("scene mismatch") && Catch::Contains("assets/dataset"));
  ClientConfig same = clientOf(server, CodecId::Pcm16);
  same.sceneDigest = 0xaaaa;
  Client matching(same);
  REQUIRE_NOTHROW(matching.connect());
  CHECK(matching.session().sceneDigest == 0xaaaa);
  matching.disconnect();
  REQUIRE(eventually([&] { return !server.stats().clientConnected; }));
  Client headless(clientOf(server, CodecId::Pcm16));  // digest 0: nothing shown to compare
  CHECK_NOTHROW(headless.connect());
}

TEST_CASE("A silent client times out and its session ends cleanly") {
  ServerConfig config = mapServer();
  config.timeout_ns = 150'000'000;
  Server server(config);
  server.start();
  {
    ClientConfig clientConfig = clientOf(server, CodecId::Perceptual);
    clientConfig.keepAlive_ns = 10'000'000'000;  // never: the client goes silent
    Client client(clientConfig);
    client.connect();
    CHECK(server.stats().clientConnected);
    REQUIRE(eventually([&] { return server.stats().timeouts == 1; }));
    CHECK_FALSE(server.stats().clientConnected);
    // The server said bye: the client learns its session is over.
    REQUIRE(eventually([&] { return client.stats().serverSaidBye; }));
  }
  // A keep-alive sending client stays connected past the timeout.
  ClientConfig livelyConfig = clientOf(server, CodecId::Perceptual);
  livelyConfig.keepAlive_ns = 30'000'000;
  Client keepsTalking(livelyConfig);
  keepsTalking.connect();
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  CHECK(server.stats().clientConnected);
  CHECK(server.stats().timeouts == 1);
  CHECK(keepsTalking.stats().rtt_ns > 0);
}

TEST_CASE("A reconnecting client resumes with a restarted server and refuses another stream format") {
  auto server = std::make_unique<Server>(mapServer());
  server->start();
  const Endpoint address = server->endpoint();
  ClientConfig config = clientOf(*server, CodecId::Perceptual);
  config.reconnect = true;
  config.reconnectInterval_ns = 50'000'000;
  Client client(config);
  client.connect();
  const std::uint32_t firstSession = client.session().sessionId;
  slide(client, 1, 20);
  server.reset();  // says bye: the session is over
  REQUIRE(eventually([&] { return !client.stats().connected; }));
  CHECK_FALSE(client.sendPose(slidePose(21)));
  // A new server on the same address: the client's hellos find it and the stream resumes.
  ServerConfig again = mapServer();
  again.bind = address;
  server = std::make_unique<Server>(again);
  server->start();
  REQUIRE(eventually([&] { return client.stats().connected; }));
  CHECK(client.stats().reconnects == 1);
  CHECK(client.session().sessionId == 1);  // the new server's first session
  CHECK(firstSession == 1);
  const auto before = client.stats().framesReceived;
  slide(client, 22, 20);
  CHECK(eventually([&] { return client.stats().framesReceived >= before + 15; }));
  // A server streaming another format (3 actuators) is not resumed with.
  server.reset();
  REQUIRE(eventually([&] { return !client.stats().connected; }));
  ServerConfig otherFormat = mapServer();
  otherFormat.bind = address;
  otherFormat.actuatorCount = 3;
  server = std::make_unique<Server>(otherFormat);
  server->start();
  REQUIRE(eventually([&] { return server->stats().sessions >= 1; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  CHECK_FALSE(client.stats().connected);
  CHECK(client.stats().reconnects == 1);
}

TEST_CASE("Actuator output returns to zero when the stream stops") {
  Server server(mapServer());
  server.start();
  vt::LatestValue<ActuatorFrame> latest;
  ClientConfig config = clientOf(server, CodecId::Perceptual);
  config.latestOut = &latest;
  Impairment impairment;
  impairment.loss = 0.05;
  impairment.jitter_ns = 1'000'000;
  impairment.seed = 3;
  config.impairment = impairment;
  Client client(config);
  client.connect();
  slide(client, 1, 100);
  ActuatorFrame frame;
  REQUIRE(latest.read(frame));
  // Poses stop (the hand still touches): within the hold + fade time the output is zero.
  REQUIRE(eventually([&] { return latest.read(frame) && silent(frame); }, 500));
  REQUIRE(eventually([&] { return !client.stats().jitter.depth && client.stats().framesConcealed > 0; }, 500));
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  REQUIRE(latest.read(frame));
  CHECK(silent(frame));
  CHECK(client.stats().jitter.lost > 0);  // the 5 % loss was concealed
}

TEST_CASE("The server counts malformed datagrams and refuses another protocol version") {
  Server server(mapServer());
  server.start();
  Transport raw(kAnyPort);
  const std::array<std::uint8_t, 7> garbage{1, 2, 3, 4, 5, 6, 7};
  raw.send(garbage, server.endpoint());
  std::array<std::uint8_t, kMaxDatagram + 1> bytes{};
  Hello hello;
  hello.codecCount = 1;
  hello.codecs[0] = 3;
  std::size_t size = encodePacket({1, now(), hello}, bytes);
  bytes[4] = 9;  // version 9
  raw.send(std::span(bytes.data(), size), server.endpoint());
  Endpoint from;
  size = raw.receive(bytes, from, now() + 2'000'000'000);
  Packet reply;
  REQUIRE(decodePacket(std::span(bytes.data(), size), reply) == DecodeStatus::Ok);
  REQUIRE(std::holds_alternative<Refuse>(reply.message));
  CHECK(std::get<Refuse>(reply.message).reason == RefuseReason::Version);
  CHECK(server.rejects().of(DecodeStatus::Truncated) == 1);
  CHECK(server.rejects().of(DecodeStatus::UnknownVersion) == 1);
  // A pose from a stranger is ignored and counted, and nobody is refused for no codec silently.
  raw.send(std::span(bytes.data(), encodePacket({2, now(), slidingHand(0, 0, now(), 1)}, bytes)), server.endpoint());
  REQUIRE(eventually([&] { return server.stats().strangerPackets == 1; }));
  Hello unknownCodec;
  unknownCodec.codecCount = 1;
  unknownCodec.codecs[0] = 77;
  raw.send(std::span(bytes.data(), encodePacket({3, now(), unknownCodec}, bytes)), server.endpoint());
  size = raw.receive(bytes, from, now() + 2'000'000'000);
  REQUIRE(decodePacket(std::span(bytes.data(), size), reply) == DecodeStatus::Ok);
  REQUIRE(std::holds_alternative<Refuse>(reply.message));
  CHECK(std::get<Refuse>(reply.message).reason == RefuseReason::NoCommonCodec);
}

TEST_CASE("Connecting to nothing fails with a clear error") {
  ClientConfig config;
  config.server = parseEndpoint("127.0.0.1:9");  // discard port: nobody answers
  config.connectTimeout_ns = 300'000'000;
  Client client(config);
  CHECK_THROWS_WITH(client.connect(), Catch::Contains("no answer") && Catch::Contains("127.0.0.1:9"));
}
