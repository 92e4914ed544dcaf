// Authenticated sessions: keyed client and server, wrong and missing keys, replayed hellos,
// the non-loopback rule, and a flood of forged datagrams the session must survive.
#include <catch2/catch.hpp>

#include <fstream>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/net/client.hpp"
#include "vt/net/map_frame_source.hpp"
#include "vt/net/server.hpp"
#include "session_constants.hpp"
#include "raw_handshake.hpp"
#include "test_support.hpp"

using namespace vt::net;
using vt::test::eventually;
using vt::haptics::ActuatorFrame;

namespace {

ServerConfig keyedServer(const Key& key) {
  ServerConfig config;
  config.bind = kAnyPort;
  config.key = key;
  auto source = std::make_shared<MapFrameSource>();
  config.frameSource = [source](const vt::HandPose& pose, ActuatorFrame& frame) { source->render(pose, frame); };
  return config;
}

ClientConfig keyedClient(const Server& server, std::optional<Key> key, const vt::PoseHistory& poses) {
  ClientConfig config;
  config.server = server.endpoint();
  config.key = key;
  config.poses = &poses;
  config.connectTimeout_ns = 400'000'000;
  return config;
}

/// Resident memory of this process in bytes (Linux /proc).
std::size_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * 4096;
}

/// Streams a slide into `poses` from the calling thread for `count` periods (real time).
void slide(vt::PoseHistory& poses, int count) {
  const auto& clock = vt::SteadyClock::instance();
  std::int64_t next = clock.now_ns();
  for (int i = 0; i < count; ++i, next += kPeriod) {
    clock.sleepUntil(next);
    poses.publish(slidingHand(0.0004f * float(i), 0.01f, clock.now_ns(), std::uint64_t(i + 1)));
  }
}

}  // namespace

TEST_CASE("A keyed session streams authenticated frames both ways") {
  const Key key = generateKey();
  Server server(keyedServer(key));
  server.start();
  vt::PoseHistory poses;
  vt::LatestValue<ActuatorFrame> latest;
  ClientConfig config = keyedClient(server, key, poses);
  config.outputs.add(latest);
  Client client(config);
  poses.publish(slidingHand(0, 0.01f, vt::SteadyClock::instance().now_ns(), 1));
  client.connect();
  slide(poses, 100);
  REQUIRE(eventually([&] { return client.stats().jitter.played > 50; }));
  CHECK(server.stats().posesApplied > 50);
  CHECK(server.stats().rejected == 0);
  CHECK(client.stats().rejected == 0);
  CHECK(client.stats().decodeFailures == 0);
  // Every datagram carries the tag: a tactile frame of 5 perceptual blocks' worth is tag + lean framing.
  CHECK(client.stats().bytesSent / client.stats().datagramsSent <= 200 + kTagSize);
}

TEST_CASE("A wrong or missing key gets no session, and the refusal says why") {
  Server server(keyedServer(generateKey()));
  server.start();
  vt::PoseHistory poses;
  Client wrong(keyedClient(server, generateKey(), poses));
  CHECK_THROWS_WITH(wrong.connect(), Catch::Contains("no authenticated answer") && Catch::Contains("authentication failed"));
  Client plain(keyedClient(server, std::nullopt, poses));
  CHECK_THROWS_WITH(plain.connect(), Catch::Contains("refused") && Catch::Contains("--key"));
  CHECK(server.stats().sessions == 0);
  CHECK(server.rejects().of(DecodeStatus::Unauthentic) >= 2);
  // The other way round: a keyed client and a server without a key.
  ServerConfig open = keyedServer(generateKey());
  open.key.reset();
  Server unkeyed(open);
  unkeyed.start();
  ClientConfig config = keyedClient(unkeyed, generateKey(), poses);
  Client keyed(config);
  CHECK_THROWS_WITH(keyed.connect(), Catch::Contains("no key"));
}

TEST_CASE("The server logs each refused client as it is refused, one line a second at most, counting the rest") {
  std::mutex mutex;
  std::vector<std::string> lines;
  vt::log::setSink([&](vt::log::Level, std::string_view line) {
    const std::lock_guard lock(mutex);
    if (line.find("server: refused") != std::string_view::npos) lines.emplace_back(line);
  });
  const auto count = [&] {
    const std::lock_guard lock(mutex);
    return lines.size();
  };
  Server server(keyedServer(generateKey()));
  server.start();
  vt::PoseHistory poses;
  Client wrong(keyedClient(server, generateKey(), poses));  // retries its hello for 400 ms
  CHECK_THROWS(wrong.connect());
  CHECK(count() == 1);  // at once, not only in the report at exit; the retries within the second are counted
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  Client again(keyedClient(server, generateKey(), poses));
  CHECK_THROWS(again.connect());
  vt::log::setSink({});
  REQUIRE(count() == 2);
  CHECK_THAT(lines[0], Catch::StartsWith("server: refused 127.0.0.1:") && Catch::Contains("authentication failed"));
  CHECK_THAT(lines[1], Catch::Contains("other refusals since the last line"));
  CHECK(server.stats().refused + server.stats().refusalsSuppressed >= 4);
}

TEST_CASE("A replayed hello gets no session: in a loop of 80, or at a restarted server, not even an answer") {
  const Key key = generateKey();
  auto server = std::make_unique<Server>(keyedServer(key));
  server->start();
  const Endpoint at = server->endpoint();
  Transport raw(kAnyPort);
  Hello hello;
  hello.codecCount = 1;
  hello.codecs[0] = std::uint8_t(vt::haptics::CodecId::Perceptual);
  hello.radius_m.fill(0.008f);
  // Captured: the client's first hello (answered with a challenge) and the one with its cookie.
  std::vector<test::SentHello> captured;
  Packet packet;
  REQUIRE(test::rawHandshake(raw, at, hello, packet, &key, &captured));
  REQUIRE(std::holds_alternative<Accept>(packet.message));
  REQUIRE(captured.size() == 2);
  REQUIRE(eventually([&] { return server->stats().sessions == 1; }));
  const auto silence = [&] { return !test::receiveAnswer(raw, captured[0], packet, &key, 100'000'000); };
  // A loop of 80 (the old cache held 64 hellos): each one was taken once, so none is answered.
  for (int i = 0; i < 80; ++i)
    for (const auto& h : captured) raw.send(h.bytes, at);
  CHECK(silence());
  CHECK(server->stats().sessions == 1);
  CHECK(server->rejects().of(DecodeStatus::Replayed) >= 160);
  // A restarted server (a new cookie secret, nothing remembered) on the same address: the hello
  // with a cookie gets nothing; the first hello at most one challenge; neither a session.
  server.reset();
  ServerConfig config = keyedServer(key);
  config.bind = at;
  Server restarted(config);
  restarted.start();
  for (int i = 0; i < 80; ++i) raw.send(captured[1].bytes, at);
  CHECK(silence());
  for (int i = 0; i < 80; ++i) raw.send(captured[0].bytes, at);
  int answers = 0;
  while (test::receiveAnswer(raw, captured[0], packet, &key, 100'000'000)) {
    CHECK(std::holds_alternative<Challenge>(packet.message));
    ++answers;
  }
  CHECK(answers <= 1);
  CHECK(restarted.stats().sessions == 0);
  CHECK(restarted.stats().challenges <= 1);
}

TEST_CASE("A keyless session is held by its token: a blind spoofer can neither end it nor open one") {
  ServerConfig config = keyedServer(generateKey());
  config.key.reset();  // loopback without a key
  Server server(config);
  server.start();
  Transport raw(kAnyPort);
  Hello hello;
  hello.codecCount = 1;
  hello.codecs[0] = std::uint8_t(vt::haptics::CodecId::Perceptual);
  hello.radius_m.fill(0.008f);
  // A hello with a cookie it never received (a spoofed source cannot read the challenge): nothing.
  hello.cookie.fill(0x42);
  Packet packet;
  const test::SentHello guessed = test::sendHello(raw, server.endpoint(), hello);
  CHECK_FALSE(test::receiveAnswer(raw, guessed, packet, nullptr, 200'000'000));
  CHECK(server.stats().sessions == 0);
  hello.cookie = {};
  REQUIRE(test::rawHandshake(raw, server.endpoint(), hello, packet));
  const Accept accept = std::get<Accept>(packet.message);
  REQUIRE(eventually([&] { return server.stats().clientConnected; }));
  StreamContext context;
  context.sessionId = accept.sessionId;
  context.epoch_ns = accept.epoch_ns;
  context.radius_m.fill(0.008f);
  std::array<std::uint8_t, kMaxDatagram> bytes{};
  // Every session byte and many sequences, with a guessed token: the session goes on.
  std::uint64_t sequence = 0;
  for (std::uint32_t session = 0; session < 256; ++session) {
    StreamContext spoofed = context;
    spoofed.sessionId = session;
    spoofed.token = accept.token ^ (std::uint64_t(session + 1) << 13);
    raw.send(std::span(bytes.data(), encodeStream(Bye{}, ++sequence, spoofed, Direction::ClientToServer, bytes)),
             server.endpoint());
  }
  REQUIRE(eventually([&] { return server.rejects().of(DecodeStatus::Unauthentic) >= 1; }));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  CHECK(server.stats().clientConnected);
  // The client itself, with the accept's token, ends it.
  context.token = accept.token;
  raw.send(std::span(bytes.data(), encodeStream(Bye{}, ++sequence, context, Direction::ClientToServer, bytes)),
           server.endpoint());
  CHECK(eventually([&] { return !server.stats().clientConnected; }));
}

TEST_CASE("Off loopback a key is required, and the message says how to make one") {
  ServerConfig config = keyedServer(generateKey());
  config.key.reset();
  config.bind = parseEndpoint("0.0.0.0:0");
  CHECK_THROWS_WITH(Server(config), Catch::Contains("0.0.0.0:0") && Catch::Contains("--key FILE"));
  ClientConfig client;
  client.server = parseEndpoint("10.77.0.1:47800");
  CHECK_THROWS_WITH(Client(client), Catch::Contains("10.77.0.1:47800") && Catch::Contains("--key"));
}

TEST_CASE("A flood of 100k forged datagrams leaves the keyed session running with flat memory and counted rejects") {
  const Key key = generateKey();
  Server server(keyedServer(key));
  server.start();
  vt::PoseHistory poses;
  Client client(keyedClient(server, key, poses));
  poses.publish(slidingHand(0, 0.01f, vt::SteadyClock::instance().now_ns(), 1));
  client.connect();
  slide(poses, 25);
  REQUIRE(eventually([&] { return client.stats().jitter.played > 10; }));
  const std::size_t residentBefore = residentBytes();
  const auto playedBefore = client.stats().jitter.played;
  // Forgeries of every shape from another socket: hellos with bad tags (the authenticated
  // decoder runs on each), stream datagrams, and noise. Poses keep flowing meanwhile.
  constexpr int kForged = 100'000;
  Transport attacker(kAnyPort);
  std::mt19937 rng(9);
  std::array<std::uint8_t, 200> forged{};
  std::atomic<bool> flooding{true};
  std::thread hand([&] {
    const auto& clock = vt::SteadyClock::instance();
    for (std::uint64_t i = 2; flooding.load(); ++i) {
      clock.sleepUntil(clock.now_ns() + kPeriod);
      poses.publish(slidingHand(0.0004f * float(i % 200), 0.01f, clock.now_ns(), i));
    }
  });
  const std::int64_t start = vt::SteadyClock::instance().now_ns();
  for (int i = 0; i < kForged; ++i) {
    for (auto& b : forged) b = std::uint8_t(rng());
    std::size_t size = 20 + rng() % 180;
    if (i % 3 == 0) {  // a keyed hello's shape: magic, version 3, type hello | keyed
      const std::uint8_t head[] = {'V', 'T', 'N', 'P', kProtocolVersion, 0x81};
      std::copy(std::begin(head), std::end(head), forged.begin());
      size = 6 + kNonceSize + 40 + kTagSize;
    } else if (i % 3 == 1) {  // a stream datagram of the session's kind
      forged[0] = 0xC4;
    }
    attacker.send(std::span(forged.data(), size), server.endpoint());
  }
  const double flood_s = double(vt::SteadyClock::instance().now_ns() - start) / 1e9;
  REQUIRE(eventually([&] { return server.stats().datagramsReceived >= std::uint64_t(kForged / 2); }, 5000));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the tail of the flood drains
  flooding.store(false);
  hand.join();
  const ServerStats stats = server.stats();
  const std::size_t residentAfter = residentBytes();
  std::size_t answers = 0;
  std::array<std::uint8_t, kMaxDatagram + 1> reply{};
  Endpoint from;
  while (attacker.receive(reply, from, vt::SteadyClock::instance().now_ns() + 20'000'000) > 0) ++answers;
  WARN("flood: " << kForged << " forged datagrams sent in " << flood_s << " s; server received " << stats.datagramsReceived
                 << ", rejected " << stats.rejected << " (unauthentic " << server.rejects().of(DecodeStatus::Unauthentic)
                 << "), strangers " << stats.strangerPackets << ", refusals sent " << stats.refused << " / suppressed "
                 << stats.refusalsSuppressed << ", answers to the attacker " << answers << "; resident memory "
                 << residentBefore / 1024 << " -> " << residentAfter / 1024 << " KiB; frames played during the flood "
                 << client.stats().jitter.played - playedBefore);
  CHECK(client.stats().connected);
  CHECK(server.stats().clientConnected);
  CHECK(client.stats().jitter.played > playedBefore + 20);  // the stream went on
  // Every forgery the socket delivered is counted (some are lost in the kernel's buffer).
  CHECK(stats.rejected + stats.strangerPackets + stats.refusalsSuppressed >= stats.datagramsReceived - stats.posesApplied - 1000);
  CHECK(server.rejects().of(DecodeStatus::Unauthentic) > std::uint64_t(kForged / 10));
  // No reflection: at most the refusal bucket (5 at once, 5 a second) got an answer.
  CHECK(answers <= 5 + std::size_t(5 * (flood_s + 1.0)));
#if defined(VT_SANITIZER_THREAD) || defined(VT_SANITIZER_ADDRESS)
  // Sanitizer shadow memory grows with every thread's activity: the flat-memory bound is
  // checked in the plain build only.
  (void)residentBefore;
  (void)residentAfter;
#else
  CHECK(residentAfter <= residentBefore + (2u << 20));
#endif
}
