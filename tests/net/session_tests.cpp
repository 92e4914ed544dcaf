// Client and server sessions on loopback. Timing runs on a ManualClock shared by both ends
// (timeouts, keep-alives, reconnection, playout): the tests move time and only wait for the
// other threads to react to it, never for wall time to pass. Poses go lock-step: the test sends
// one, waits for its frame, then advances the clock by one period.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <mutex>
#include <thread>

#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/codec/stream_codec.hpp"
#include "vt/net/client.hpp"
#include "vt/net/map_frame_source.hpp"
#include "vt/net/server.hpp"
#include "session_constants.hpp"
#include "raw_handshake.hpp"
#include "test_support.hpp"

using namespace vt::net;
using vt::test::eventually;
using vt::haptics::ActuatorFrame;
using vt::haptics::CodecId;

namespace {

constexpr std::int64_t kStart = 1'000'000'000;

ServerConfig mapServer(const vt::Clock* clock = nullptr) {
  ServerConfig config;
  config.bind = kAnyPort;
  config.clock = clock;
  auto source = std::make_shared<MapFrameSource>();
  config.frameSource = [source](const vt::HandPose& pose, ActuatorFrame& frame) { source->render(pose, frame); };
  return config;
}

ClientConfig clientOf(const Server& server, CodecId codec, const vt::PoseHistory& poses,
                      const vt::Clock* clock = nullptr) {
  ClientConfig config;
  config.server = server.endpoint();
  config.codecs = {codec};
  config.poses = &poses;
  config.clock = clock;
  config.pacePoses = clock == nullptr;  // a manual clock: the test sends each pose itself
  return config;
}

/// The scripted slide: 0.1 m/s along x, one pose per frame period.
vt::HandPose slidePose(std::uint64_t sequence, std::int64_t t_ns) {
  return slidingHand(0.0004f * float(sequence), 0.01f, t_ns, sequence);
}

/// Lock-step on the manual clock: pose i at kStart + i * period, its frame back before time moves on.
// Poses first..first+count-1 of the slide, one per period on the manual clock, each sent and
// applied before the next; the client then holds every frame the server sent so far (packed or
// longer blocks come back a few frames at a time).
void slideLockStep(vt::ManualClock& clock, vt::PoseHistory& poses, const Server& server, Client& client,
                   std::uint64_t first, int count) {
  const auto sentBefore = server.stats().framesSent, receivedBefore = client.stats().framesReceived;
  for (int i = 0; i < count; ++i) {
    const std::uint64_t s = first + std::uint64_t(i);
    const std::int64_t t = kStart + std::int64_t(s) * kPeriod;
    clock.set(t);
    poses.publish(slidePose(s, t));
    const auto applied = server.stats().posesApplied;
    REQUIRE(client.sendPoseAt(t));
    REQUIRE(eventually([&] {
      return server.stats().posesApplied > applied &&
             client.stats().framesReceived - receivedBefore == server.stats().framesSent - sentBefore;
    }));
    // Time moves on only once the playout has seen this time: every frame due by now has
    // played now, however late the client's threads were scheduled.
    REQUIRE(eventually([&] { return client.stats().playedThrough_ns >= t; }));
  }
}

// A server and a connected client on one manual clock, every frame the client plays recorded;
// `configure` adjusts the client (codec choice, packing, block length) before it connects.
struct RecordedSession {
  RecordedSession(CodecId codec, const std::function<void(ClientConfig&)>& configure,
                  const std::function<void(ServerConfig&)>& configureServer = {})
      // The server is listening before the client (a member after it) is made.
      : server(serverConfig(configureServer)), client((server.start(), clientConfig(codec, configure))) {
    client.connect();
  }
  ServerConfig serverConfig(const std::function<void(ServerConfig&)>& configure) {
    ServerConfig config = mapServer(&clock);
    if (configure) configure(config);
    return config;
  }
  ClientConfig clientConfig(CodecId codec, const std::function<void(ClientConfig&)>& configure) {
    ClientConfig config = clientOf(server, codec, poses, &clock);
    config.outputs.add(recorded);
    configure(config);
    return config;
  }
  vt::ManualClock clock{kStart};
  Server server;
  vt::SpscRing<ActuatorFrame> recorded{1024};
  vt::PoseHistory poses;
  Client client;
};

// A raw client's session: the handshake by hand (one codec, hello `flags`), the stream context from the accept.
StreamContext rawSession(Transport& raw, const Server& server, CodecId codec, std::uint8_t flags, Accept& accept) {
  Hello hello;
  hello.codecCount = 1;
  hello.codecs[0] = std::uint8_t(codec);
  hello.flags = flags;
  hello.client_t_ns = kStart;
  hello.radius_m.fill(0.008f);
  Packet packet;
  REQUIRE(vt::net::test::rawHandshake(raw, server.endpoint(), hello, packet));
  accept = std::get<Accept>(packet.message);
  StreamContext context;
  context.token = accept.token;
  context.sessionId = accept.sessionId;
  context.epoch_ns = accept.epoch_ns;
  context.actuatorCount = accept.actuatorCount;
  context.radius_m.fill(0.008f);
  return context;
}

// The slide's poses of these sequences from a raw client, each at its time on the manual clock
// and applied by the server before the next.
void sendRawPoses(vt::ManualClock& clock, Transport& raw, const Server& server, StreamContext& context,
                  std::initializer_list<std::uint64_t> sequences) {
  std::array<std::uint8_t, kMaxDatagram + 1> bytes{};
  std::uint64_t datagram = 0;
  for (const std::uint64_t s : sequences) {
    const std::int64_t t = kStart + std::int64_t(s) * kPeriod;
    clock.set(t);
    const Pose pose{s, slidePose(s, t)};
    raw.send(std::span(bytes.data(), encodeStream(pose, ++datagram, context, Direction::ClientToServer, bytes)),
             server.endpoint());
    REQUIRE(eventually([&] { return server.stats().posesApplied == datagram; }));
  }
}

// Advances the manual clock a period at a time (at most `periods`) until the client has played
// `frames` frames.
void playOut(vt::ManualClock& clock, const Client& client, std::uint64_t frames, int periods) {
  for (int i = 0; i < periods && client.stats().jitter.played < frames; ++i) {
    const auto played = client.stats().jitter.played;
    clock.advance(kPeriod);
    const std::int64_t t = clock.now_ns();
    eventually([&] { return client.stats().playedThrough_ns >= t && client.stats().jitter.played > played; }, 200);
  }
}

bool silentBlocks(const ActuatorFrame& frame) {
  for (const auto& block : frame.block)
    for (float v : block)
      if (v != 0.0f) return false;
  return true;
}

}  // namespace

TEST_CASE("A loopback session reproduces the single-process actuator signal on time") {
  for (CodecId codec : {CodecId::RawFloat32, CodecId::Perceptual}) {
    for (int blocks : {1, 4}) {
      RecordedSession session(codec, [&](ClientConfig& config) { config.blocksPerDatagram = blocks; });
      auto& [clock, server, recorded, poses, client] = session;
      CHECK(client.session().codec == std::uint8_t(codec));
      CHECK(client.session().blocksPerDatagram == blocks);
      constexpr int kPoses = 120;
      slideLockStep(clock, poses, server, client, 1, kPoses);
      playOut(clock, client, kPoses, 10);
      INFO("codec " << vt::haptics::codecName(codec) << " blocks " << blocks << " lost " << client.stats().jitter.lost
                    << " late " << client.stats().jitter.late << " concealed " << client.stats().jitter.concealed);
      CHECK(client.stats().jitter.played == kPoses);
      client.disconnect();

      // The single-process run: the same renderer on the same poses as the wire carries them.
      MapFrameSource reference;
      std::map<std::uint64_t, ActuatorFrame> expected;
      for (std::uint64_t s = 1; s <= kPoses; ++s)
        reference.render(slidePose(s, kStart + std::int64_t(s) * kPeriod), expected[s]);
      ActuatorFrame frame;
      int compared = 0, matched = 0;
      double signal = 0, noise = 0;
      while (recorded.pop(frame)) {
        const auto it = expected.find(frame.sequence);
        if (it == expected.end() || frame.pose_t_ns == 0) continue;
        ++compared;
        double frameSignal = 0, frameNoise = 0;
        for (int a = 0; a < 5; ++a)
          for (int i = 0; i < 32; ++i) {
            const double ref = it->second.block[std::size_t(a)][std::size_t(i)];
            const double d = ref - frame.block[std::size_t(a)][std::size_t(i)];
            frameSignal += ref * ref;
            frameNoise += d * d;
          }
        // Raw: only the pose quantisation (0.02 mm steps) separates the two.
        matched += frameNoise <= frameSignal * (codec == CodecId::RawFloat32 ? 1e-3 : 0.1) ? 1 : 0;
        signal += frameSignal;
        noise += frameNoise;
      }
      const auto stats = client.stats();
      INFO("codec " << vt::haptics::codecName(codec) << " blocks " << blocks << ": compared " << compared << " matched "
                    << matched << " late " << stats.jitter.late);
      CHECK(compared == kPoses);  // lock-step on one clock: every frame plays on time
      CHECK(matched == compared);
      CHECK(10.0 * std::log10(signal / std::max(noise, 1e-30)) >= 20.0);
      CHECK(stats.decodeFailures == 0);
      CHECK(server.stats().posesApplied == kPoses);
      // Latency on one clock: the pose's time to its playout, which is the next period (the
      // clock moves in periods) plus, packed, the wait for the datagram's last block.
      const auto latencies = client.latencies();
      REQUIRE(latencies.size() == std::size_t(kPoses));
      std::vector<std::int64_t> sorted = latencies;
      std::sort(sorted.begin(), sorted.end());
      INFO("latency " << sorted.front() << " .. " << sorted.back() << " ns, median " << sorted[sorted.size() / 2]);
      CHECK(sorted.front() >= kPeriod);
      const int packed = codec == CodecId::RawFloat32 ? std::min(blocks, 2) : blocks;  // 2 raw blocks fill a datagram
      // One clock, and time moves on only once the playout has seen it: every frame plays within
      // the packing wait plus the next period, however the threads were scheduled.
      CHECK(sorted[sorted.size() / 2] >= kPeriod * packed);
      CHECK(sorted.back() <= kPeriod * (packed + 1));
    }
  }
}

TEST_CASE("The codec block length is negotiated: granted as asked, or refused naming both") {
  vt::PoseHistory poses;
  Server any(mapServer());  // block_ms 0: whichever the client asks for
  any.start();
  ClientConfig asked = clientOf(any, CodecId::Perceptual, poses);
  asked.block_ms = 16;
  Client sixteen(asked);
  sixteen.connect();
  CHECK(sixteen.session().block_ms == 16);
  sixteen.disconnect();
  REQUIRE(eventually([&] { return !any.stats().clientConnected; }));
  // Raw float32 blocks of 128 ms (20 kB) cannot travel in one datagram: refused, saying so.
  ClientConfig raw = clientOf(any, CodecId::RawFloat32, poses);
  raw.block_ms = 128;
  Client tooBig(raw);
  CHECK_THROWS_WITH(tooBig.connect(), Catch::Contains("raw-f32 blocks of 128 ms") && Catch::Contains("perceptual"));
  // Offered both, the server takes the one whose block fits.
  raw.codecs = {CodecId::RawFloat32, CodecId::Perceptual};
  Client fallback(raw);
  fallback.connect();
  CHECK(fallback.session().codec == std::uint8_t(CodecId::Perceptual));
  CHECK(fallback.session().block_ms == 128);
  fallback.disconnect();

  ServerConfig pinned = mapServer();
  pinned.block_ms = 4;
  Server fixed(pinned);
  fixed.start();
  ClientConfig other = clientOf(fixed, CodecId::Perceptual, poses);
  other.block_ms = 16;
  Client refused(other);
  CHECK_THROWS_WITH(refused.connect(), Catch::Contains("16 ms asked") && Catch::Contains("streams 4 ms"));
  CHECK(fixed.stats().refused == 1);
  other.block_ms = 4;
  Client matching(other);
  CHECK_NOTHROW(matching.connect());
  other.block_ms = 12;
  CHECK_THROWS_WITH(Client(other), Catch::Contains("12 ms"));
  pinned.block_ms = 12;
  CHECK_THROWS_WITH(Server(pinned), Catch::Contains("12 ms"));
}

TEST_CASE("Loopback sessions of 16 and 128 ms blocks reproduce the locally rendered signal within the codec's SNR") {
  for (const auto& [codec, block_ms] : {std::pair{CodecId::Perceptual, 16}, std::pair{CodecId::Pcm16, 16},
                                        std::pair{CodecId::Perceptual, 128}}) {
    const int frames = block_ms / 4;
    RecordedSession session(codec, [length = block_ms](ClientConfig& config) { config.block_ms = length; });
    auto& [clock, server, recorded, poses, client] = session;
    REQUIRE(client.session().block_ms == block_ms);
    constexpr int kPoses = 256;  // whole blocks at both lengths
    slideLockStep(clock, poses, server, client, 1, kPoses);
    CHECK(server.stats().framesSent == kPoses);  // whole blocks only
    playOut(clock, client, kPoses, frames + 10);  // the last block plays out
    client.disconnect();
    INFO(vt::haptics::codecName(codec) << " " << block_ms << " ms: lost " << client.stats().jitter.lost << " late "
                                       << client.stats().jitter.late);
    CHECK(client.stats().jitter.played == kPoses);
    CHECK(client.stats().decodeFailures == 0);
    // Upstream payload: the pose bodies alone (the datagrams add a 4-byte header).
    CHECK(client.stats().poseBytes >= kPoses * 100);
    CHECK(client.stats().poseBytes + kPoses * kStreamHeaderSize <= client.stats().bytesSent);

    // The single-process run, and the same codec applied to it locally: the wire may not add noise.
    MapFrameSource reference;
    std::map<std::uint64_t, ActuatorFrame> expected;
    for (std::uint64_t s = 1; s <= kPoses; ++s) reference.render(slidePose(s, kStart + std::int64_t(s) * kPeriod), expected[s]);
    auto encoder = vt::haptics::makeBlockEncoder({codec, 50, 5, 8000, 32, block_ms});
    auto decoder = vt::haptics::makeBlockDecoder({codec, 50, 5, 8000, 32, block_ms});
    std::map<std::uint64_t, vt::haptics::WaveBlock> local;
    for (std::uint64_t s = 1; s <= kPoses; ++s) {
      if (!encoder->push(expected[s].block)) continue;
      REQUIRE(decoder->decode(encoder->packet()));
      for (int f = 0; f < frames; ++f) local[s - std::uint64_t(frames - 1 - f)] = decoder->frame(f);
    }
    const auto snr = [](double signal, double noise) { return 10.0 * std::log10(signal / std::max(noise, 1e-30)); };
    double signal = 0, wireNoise = 0, localNoise = 0;
    int compared = 0;
    ActuatorFrame frame;
    while (recorded.pop(frame)) {
      const auto it = expected.find(frame.sequence);
      if (it == expected.end() || frame.pose_t_ns == 0) continue;
      ++compared;
      for (std::size_t a = 0; a < 5; ++a)
        for (std::size_t i = 0; i < 32; ++i) {
          const double ref = it->second.block[a][i];
          signal += ref * ref;
          wireNoise += (ref - frame.block[a][i]) * (ref - frame.block[a][i]);
          localNoise += (ref - local[frame.sequence][a][i]) * (ref - local[frame.sequence][a][i]);
        }
    }
    INFO("wire SNR " << snr(signal, wireNoise) << " dB, local codec " << snr(signal, localNoise) << " dB");
    CHECK(compared == kPoses);
    CHECK(snr(signal, localNoise) >= 20.0);
    // Only the pose quantisation (0.02 mm steps, ~90 dB here) separates the wire's input from the local one.
    CHECK(snr(signal, wireNoise) >= std::min(snr(signal, localNoise) - 1.0, 60.0));
    // A frame plays once its whole block has arrived: the first frame of a block waits for the last pose.
    const auto latencies = client.latencies();
    REQUIRE(latencies.size() == std::size_t(kPoses));
    CHECK(*std::max_element(latencies.begin(), latencies.end()) >= kPeriod * frames);
  }
}

TEST_CASE("The server renders lost poses' blocks from the hand interpolated across the gap") {
  vt::ManualClock clock(kStart);
  std::vector<std::pair<std::int64_t, float>> blocks;  // (time, index tip x) of each block rendered
  std::mutex blocksMutex;  // written by the server's network thread, read here
  ServerConfig config = mapServer(&clock);
  config.frameSource = [&](const vt::HandPose& pose, ActuatorFrame& frame) {
    const std::lock_guard lock(blocksMutex);
    blocks.push_back({pose.t_ns, pose.at(vt::HandJoint::IndexTip).x});
    frame = ActuatorFrame::silent(5, 0);
    frame.blockLength = 32;
    frame.sampleRate_hz = 8000;
  };
  Server server(config);
  server.start();
  // A raw client: poses 1, 2, 3, 6, 7 (4 and 5 lost on the way).
  Transport raw(kAnyPort);
  Accept accept;
  StreamContext context = rawSession(raw, server, CodecId::RawFloat32, 0, accept);
  sendRawPoses(clock, raw, server, context, {1, 2, 3, 6, 7});
  CHECK(server.stats().gapTicks == 2);
  const auto rendered = [&] {
    const std::lock_guard lock(blocksMutex);
    return blocks;
  }();
  REQUIRE(rendered.size() == 7);  // one block per sequence number, the lost ones included
  // The gap's blocks: at the missing poses' times, the hand a third and two thirds of the way.
  const float x3 = rendered[2].second, x6 = rendered[5].second;
  CHECK(rendered[3].first - rendered[2].first == kPeriod);
  CHECK(rendered[4].first - rendered[3].first == kPeriod);
  CHECK(rendered[3].second == Approx(x3 + (x6 - x3) / 3.0f).margin(1e-5));
  CHECK(rendered[4].second == Approx(x3 + 2.0f * (x6 - x3) / 3.0f).margin(1e-5));
  // The received poses' frames come back; the gap's would reach the client after their slots
  // (it conceals them), so at one frame per block they are rendered but not sent.
  std::vector<std::uint64_t> sequences;
  std::array<std::uint8_t, kMaxDatagram + 1> bytes{};
  Endpoint from;
  std::size_t size = 0;
  Packet packet;
  const auto now = [] { return vt::SteadyClock::instance().now_ns(); };
  context.receiving = Direction::ServerToClient;
  while ((size = raw.receive(bytes, from, now() + 200'000'000)) > 0 && sequences.size() < 5) {
    if (decodeStream(std::span(bytes.data(), size), context, packet) != DecodeStatus::Ok) continue;
    if (const auto* tactile = std::get_if<Tactile>(&packet.message)) sequences.push_back(tactile->firstSequence);
  }
  CHECK(sequences == std::vector<std::uint64_t>{1, 2, 3, 6, 7});
}

TEST_CASE("With redundancy each datagram carries the block before its newest, a lost pose's block waits for the next") {
  vt::ManualClock clock(kStart);
  ServerConfig config = mapServer(&clock);
  Server server(config);
  server.start();
  Transport raw(kAnyPort);
  Accept accept;
  StreamContext context = rawSession(raw, server, CodecId::Pcm16, kHelloRedundancy, accept);
  sendRawPoses(clock, raw, server, context, {1, 2, 3, 6, 7});  // poses 4 and 5 lost on the way
  // (first sequence, blocks) of each tactile datagram: the first alone, then each new block after
  // the one sent before it; the gap's blocks (4, 5) go with pose 6's, which carries no copy.
  std::vector<std::pair<std::uint64_t, int>> datagrams;
  std::vector<float> firstSamples;  // actuator 1's first sample of each block, in datagram order
  context.receiving = Direction::ServerToClient;
  std::array<std::uint8_t, kMaxDatagram + 1> bytes{};
  Packet packet;
  const auto decoder = vt::haptics::makeBlockDecoder({.id = CodecId::Pcm16,
                                                      .channels = accept.actuatorCount,
                                                      .sampleRate_hz = int(accept.sampleRate_hz),
                                                      .frameLength = accept.blockLength,
                                                      .block_ms = accept.block_ms});
  Endpoint from;
  std::size_t size = 0;
  const auto now = [] { return vt::SteadyClock::instance().now_ns(); };
  while (datagrams.size() < 5 && (size = raw.receive(bytes, from, now() + 200'000'000)) > 0) {
    if (decodeStream(std::span(bytes.data(), size), context, packet) != DecodeStatus::Ok) continue;
    const auto* tactile = std::get_if<Tactile>(&packet.message);
    if (!tactile) continue;
    datagrams.push_back({tactile->firstSequence, tactile->blockCount});
    for (int b = 0; b < tactile->blockCount; ++b) {
      REQUIRE(decoder->decode(tactile->block(b)));
      firstSamples.push_back(decoder->frame(0)[1][0]);
    }
  }
  CHECK(datagrams == std::vector<std::pair<std::uint64_t, int>>{{1, 1}, {1, 2}, {2, 2}, {4, 3}, {6, 2}});
  // A block sent again is the block sent before, byte for byte in what it decodes to.
  REQUIRE(firstSamples.size() == 10);
  CHECK(firstSamples[1] == firstSamples[0]);  // block 1
  CHECK(firstSamples[3] == firstSamples[2]);  // block 2
  CHECK(firstSamples[8] == firstSamples[7]);  // block 6
  const ServerStats stats = server.stats();
  CHECK(stats.framesSent == 7);
  CHECK(stats.blocksResent == 3);
}

TEST_CASE("With redundancy on a lossy link only back-to-back losses are concealed, one block period later") {
  std::array<std::uint64_t, 2> concealed{}, dropped{};
  std::array<std::int64_t, 2> latency{};
  constexpr int kPoses = 500;
  for (const bool redundancy : {false, true}) {
    // No keep-alives: each step's datagrams are then exactly the pose's frames.
    constexpr std::int64_t kNever = std::int64_t(1) << 60;
    RecordedSession session(
        CodecId::Pcm16,
        [&](ClientConfig& config) {
          config.redundancy = redundancy;
          config.impairment.loss = 0.1;
          config.impairment.seed = 11;
          config.keepAlive_ns = kNever;
        },
        [&](ServerConfig& config) { config.keepAlive_ns = kNever; });
    // References, not a structured binding: the lambdas below capture them (clang 14 cannot
    // capture structured bindings).
    vt::ManualClock& clock = session.clock;
    Server& server = session.server;
    vt::PoseHistory& poses = session.poses;
    Client& client = session.client;
    // The session opens with a keep-alive each way (the client's, answered, and the server's
    // first clock sample): two datagrams to the client, kept or dropped. Counted here, they
    // cannot later pass for a pose's datagram, which would then arrive after time moved on and
    // shift the jitter buffer's base by a period. (The drop count also holds drops during the
    // handshake; with this seed none happens there, so the two counted are the opening ones.)
    REQUIRE(eventually([&] {
      const ClientStats c = client.stats();
      return c.keepAlives + c.datagramsDropped >= 2;
    }));
    for (std::uint64_t s = 1; s <= std::uint64_t(kPoses); ++s) {
      const std::int64_t t = kStart + std::int64_t(s) * kPeriod;
      clock.set(t);
      poses.publish(slidePose(s, t));
      const auto applied = server.stats().posesApplied;
      const ClientStats before = client.stats();
      REQUIRE(client.sendPoseAt(t));
      // Time moves on once the pose's frame has reached the client, or its datagram was dropped on
      // the way (with keep-alives off it is the only datagram a step sends).
      ClientStats c;
      const bool arrived = eventually([&] {
        c = client.stats();
        return server.stats().posesApplied > applied &&
               (c.framesReceived > before.framesReceived || c.datagramsDropped > before.datagramsDropped);
      });
      INFO("pose " << s << ": client frames " << c.framesReceived << " dropped " << c.datagramsDropped << " (before "
                   << before.framesReceived << " / " << before.datagramsDropped << "), connected " << c.connected);
      REQUIRE(arrived);
      REQUIRE(eventually([&] { return client.stats().playedThrough_ns >= t; }));
    }
    playOut(clock, client, kPoses, 10);
    const ClientStats stats = client.stats();
    concealed[redundancy] = stats.jitter.lost;
    dropped[redundancy] = stats.datagramsDropped;
    const auto latencies = client.latencies();
    REQUIRE(!latencies.empty());
    std::vector<std::int64_t> sorted = latencies;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
    latency[redundancy] = sorted[sorted.size() / 2];
    client.disconnect();
  }
  INFO("lost slots without / with redundancy " << concealed[0] << " / " << concealed[1] << " of " << kPoses
                                                << ", datagrams dropped " << dropped[0] << " / " << dropped[1]);
  // About 10 % of the datagrams are dropped either way; without redundancy each is a lost slot,
  // with it only a block whose two datagrams were both dropped (about 1 %).
  CHECK(dropped[0] >= 25);
  CHECK(dropped[1] >= 25);
  CHECK(concealed[0] >= dropped[0] * 8 / 10);
  CHECK(concealed[1] <= std::max<std::uint64_t>(2, dropped[1] / 4));
  // The price: one block period more between a pose and its frame played.
  INFO("median latency without / with " << latency[0] << " / " << latency[1] << " ns");
  CHECK(latency[1] - latency[0] == Approx(double(kPeriod)).margin(1'000'000));
}

TEST_CASE("A second client is refused with a reason while the first is connected") {
  Server server(mapServer());
  server.start();
  vt::PoseHistory poses;
  Client first(clientOf(server, CodecId::Pcm16, poses));
  first.connect();
  vt::HandPose hand = slidePose(1, vt::SteadyClock::instance().now_ns());
  poses.publish(hand);  // the first client's poses confirm its session
  REQUIRE(eventually([&] { return server.stats().posesApplied > 0; }));
  Client second(clientOf(server, CodecId::Pcm16, poses));
  CHECK_THROWS_WITH(second.connect(), Catch::Contains("busy"));
  CHECK(server.stats().refused >= 1);
  first.disconnect();
  // The slot is free again after the first client's bye.
  REQUIRE(eventually([&] { return !server.stats().clientConnected; }));
  Client third(clientOf(server, CodecId::Pcm16, poses));
  CHECK_NOTHROW(third.connect());
  CHECK(server.stats().sessions == 2);
}

TEST_CASE("A client showing another scene is refused and one without a scene is accepted") {
  ServerConfig config = mapServer();
  config.sceneDigest = 0xaaaa;
  config.sceneName = "dataset assets/dataset (8 objects)";
  Server server(config);
  server.start();
  vt::PoseHistory poses;
  ClientConfig other = clientOf(server, CodecId::Pcm16, poses);
  other.sceneDigest = 0xbbbb;
  Client mismatched(other);
  CHECK_THROWS_WITH(mismatched.connect(), Catch::Contains("scene mismatch") && Catch::Contains("assets/dataset"));
  ClientConfig same = clientOf(server, CodecId::Pcm16, poses);
  same.sceneDigest = 0xaaaa;
  Client matching(same);
  REQUIRE_NOTHROW(matching.connect());
  CHECK(matching.session().sceneDigest == 0xaaaa);
  matching.disconnect();
  REQUIRE(eventually([&] { return !server.stats().clientConnected; }));
  Client headless(clientOf(server, CodecId::Pcm16, poses));  // digest 0: nothing shown to compare
  CHECK_NOTHROW(headless.connect());
}

TEST_CASE("A silent client times out on the server's clock and a talking one stays") {
  vt::ManualClock clock(kStart);
  ServerConfig config = mapServer(&clock);
  config.timeout_ns = 150'000'000;
  // The client answers the server's keep-alives (clock-offset samples), which counts as hearing
  // it: only the first exchange, at the session's start, happens within this test's clock.
  config.keepAlive_ns = 10'000'000'000;
  Server server(config);
  server.start();
  vt::PoseHistory poses;
  {
    ClientConfig clientConfig = clientOf(server, CodecId::Perceptual, poses, &clock);
    clientConfig.keepAlive_ns = 10'000'000'000;  // never again: the client goes silent
    clientConfig.timeout_ns = 10'000'000'000;
    Client client(clientConfig);
    client.connect();
    // Hello, the client's first keep-alive, and its answer to the server's: then silence.
    // (Two hellos: the first gets the server's challenge.)
    REQUIRE(eventually([&] { return client.stats().keepAlives >= 1 && server.stats().datagramsReceived >= 4; }));
    CHECK(server.stats().clientConnected);
    clock.advance(100'000'000);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the server's thread sees 100 ms: not yet
    CHECK(server.stats().timeouts == 0);
    clock.advance(60'000'000);
    REQUIRE(eventually([&] { return server.stats().timeouts == 1; }));
    CHECK_FALSE(server.stats().clientConnected);
    // The server said bye: the client learns its session is over.
    REQUIRE(eventually([&] { return client.stats().serverSaidBye; }));
  }
  // A client whose keep-alives go out every 30 ms of the clock stays past the timeout.
  ClientConfig livelyConfig = clientOf(server, CodecId::Perceptual, poses, &clock);
  livelyConfig.keepAlive_ns = 30'000'000;
  Client keepsTalking(livelyConfig);
  keepsTalking.connect();
  for (int i = 0; i < 14; ++i) {  // 420 ms
    const auto heard = server.stats().datagramsReceived;
    clock.advance(30'000'000);
    REQUIRE(eventually([&] { return server.stats().datagramsReceived > heard; }));
  }
  CHECK(server.stats().clientConnected);
  CHECK(server.stats().timeouts == 1);
  CHECK(keepsTalking.stats().keepAlives > 0);
}

TEST_CASE("The client reports the round-trip time while poses flow, and the server a clock offset") {
  Server server(mapServer());
  server.start();
  vt::PoseHistory poses;
  ClientConfig config = clientOf(server, CodecId::Perceptual, poses);
  config.keepAlive_ns = 20'000'000;
  Client client(config);
  const auto& clock = vt::SteadyClock::instance();
  poses.publish(slidePose(1, clock.now_ns()));
  client.connect();
  // The sender thread streams poses (the history predicts the held hand forward).
  for (int i = 2; i < 60; ++i) {
    clock.sleepUntil(clock.now_ns() + kPeriod);
    poses.publish(slidePose(std::uint64_t(i), clock.now_ns()));
  }
  REQUIRE(eventually([&] { return client.stats().posesSent > 40 && server.stats().rtt_ns > 0; }));
  const auto stats = client.stats();
  CHECK(stats.rtt_ns > 0);
  CHECK(stats.rtt_ns < 100'000'000);
  // One clock on both ends: the measured offset is within the round trip of zero.
  CHECK(std::abs(server.stats().clockOffset_ns) <= server.stats().rtt_ns);
}

TEST_CASE("A reconnecting client resumes with a restarted server and refuses another stream format") {
  vt::ManualClock clock(kStart);
  auto server = std::make_unique<Server>(mapServer(&clock));
  server->start();
  const Endpoint address = server->endpoint();
  vt::PoseHistory poses;
  ClientConfig config = clientOf(*server, CodecId::Perceptual, poses, &clock);
  config.reconnect = true;
  config.reconnectInterval_ns = 50'000'000;
  Client client(config);
  client.connect();
  const std::uint32_t firstSession = client.session().sessionId;
  slideLockStep(clock, poses, *server, client, 1, 20);
  server.reset();  // says bye: the session is over
  REQUIRE(eventually([&] { return !client.stats().connected; }));
  CHECK_FALSE(client.sendPoseAt(clock.now_ns()));
  // A new server on the same address: the client's hellos (every 50 ms of its clock) find it.
  ServerConfig again = mapServer(&clock);
  again.bind = address;
  server = std::make_unique<Server>(again);
  server->start();
  clock.advance(60'000'000);
  REQUIRE(eventually([&] { return client.stats().connected; }));
  CHECK(client.stats().reconnects == 1);
  CHECK(client.session().sessionId == 1);  // the new server's first session
  CHECK(firstSession == 1);
  const auto before = client.stats().framesReceived;
  slideLockStep(clock, poses, *server, client, 100, 20);
  CHECK(client.stats().framesReceived == before + 20);
  // A server streaming another format (3 actuators) is not resumed with.
  server.reset();
  REQUIRE(eventually([&] { return !client.stats().connected; }));
  ServerConfig otherFormat = mapServer(&clock);
  otherFormat.bind = address;
  otherFormat.actuatorCount = 3;
  server = std::make_unique<Server>(otherFormat);
  server->start();
  clock.advance(60'000'000);
  REQUIRE(eventually([&] { return server->stats().sessions >= 1; }));
  const auto heard = server->stats().datagramsReceived;
  clock.advance(60'000'000);
  REQUIRE(eventually([&] { return server->stats().datagramsReceived > heard; }));  // it keeps asking
  CHECK_FALSE(client.stats().connected);
  CHECK(client.stats().reconnects == 1);
}

TEST_CASE("Actuator output returns to zero when the stream stops") {
  vt::ManualClock clock(kStart);
  Server server(mapServer(&clock));
  server.start();
  vt::LatestValue<ActuatorFrame> latest;
  vt::PoseHistory poses;
  ClientConfig config = clientOf(server, CodecId::Perceptual, poses, &clock);
  config.outputs.add(latest);
  Client client(config);
  client.connect();
  slideLockStep(clock, poses, server, client, 1, 50);
  clock.advance(kPeriod);
  ActuatorFrame frame;
  REQUIRE(eventually([&] { return latest.read(frame) && !silentBlocks(frame); }));
  // Poses stop (the hand still touches): within the hold + fade time the output is zero.
  for (int i = 0; i < 6; ++i) {
    const auto concealed = client.stats().framesConcealed;  // before the clock moves: the slot may be concealed at once
    clock.advance(kPeriod);
    REQUIRE(eventually([&] { return client.stats().framesConcealed > concealed; }));
  }
  REQUIRE(latest.read(frame));
  CHECK(silentBlocks(frame));
  CHECK(client.stats().jitter.depth == 0);
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
  std::size_t size = encodeHandshake(hello, bytes);
  bytes[4] = 9;  // version 9
  raw.send(std::span(bytes.data(), size), server.endpoint());
  const auto now = [] { return vt::SteadyClock::instance().now_ns(); };
  Endpoint from;
  size = raw.receive(bytes, from, now() + 2'000'000'000);
  Packet reply;
  REQUIRE(decodeHandshake(std::span(bytes.data(), size), reply) == DecodeStatus::Ok);
  REQUIRE(std::holds_alternative<Refuse>(reply.message));
  CHECK(std::get<Refuse>(reply.message).reason == RefuseReason::Version);
  CHECK(std::get<Refuse>(reply.message).message().find("version 4") != std::string_view::npos);
  CHECK(server.rejects().of(DecodeStatus::UnknownVersion) == 1);
  CHECK(server.rejects().total() >= 1);
  // A version-2 or -3 client's hello is answered in its own layout, naming both versions.
  for (const int version : {2, 3}) {
    size = encodeLegacyRefuse("x", bytes, version);  // any datagram of that version will do as the hello
    bytes[5] = 1;
    raw.send(std::span(bytes.data(), size), server.endpoint());
    size = raw.receive(bytes, from, now() + 2'000'000'000);
    REQUIRE(size > 0);
    CHECK(handshakeVersion(std::span(bytes.data(), size)) == version);
    CHECK(legacyRefuseText(std::span(bytes.data(), size)).find("version 4, this client version 3 or older") !=
          std::string_view::npos);
  }
  // Stream traffic from a stranger (the garbage above too) is ignored and counted.
  StreamContext context;
  raw.send(std::span(bytes.data(), encodeStream(KeepAlive{false, 1, 0, 0}, 1, context, Direction::ClientToServer, bytes)),
           server.endpoint());
  REQUIRE(eventually([&] { return server.stats().strangerPackets == 2; }));
  Hello unknownCodec;
  unknownCodec.codecCount = 1;
  unknownCodec.codecs[0] = 77;
  REQUIRE(vt::net::test::rawHandshake(raw, server.endpoint(), unknownCodec, reply));
  REQUIRE(std::holds_alternative<Refuse>(reply.message));
  CHECK(std::get<Refuse>(reply.message).reason == RefuseReason::NoCommonCodec);
}

TEST_CASE("A v4 client names both versions when an older server answers") {
  // An old server's refusal as it sends one: the version-2 layout.
  Transport oldServer(kAnyPort);
  vt::PoseHistory poses;
  ClientConfig config;
  config.server = oldServer.localEndpoint();
  config.poses = &poses;
  Client client(config);
  std::thread answer([&] {
    std::array<std::uint8_t, kMaxDatagram + 1> bytes{};
    Endpoint from;
    if (oldServer.receive(bytes, from, vt::SteadyClock::instance().now_ns() + 2'000'000'000) == 0) return;
    const std::size_t size = encodeLegacyRefuse("unsupported protocol version (server speaks 2)", bytes);
    oldServer.send(std::span(bytes.data(), size), from);
  });
  CHECK_THROWS_WITH(client.connect(), Catch::Contains("version 2") && Catch::Contains("version 4"));
  answer.join();
}

TEST_CASE("Connecting to nothing fails with a clear error") {
  ClientConfig config;
  config.server = parseEndpoint("127.0.0.1:9");  // discard port: nobody answers
  config.connectTimeout_ns = 300'000'000;
  Client client(config);
  CHECK_THROWS_WITH(client.connect(), Catch::Contains("no answer") && Catch::Contains("127.0.0.1:9"));
}
