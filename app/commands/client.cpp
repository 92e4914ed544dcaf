// `vtouching client`: the paper's client, headless. A scripted hand slides its fingertips back
// and forth over the demo scene's stripes plate at the session's pose rate; the server's
// tactile stream is decoded, played out and recorded; latency and stream statistics are
// reported at the end. (Desktop, headset and glove input join when the app's modes exist.)
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "net_options.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/devices/recorder.hpp"
#include "vt/net/client.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

// Stripes plate of the demo scene: centre x = -0.27 m, 0.14 m wide, top face at y = 0.006 m.
constexpr float kPlateX_m = -0.27f;
constexpr float kSlideHalfWidth_m = 0.05f;
constexpr float kSlideSpeed_m_s = 0.1f;
constexpr float kTipRadius_m = 0.008f;
constexpr float kTipY_m = 0.006f + kTipRadius_m - 0.002f;  // 2 mm into the surface

/// Fingertips across the plate (spread in z), sliding in x as a triangle wave; other joints
/// well above the table so only the tips touch.
vt::HandPose slidePose(double t_s, std::int64_t t_ns, std::uint64_t sequence) {
  const double period = 4.0 * kSlideHalfWidth_m / kSlideSpeed_m_s;
  const double phase = std::fmod(t_s, period) / period;
  const float offset = float(kSlideHalfWidth_m * (phase < 0.5 ? 4.0 * phase - 1.0 : 3.0 - 4.0 * phase));
  vt::HandPose pose;
  pose.t_ns = t_ns;
  pose.sequence = sequence;
  pose.valid = true;
  for (auto& p : pose.position) p = {kPlateX_m + offset, 0.2f, 0.0f};
  for (auto& q : pose.orientation) q = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  for (auto& r : pose.radius_m) r = kTipRadius_m;
  for (int f = 0; f < vt::kFingerCount; ++f)
    pose.position[std::size_t(vt::kFingertips[std::size_t(f)])] = {kPlateX_m + offset, kTipY_m, -0.04f + 0.02f * float(f)};
  return pose;
}

double percentile_ms(std::vector<std::int64_t> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return double(v[std::size_t(p * double(v.size() - 1))]) / 1e6;
}

}  // namespace

VT_COMMAND(client, "client --connect ADDR:PORT [--seconds N] [--codecs LIST] [--quality 0..100] "
                   "[--record-csv FILE] [--record-wav FILE] [--loss P] [--jitter-ms MS] [--json]",
           "tactile client: scripted slide over the demo plates, plays and records the server's stream") {
  using namespace vt;
  const auto connect = args.value("connect");
  if (!connect) fail("client: --connect ADDR:PORT is required (e.g. 127.0.0.1:47800)");
  net::ClientConfig config;
  config.server = net::parseEndpoint(*connect, "--connect");
  const double seconds = args.doubleOr("seconds", 5.0);
  config.codecs = app::parseCodecList(args.valueOr("codecs", "perceptual,pcm16,raw-f32"));
  config.quality = args.intOr("quality", 50);
  config.impairment = app::impairmentOptions(args);
  const std::string csv = args.valueOr("record-csv", "");
  const std::string wav = args.valueOr("record-wav", "");
  const bool json = args.flag("json");
  args.finish();

  SpscRing<haptics::ActuatorFrame> played(1024);
  config.framesOut = &played;
  net::Client client(config);
  client.connect();
  std::unique_ptr<haptics::ActuatorRecorder> recorder;
  if (!csv.empty() || !wav.empty())
    recorder = std::make_unique<haptics::ActuatorRecorder>(csv, wav, client.session().actuatorCount);

  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  const auto& clock = SteadyClock::instance();
  const std::int64_t period_ns =
      std::int64_t(client.session().blockLength) * 1'000'000'000 / std::int64_t(client.session().sampleRate_hz);
  const std::int64_t start = clock.now_ns();
  std::int64_t next = start;
  haptics::ActuatorFrame frame;
  for (std::uint64_t sequence = 1; !g_stop && next - start < std::int64_t(seconds * 1e9); ++sequence, next += period_ns) {
    clock.sleepUntil(next);
    if (!client.sendPose(slidePose(double(next - start) / 1e9, clock.now_ns(), sequence))) break;  // session over
    if (recorder) recorder->drain(played);
    else
      while (played.pop(frame)) {
      }
  }
  client.disconnect();  // the jitter buffer's tail and a final silent frame reach the sinks
  if (recorder) {
    recorder->drain(played);
    recorder->finish();
  }
  const auto stats = client.stats();
  const auto latencies = client.latencies();
  nlohmann::ordered_json out = {
      {"codec", haptics::codecName(haptics::CodecId(client.session().codec))},
      {"poses_sent", stats.posesSent},
      {"frames_received", stats.framesReceived},
      {"frames_played", stats.jitter.played},
      {"frames_concealed", stats.jitter.concealed},
      {"frames_lost", stats.jitter.lost},
      {"frames_late", stats.jitter.late},
      {"frames_reordered", stats.jitter.reordered},
      {"max_buffer_depth", stats.jitter.maxDepth},
      {"playout_delay_ms", double(stats.jitter.targetDelay_ns) / 1e6},
      {"latency_p50_ms", percentile_ms(latencies, 0.5)},
      {"latency_p99_ms", percentile_ms(latencies, 0.99)},
      {"rejected_datagrams", stats.rejected},
      {"server_ended_session", stats.serverSaidBye},
  };
  if (json) std::printf("%s\n", out.dump(2).c_str());
  else
    for (const auto& [key, value] : out.items()) std::printf("%-22s %s\n", key.c_str(), value.dump().c_str());
  return stats.posesSent > 0 ? 0 : 1;
}
