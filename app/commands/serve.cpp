// `vtouching serve`: the paper's tactile server, headless. Runs the haptic loop on the demo
// scene for one remote client at a time: each pose received is applied to the mirror hand, the
// loop ticks once on it (pose-driven, lowest latency) and the frame is encoded and sent back.
#include <csignal>
#include <cstdio>
#include <memory>
#include <thread>

#include "cli.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/haptics/haptic_loop.hpp"
#include "vt/net/server.hpp"
#include "vt/scene/demo_scene.hpp"
#include "net_options.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

}  // namespace

VT_COMMAND(serve, "serve [--bind ADDR:PORT] [--seconds N] [--codecs LIST] [--timeout-ms MS] [--model paper|texture] "
                  "[--preset five|vtouching] [--loss P] [--jitter-ms MS]",
           "tactile server: haptic loop on the demo scene for one remote client (loopback by default)") {
  using namespace vt;
  net::ServerConfig config;
  config.bind = net::parseEndpoint(args.valueOr("bind", "127.0.0.1:47800"), "--bind");
  const double seconds = args.doubleOr("seconds", 0.0);
  config.codecs = app::parseCodecList(args.valueOr("codecs", "perceptual,pcm16,raw-f32"));
  config.timeout_ns = std::int64_t(args.intOr("timeout-ms", 1000)) * 1'000'000;
  config.impairment = app::impairmentOptions(args);
  const std::string model = args.valueOr("model", "texture");
  const std::string preset = args.valueOr("preset", "five");
  args.finish();

  if (preset != "five" && preset != "vtouching") fail("--preset expects five|vtouching, not '", preset, "'");
  haptics::HapticConfig haptic =
      preset == "vtouching" ? haptics::HapticConfig::vTouching() : haptics::HapticConfig::fiveFingertips();
  if (model == "paper") haptic.renderer.model = haptics::TactileModel::PaperIntensity;
  else if (model == "texture") haptic.renderer.model = haptics::TactileModel::TextureWaveform;
  else fail("--model expects paper|texture, not '", model, "'");
  // One 32-sample block per pose at 8 kHz: the client's 250 Hz pose clock paces the stream.
  haptic.rate_hz = haptic.renderer.sampleRate_hz / float(haptics::kMaxBlockSamples);

  LatestValue<HandPose> poses;
  haptics::HapticLoop loop(haptic, poses);
  SpscRing<haptics::ActuatorFrame> frames(16);
  loop.addOutput(frames);
  loop.publishScene(haptics::makeHapticScene(std::make_shared<const Scene>(makeDemoScene())));

  config.actuatorCount = haptic.actuatorCount();
  config.blockLength = haptic.blockLength();
  config.sampleRate_hz = int(haptic.renderer.sampleRate_hz);
  config.renderer = [&](const HandPose& pose, haptics::ActuatorFrame& frame) {
    // The loop judges pose freshness on this machine's clock; the client's timestamp travels
    // back untouched in the frame (the server sets pose_t_ns from the received pose).
    HandPose local = pose;
    local.t_ns = SteadyClock::instance().now_ns();
    poses.publish(local);
    loop.tickOnce(local.t_ns);
    while (frames.pop(frame)) {
    }
  };
  net::Server server(config);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  server.start();
  std::printf("serving on %s (codecs %s; Ctrl-C stops)\n", net::toString(server.endpoint()).c_str(),
              args.valueOr("codecs", "perceptual,pcm16,raw-f32").c_str());
  std::fflush(stdout);
  const std::int64_t end = seconds > 0 ? SteadyClock::instance().now_ns() + std::int64_t(seconds * 1e9) : INT64_MAX;
  while (!g_stop && SteadyClock::instance().now_ns() < end) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  server.stop();
  const auto s = server.stats();
  std::printf("server: %llu sessions, %llu refused, %llu timeouts, %llu poses applied, %llu frames sent, %llu rejected datagrams\n",
              (unsigned long long)s.sessions, (unsigned long long)s.refused, (unsigned long long)s.timeouts,
              (unsigned long long)s.posesApplied, (unsigned long long)s.framesSent, (unsigned long long)s.rejected);
  return 0;
}
