// vt_bench net [--json] [--quick]: tactile codec figures (key "codec": rate-distortion curves
// with SNR and SPQI on signals near the priors' training families and on held-out recordings,
// next to the MPEG haptics reference model on the same samples; codec_bench.cpp), and
// end-to-end motion-to-vibration
// latency (the time a pose describes -> the actuator frame rendered for it leaving the client's
// jitter buffer) over loopback UDP for raw float32, 16-bit PCM and the perceptual codec, at 0 %
// and 5 % injected loss (the 5 % case also has 1 ms jitter and 1 % reordering, both
// directions), keyed and with several blocks per datagram; for each, the bytes on the wire per
// second and direction (datagrams + 28 bytes of IP/UDP each) next to the payload (codec data
// down, pose bodies up); also 16 and 128 ms codec blocks.
// Figures are quoted in docs/PERFORMANCE.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <optional>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench.hpp"
#include "codec_figures.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/log.hpp"
#include "vt/core/realtime.hpp"
#include "vt/haptics/codec/test_signals.hpp"
#include "vt/net/client.hpp"
#include "vt/net/map_frame_source.hpp"
#include "vt/net/server.hpp"
#include "vt/scene/pose_history.hpp"

namespace {

using namespace vt;
using haptics::CodecId;

constexpr int kRate = 8000;
constexpr int kBlock = 32;

double percentile(std::vector<std::int64_t> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return double(v[std::size_t(p * double(v.size() - 1))]) / 1e6;
}

struct LatencyRun {
  double p50_ms = 0, p99_ms = 0, max_ms = 0;
  double downWire_kbps = 0, downPayload_kbps = 0;  // wire: IP/UDP included; payload: codec data only
  double upWire_kbps = 0, upPayload_kbps = 0;      // payload: the pose bodies (no header, tag or keep-alives)
  double downBytesPerDatagram = 0, upBytesPerDatagram = 0;        // datagram sizes without IP/UDP
  std::uint64_t sent = 0, played = 0, concealed = 0, lost = 0, late = 0;
  double targetDelay_ms = 0;
  bool stuck = false;  // output not silent 200 ms after the stream stopped
  bool realtime = false;  // every thread got the SCHED_FIFO priority asked for
};

/// The priority `vtouching client` and `serve` ask for on their network and pose threads.
constexpr int kNetworkPriority = 20;

struct Case {
  const char* label;
  CodecId codec;
  double loss;
  int priority;
  bool keyed = false;
  int blocksPerDatagram = 1;
  int block_ms = 4;
};

LatencyRun measureLatency(const Case& c, double seconds) {
  net::Impairment impairment;
  if (c.loss > 0) {
    impairment.loss = c.loss;
    impairment.jitter_ns = 1'000'000;
    impairment.reorder = 0.01;
  }
  const std::optional<net::Key> key = c.keyed ? std::optional(net::generateKey()) : std::nullopt;
  net::ServerConfig serverConfig;
  serverConfig.bind = net::parseEndpoint("127.0.0.1:0");
  serverConfig.impairment = impairment;
  serverConfig.impairment.seed = 11;
  serverConfig.realtimePriority = c.priority;
  serverConfig.key = key;
  auto source = std::make_shared<net::MapFrameSource>();
  serverConfig.frameSource = [source](const HandPose& pose, haptics::ActuatorFrame& frame) { source->render(pose, frame); };
  net::Server server(serverConfig);
  server.start();

  // The scripted slide: five fingertips across the texture at 0.1 m/s, published at 1 kHz like
  // the headless client's input; the client's sender samples it once per block.
  PoseHistory poses;
  const auto& clock = SteadyClock::instance();
  poses.publish(net::slidingHand(0.0f, 0.01f, clock.now_ns(), 1));
  LatestValue<haptics::ActuatorFrame> output;
  net::ClientConfig clientConfig;
  clientConfig.server = server.endpoint();
  clientConfig.codecs = {c.codec};
  clientConfig.impairment = impairment;
  clientConfig.impairment.seed = 12;
  clientConfig.outputs.add(output);
  clientConfig.realtimePriority = c.priority;
  clientConfig.key = key;
  clientConfig.blocksPerDatagram = c.blocksPerDatagram;
  clientConfig.block_ms = c.block_ms;
  clientConfig.poses = &poses;
  net::Client client(clientConfig);
  client.connect();
  const std::int64_t start = clock.now_ns();
  for (std::int64_t next = start; next - start < std::int64_t(seconds * 1e9); next += 1'000'000) {
    clock.sleepUntil(next);
    const std::int64_t t = clock.now_ns();
    poses.publish(net::slidingHand(0.0001f * float((t - start) / 1'000'000), 0.01f, t, 0));
  }
  const std::int64_t streamed_ns = clock.now_ns() - start;
  // The hand is gone: output must fall silent (a longer block's frames come that much later).
  std::this_thread::sleep_for(std::chrono::milliseconds(200 + c.block_ms));
  LatencyRun run;
  run.realtime = c.priority > 0 && client.stats().realtime && server.stats().realtime;
  haptics::ActuatorFrame last;
  if (output.read(last))
    for (const auto& block : last.block)
      for (float v : block) run.stuck = run.stuck || v != 0.0f;
  client.disconnect();
  server.stop();
  const auto latencies = client.latencies();
  const auto stats = client.stats();
  const auto serverStats = server.stats();
  run.p50_ms = percentile(latencies, 0.5);
  run.p99_ms = percentile(latencies, 0.99);
  run.max_ms = percentile(latencies, 1.0);
  run.sent = stats.posesSent;
  run.played = stats.jitter.played;
  run.concealed = stats.jitter.concealed;
  run.lost = stats.jitter.lost;
  run.late = stats.jitter.late;
  run.targetDelay_ms = double(stats.jitter.targetDelay_ns) / 1e6;
  // What each direction costs on the wire: what was sent, each datagram with its IP/UDP headers.
  const double s = double(streamed_ns) / 1e9 + 0.2;
  const auto wire_kbps = [&](std::uint64_t bytes, std::uint64_t datagrams) {
    return double(bytes + datagrams * net::kIpUdpOverhead) * 8.0 / s / 1000.0;
  };
  run.downWire_kbps = wire_kbps(serverStats.bytesSent, serverStats.datagramsSent);
  run.downPayload_kbps = double(serverStats.codecBytes) * 8.0 / s / 1000.0;
  run.upWire_kbps = wire_kbps(stats.bytesSent, stats.datagramsSent);
  run.upPayload_kbps = double(stats.poseBytes) * 8.0 / s / 1000.0;
  run.downBytesPerDatagram = double(serverStats.bytesSent) / double(std::max<std::uint64_t>(serverStats.datagramsSent, 1));
  run.upBytesPerDatagram = double(stats.bytesSent) / double(std::max<std::uint64_t>(stats.datagramsSent, 1));
  return run;
}

void BM_PerceptualEncode(benchmark::State& state) {
  const auto codec = haptics::makeCodec(CodecId::Perceptual, 50);
  const auto signal = haptics::textureSweepSignal(0.05f, 0.25f, 0.8f, kBlock, kRate);
  haptics::WaveBlock block{};
  for (int c = 0; c < 5; ++c) std::copy(signal.begin(), signal.end(), block[std::size_t(c)].begin());
  std::array<std::uint8_t, haptics::kMaxEncodedBlock> out{};
  for (auto _ : state) benchmark::DoNotOptimize(codec->encode(block, {5, kBlock, kRate}, out));
}
BENCHMARK(BM_PerceptualEncode);

}  // namespace

VT_BENCH_SUITE(net, "tactile codec rate-distortion (SNR, SPQI, MPEG RM) and loopback motion-to-vibration latency") {
  log::setLevel(log::Level::Warn);
  nlohmann::ordered_json out;
  out["block_samples"] = kBlock;
  out["sample_rate_hz"] = kRate;
  out["codec"] = bench::codecFigures(options.quick);

  const double seconds = options.quick ? 1.0 : 5.0;
  // As the app runs (network and sender threads ask for SCHED_FIFO), then the codec at 0 % loss
  // with normal scheduling as the baseline: what a client without the permission gets; then
  // keyed (every datagram authenticated), four blocks per datagram, and 16 and 128 ms codec blocks.
  const Case cases[] = {{"raw_loss0", CodecId::RawFloat32, 0.0, kNetworkPriority},
                        {"raw_loss5", CodecId::RawFloat32, 0.05, kNetworkPriority},
                        {"pcm16_loss0", CodecId::Pcm16, 0.0, kNetworkPriority},
                        {"codec_loss0", CodecId::Perceptual, 0.0, kNetworkPriority},
                        {"codec_loss5", CodecId::Perceptual, 0.05, kNetworkPriority},
                        {"codec_loss0_normal_sched", CodecId::Perceptual, 0.0, 0},
                        {"codec_loss0_keyed", CodecId::Perceptual, 0.0, kNetworkPriority, true},
                        {"codec_loss0_4blocks", CodecId::Perceptual, 0.0, kNetworkPriority, false, 4},
                        {"codec_loss0_16ms", CodecId::Perceptual, 0.0, kNetworkPriority, false, 1, 16},
                        {"codec_loss0_128ms", CodecId::Perceptual, 0.0, kNetworkPriority, false, 1, 128}};
  for (const Case& c : cases) {
    const LatencyRun run = measureLatency(c, seconds);
    const std::string key = std::string(c.label) + "_";
    out[key + "latency_p50_ms"] = run.p50_ms;
    out[key + "latency_p99_ms"] = run.p99_ms;
    out[key + "latency_max_ms"] = run.max_ms;
    out[key + "frames_sent"] = run.sent;
    out[key + "frames_played"] = run.played;
    out[key + "frames_concealed"] = run.concealed;
    out[key + "frames_lost"] = run.lost;
    out[key + "frames_late"] = run.late;
    out[key + "playout_delay_ms"] = run.targetDelay_ms;
    out[key + "stuck_output"] = run.stuck;
    out[key + "down_wire_kbps"] = run.downWire_kbps;
    out[key + "down_payload_kbps"] = run.downPayload_kbps;
    out[key + "down_bytes_per_datagram"] = run.downBytesPerDatagram;
    out[key + "up_wire_kbps"] = run.upWire_kbps;
    out[key + "up_payload_kbps"] = run.upPayload_kbps;
    out[key + "up_bytes_per_datagram"] = run.upBytesPerDatagram;
    if (c.priority > 0) out[key + "realtime"] = run.realtime;
    if (c.codec == CodecId::Perceptual && c.loss == 0.0 && c.priority > 0 && !c.keyed && c.blocksPerDatagram == 1 &&
        c.block_ms == 4) {
      out["latency_p50_ms"] = run.p50_ms;
      out["latency_p99_ms"] = run.p99_ms;
    }
  }
  if (options.json) {
    std::printf("%s\n", out.dump(2).c_str());
  } else {
    for (const auto& [key, value] : out.items()) std::printf("%-36s %s\n", key.c_str(), value.dump().c_str());
  }
  return 0;
}
