// `vtouching client`: the paper's client. Hand input comes from the desktop (mouse and keys,
// optionally the glove's flexion), a headset (--xr) or, headless, the example trajectory; the
// scene is rendered locally from the same scene description as the server's (checked at
// hello by its tactile digest). Poses go to the server at the stream's block rate; its tactile
// frames are decoded, played through the jitter buffer and sent to the glove and recorders.
// A report (latency, stream statistics) is printed at the end.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "modes/run_report.hpp"

#include "cli.hpp"
#include "modes/desktop_mode.hpp"
#include "modes/headset_mode.hpp"
#include "modes/trajectory_run.hpp"
#include "modes/video_frames.hpp"
#include "net_options.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/realtime.hpp"
#include "vt/core/stop.hpp"
#include "vt/scene/trajectory.hpp"

namespace {

constexpr std::int64_t kHeadlessInputPeriod_ns = 1'000'000;  // trajectory poses at 1 kHz
constexpr std::int64_t kHeadlessDrainPeriod_ns = 10'000'000;

double percentile_ms(std::vector<std::int64_t> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return double(v[std::size_t(p * double(v.size() - 1))]) / 1e6;
}

void printClientReport(const vt::app::TouchPipeline& pipeline, bool json) {
  const vt::net::Client& client = *pipeline.client();
  const auto stats = client.stats();
  const auto latencies = client.latencies();
  nlohmann::ordered_json out = {
      {"codec", vt::haptics::codecName(vt::haptics::CodecId(client.session().codec))},
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
      {"rtt_ms", double(stats.rtt_ns) / 1e6},
      {"reconnects", stats.reconnects},
      {"realtime", stats.realtime},
      {"realtime_grants", vt::app::realtimeGrantsJson()},
      {"rejected_datagrams", stats.rejected},
      {"server_ended_session", stats.serverSaidBye},
      {"video_frames_received", stats.video.completed},
      {"video_frames_abandoned", stats.video.abandoned},
      {"consistency", vt::app::consistencyJson(pipeline.consistency())},
  };
  vt::app::printReport(out, json);
}

/// Headless: the trajectory (looped) drives the hand for `seconds`; Ctrl-C ends early.
void runHeadless(const vt::app::DesktopOptions& options, const vt::Trajectory& trajectory, double seconds,
                 const std::optional<std::string>& videoOut) {
  using namespace vt;
  const app::LoadedScene scene = app::loadScene(options.scene);
  app::TouchPipeline pipeline(scene, options.touchSpec());
  std::optional<app::VideoFrameWriter> video;
  if (videoOut) video.emplace(pipeline.client()->video(), *videoOut);
  const Clock& clock = SteadyClock::instance();
  const std::int64_t start = clock.now_ns();
  const double loop_s = std::max(trajectory.duration_s(), 1e-3);
  std::int64_t nextDrain = start;
  double previous_s = 0.0;
  for (std::int64_t next = start; next - start < std::int64_t(seconds * 1e9); next += kHeadlessInputPeriod_ns) {
    if (stopRequested()) break;
    clock.sleepUntil(next);
    const double t_s = double(next - start) / 1e9;
    const double into_s = std::fmod(t_s, loop_s);
    HandPose pose = trajectory.poseAt(trajectory.keys.front().t_s + into_s);
    pose.t_ns = next;  // the time this trajectory pose describes
    pipeline.publishPose(pose, into_s < previous_s);  // the loop back to the start is a jump
    previous_s = into_s;
    if (next >= nextDrain) {
      if (!pipeline.client()->stats().connected) break;  // the server ended the pipeline
      pipeline.drain();
      if (video) video->poll();
      nextDrain = next + kHeadlessDrainPeriod_ns;
    }
  }
  pipeline.stop();
  printClientReport(pipeline, options.json);
}

}  // namespace

VT_COMMAND(client) {
  using namespace vt;
  const auto connect = args.value("connect");
  if (!connect) fail("client: --connect ADDR:PORT is required (e.g. 127.0.0.1:47800)");
  net::ClientConfig config;
  config.server = net::parseEndpoint(*connect, "--connect");
  if (const auto bind = args.value("bind")) config.bind = net::parseEndpoint(*bind, "--bind");
  config.codecs = app::parseCodecList(args.valueOr("codecs", "perceptual,pcm16,raw-f32"));
  config.quality = args.intOr("quality", 50);
  config.impairment = app::impairmentOptions(args);
  config.key = app::clientKeyOption(args);
  config.block_ms = app::blockLengthOption(args).value_or(haptics::kCodecBlockLengths_ms[0]);
  config.blocksPerDatagram = args.intOr("blocks-per-datagram", 1);
  config.redundancy = !args.flag("no-redundancy");
  const auto videoOut = args.value("video-out");  // headless: received frames as DIR/frame_N.jpg
  config.wantVideo = args.flag("video") || videoOut;

  app::DesktopOptions options = app::readDesktopOptions(args);
  const bool xr = args.flag("xr"), xrRequired = args.flag("xr-required");
  const bool headless = args.flag("headless") || (!xr && !xrRequired && !app::haveDisplay());
  const double seconds = args.doubleIn("seconds", headless ? 5.0 : 0.0, 0.0, 1e6);
  const std::string trajectoryPath = args.valueOr("trajectory", app::defaultTrajectory().string());
  options.json = args.flag("json");
  args.finish();
  // An interactive client waits for a restarted server; a headless run reports and ends.
  config.reconnect = !headless;
  options.remote = config;
  options.runReport = [json = options.json](const app::TouchPipeline& pipeline) {
    printClientReport(pipeline, json);
  };
  if (headless) {
    if (trajectoryPath.empty()) fail("client: headless needs --trajectory FILE (no example trajectory found)");
    runHeadless(options, loadTrajectory(trajectoryPath), seconds > 0 ? seconds : 5.0, videoOut);
    return 0;
  }
  if (xr || xrRequired) {
    if (const auto code = app::runHeadset(options)) return *code;
    if (xrRequired) return 5;
    if (!app::haveDisplay()) fail("client: no headset and no display (use --headless)");
    std::fprintf(stderr, "vtouching: continuing with the desktop as the client's input\n");
  }
  return app::runDesktop(options);
}
