// `vtouching serve`: the paper's tactile server, headless. A touch pipeline runs the haptic loop
// on the scene (the same scene options as the app; the client must show the same scene) for one
// remote client at a time: each pose received is applied to the mirror hand, the loop ticks once
// on it (pose-driven, lowest latency) and the frame is encoded and sent back.
#include <cstdio>
#include <memory>
#include <thread>

#include "cli.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/realtime.hpp"
#include "vt/core/stop.hpp"
#include "vt/net/server.hpp"
#include "modes/haptic_options.hpp"
#include "modes/touch_pipeline.hpp"
#include "modes/scene_source.hpp"
#include "modes/server_video.hpp"
#include "net_options.hpp"

VT_COMMAND(serve) {
  using namespace vt;
  net::ServerConfig config;
  config.bind = net::parseEndpoint(args.valueOr("bind", "127.0.0.1:47800"), "--bind");
  const double seconds = args.doubleIn("seconds", 0.0, 0.0, 1e6);
  const std::string codecs = args.valueOr("codecs", "perceptual,pcm16,raw-f32");
  config.codecs = app::parseCodecList(codecs);
  config.timeout_ns = std::int64_t(args.intIn("timeout-ms", 1000, 1, 65535)) * 1'000'000;
  // Without the option the server streams the block length each client asks for.
  config.block_ms = app::blockLengthOption(args).value_or(0);
  config.impairment = app::impairmentOptions(args);
  config.key = app::serverKeyOption(args);  // required off loopback (the server says so)
  config.realtimePriority = 20;  // pose-driven rendering runs on the network thread (like the haptic loop)
  const app::SceneOptions sceneOptions = app::readSceneOptions(args);
  app::HapticOptions hapticOptions = app::readHapticOptions(args);
  // The actuator output it renders (for whichever client is connected), recorded like every
  // mode's; the option table gives serve only the recorders among the sink options.
  const app::HapticSinks sinks = app::readHapticSinks(args, "none");
  const bool video = args.flag("video");
  const app::ServerVideoOptions videoOptions{.fps = args.doubleOr("video-fps", 15.0), .quality = args.intOr("video-quality", 75),
                                             .hand = app::readHandViewOptions(args)};
  args.finish();

  // One 32-sample block per pose at 8 kHz: the client's 250 Hz pose clock paces the stream.
  hapticOptions.rate_hz = app::makeHapticConfig(hapticOptions).tactile.sampleRate_hz / float(haptics::kMaxBlockSamples);
  const app::LoadedScene scene = app::loadScene(sceneOptions);
  config.sceneDigest = tactileDigest(*scene.scene);
  config.sceneName = scene.description;
  // The touch pipeline builds the server: its network thread maps each pose's stamp onto this
  // clock, writes it into the pipeline's pose history and ticks the pipeline's loop at that time
  // (and at lost poses' times, the hand interpolated across the gap), so blocks are spaced by
  // the times the poses describe; the frame goes to the stream and to the recorders.
  app::TouchPipeline pipeline(scene, {.sceneOptions = sceneOptions, .haptic = hapticOptions, .sinks = sinks,
                                    .drive = app::TouchDrive::Served, .served = config});
  net::Server& server = *pipeline.server();
  std::unique_ptr<app::ServerVideo> serverVideo;  // the virtual camera, for clients that ask (--video)
  if (video) (serverVideo = std::make_unique<app::ServerVideo>(scene, pipeline.poses(), server, videoOptions))->start();
  std::printf("serving %s on %s (model %s, codecs %s%s; Ctrl-C stops)\n", scene.description.c_str(),
              net::toString(server.endpoint()).c_str(), app::modelName(hapticOptions.model),
              codecs.c_str(), config.key ? ", authenticated" : "");
  std::fflush(stdout);
  const std::int64_t end = seconds > 0 ? SteadyClock::instance().now_ns() + std::int64_t(seconds * 1e9) : INT64_MAX;
  while (!stopRequested() && SteadyClock::instance().now_ns() < end) {
    pipeline.drain();  // the loop's frames and traces, off the network thread
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (serverVideo) {
    serverVideo->stop();
    const app::ServerVideoStats v = serverVideo->stats();
    std::printf("video: %llu frames sent, render %.1f ms, JPEG encode %.1f ms, %.0f bytes per frame\n",
                (unsigned long long)v.framesSent, v.meanRender_ms, v.meanEncode_ms, v.meanJpegBytes);
  }
  pipeline.stop();  // the server first, then --record-csv/--record-wav
  const auto s = server.stats();
  std::printf("server: %llu sessions, %llu refused, %llu timeouts, %llu poses applied, %llu frames sent, %llu rejected "
              "datagrams; real time: %s\n",
              (unsigned long long)s.sessions, (unsigned long long)s.refused, (unsigned long long)s.timeouts,
              (unsigned long long)s.posesApplied, (unsigned long long)s.framesSent, (unsigned long long)s.rejected,
              vt::describeRealtimeGrants().c_str());
  return 0;
}
