// vt_bench net [--json] [--quick]: tactile codec figures (compression ratio over 16-bit PCM,
// SNR, encode/decode time per block) on the test signals, and end-to-end motion-to-vibration
// latency (pose timestamp -> actuator frame leaving the client's jitter buffer) over loopback
// UDP for raw float32 and the perceptual codec, at 0 % and 5 % injected loss (the 5 % case also
// has 1 ms jitter and 1 % reordering, both directions). Figures are quoted in docs/PERFORMANCE.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/log.hpp"
#include "vt/core/realtime.hpp"
#include "vt/haptics/codec/test_signals.hpp"
#include "vt/net/client.hpp"
#include "vt/net/map_renderer.hpp"
#include "vt/net/server.hpp"

namespace {

using namespace vt;
using haptics::CodecId;

constexpr int kRate = 8000;
constexpr int kBlock = 32;
constexpr std::int64_t kPeriod_ns = std::int64_t(kBlock) * 1'000'000'000 / kRate;

double percentile(std::vector<std::int64_t> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return double(v[std::size_t(p * double(v.size() - 1))]) / 1e6;
}

struct LatencyRun {
  double p50_ms = 0, p99_ms = 0, max_ms = 0;
  std::uint64_t sent = 0, played = 0, concealed = 0, lost = 0, late = 0;
  double targetDelay_ms = 0;
  bool stuck = false;  // output not silent 200 ms after the stream stopped
  bool realtime = false;  // every thread got the SCHED_FIFO priority asked for
};

/// The priority `vtouching client` and `serve` ask for on their network and pose threads.
constexpr int kNetworkPriority = 20;

LatencyRun measureLatency(CodecId codec, double loss, double seconds, int realtimePriority) {
  net::Impairment impairment;
  if (loss > 0) {
    impairment.loss = loss;
    impairment.jitter_ns = 1'000'000;
    impairment.reorder = 0.01;
  }
  net::ServerConfig serverConfig;
  serverConfig.bind = net::parseEndpoint("127.0.0.1:0");
  serverConfig.impairment = impairment;
  serverConfig.impairment.seed = 11;
  serverConfig.realtimePriority = realtimePriority;
  auto renderer = std::make_shared<net::MapRenderer>();
  serverConfig.renderer = [renderer](const HandPose& pose, haptics::ActuatorFrame& frame) { renderer->render(pose, frame); };
  net::Server server(serverConfig);
  server.start();

  LatestValue<haptics::ActuatorFrame> output;
  net::ClientConfig clientConfig;
  clientConfig.server = server.endpoint();
  clientConfig.codecs = {codec};
  clientConfig.impairment = impairment;
  clientConfig.impairment.seed = 12;
  clientConfig.latestOut = &output;
  clientConfig.realtimePriority = realtimePriority;
  net::Client client(clientConfig);
  client.connect();

  // The scripted slide: five fingertips across the texture at 0.1 m/s, one pose per block, from
  // a pose thread like the client's forwarder.
  bool senderRealtime = realtimePriority == 0;
  std::thread sender([&] {
    if (realtimePriority > 0) senderRealtime = requestRealtime("bench sender", realtimePriority).granted();
    const auto& clock = SteadyClock::instance();
    const int poses = int(seconds * 1e9 / double(kPeriod_ns));
    std::int64_t next = clock.now_ns();
    for (int i = 1; i <= poses; ++i, next += kPeriod_ns) {
      clock.sleepUntil(next);
      client.sendPose(net::slidingHand(0.0004f * float(i), 0.01f, clock.now_ns(), std::uint64_t(i)));
    }
  });
  sender.join();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  LatencyRun run;
  run.realtime = realtimePriority > 0 && senderRealtime && client.stats().realtime && server.stats().realtime;
  haptics::ActuatorFrame last;
  if (output.read(last))
    for (const auto& block : last.block)
      for (float v : block) run.stuck = run.stuck || v != 0.0f;
  client.disconnect();
  server.stop();
  const auto latencies = client.latencies();
  const auto stats = client.stats();
  run.p50_ms = percentile(latencies, 0.5);
  run.p99_ms = percentile(latencies, 0.99);
  run.max_ms = percentile(latencies, 1.0);
  run.sent = stats.posesSent;
  run.played = stats.jitter.played;
  run.concealed = stats.jitter.concealed;
  run.lost = stats.jitter.lost;
  run.late = stats.jitter.late;
  run.targetDelay_ms = double(stats.jitter.targetDelay_ns) / 1e6;
  return run;
}

struct Signal {
  std::string name;
  std::vector<float> samples;
};

std::vector<Signal> testSignals(int samples) {
  return {{"texture_sweep", haptics::textureSweepSignal(0.05f, 0.25f, 0.8f, samples, kRate)},
          {"texture_slow", haptics::textureSweepSignal(0.02f, 0.08f, 0.8f, samples, kRate)},
          {"sine_80hz", haptics::sineSignal(80.0f, 0.5f, samples, kRate)},
          {"sine_250hz", haptics::sineSignal(250.0f, 0.5f, samples, kRate)},
          {"band_noise_50_800hz", haptics::bandNoiseSignal(50.0f, 800.0f, 0.2f, samples, kRate, 7)},
          {"white_noise", haptics::bandNoiseSignal(0.0f, 4000.0f, 0.2f, samples, kRate, 8)}};
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

VT_BENCH_SUITE(net, "tactile codec ratio/SNR/timing and loopback motion-to-vibration latency") {
  log::setLevel(log::Level::Warn);
  nlohmann::ordered_json out;
  const int samples = options.quick ? kRate : kRate * 10;
  out["block_samples"] = kBlock;
  out["sample_rate_hz"] = kRate;
  out["codec_quality"] = 50;
  const auto perceptual = haptics::makeCodec(CodecId::Perceptual, 50);
  nlohmann::ordered_json signals;
  for (const auto& signal : testSignals(samples)) {
    const auto r = haptics::evaluateCodec(*perceptual, signal.samples, kBlock, kRate);
    signals[signal.name] = {{"ratio", r.ratio}, {"snr_db", r.snr_db}, {"kbps", r.bitrate_kbps},
                            {"encode_us_per_block", r.encode_us_per_block},
                            {"decode_us_per_block", r.decode_us_per_block}};
    if (signal.name == "texture_sweep") {
      out["codec_ratio"] = r.ratio;
      out["codec_snr_db"] = r.snr_db;
      out["codec_encode_us_per_block"] = r.encode_us_per_block;
      out["codec_decode_us_per_block"] = r.decode_us_per_block;
    }
  }
  // Five actuators at once (the glove): one block carries every channel.
  const auto multi = haptics::evaluateCodec(*perceptual, testSignals(samples)[0].samples, kBlock, kRate, 5);
  out["codec_5ch_ratio"] = multi.ratio;
  out["codec_5ch_encode_us_per_block"] = multi.encode_us_per_block;
  out["signals"] = signals;

  const double seconds = options.quick ? 1.0 : 5.0;
  // As the app runs (network and pose threads ask for SCHED_FIFO), then the codec at 0 % loss
  // with normal scheduling as the baseline: what a client without the permission gets.
  struct Case {
    const char* label;
    CodecId codec;
    double loss;
    int priority;
  };
  const Case cases[] = {{"raw_loss0", CodecId::RawFloat32, 0.0, kNetworkPriority},
                        {"raw_loss5", CodecId::RawFloat32, 0.05, kNetworkPriority},
                        {"codec_loss0", CodecId::Perceptual, 0.0, kNetworkPriority},
                        {"codec_loss5", CodecId::Perceptual, 0.05, kNetworkPriority},
                        {"codec_loss0_normal_sched", CodecId::Perceptual, 0.0, 0}};
  for (const Case& c : cases) {
    const LatencyRun run = measureLatency(c.codec, c.loss, seconds, c.priority);
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
    if (c.priority > 0) out[key + "realtime"] = run.realtime;
    if (c.codec == CodecId::Perceptual && c.loss == 0.0 && c.priority > 0) {
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
