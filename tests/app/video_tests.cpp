// The server's video stream end to end: ServerVideo renders the scene and the mirror hand on
// lavapipe, net::Server sends JPEG frames over loopback, net::Client reassembles them.
#include <chrono>
#include <cmath>
#include <thread>

#include <catch2/catch.hpp>

#include "modes/hand_control.hpp"
#include "modes/scene_source.hpp"
#include "modes/server_video.hpp"
#include "modes/video_frames.hpp"
#include "test_support.hpp"
#include "vt/core/clock.hpp"
#include "vt/net/client.hpp"
#include "vt/net/server.hpp"
#include "vt/scene/jpeg.hpp"

using namespace vt;

namespace {

// Standard deviation of the luma: a flat (clear-colour only) frame is ~0.
double lumaStdDev(const Image8& rgba) {
  double sum = 0, sum2 = 0;
  const std::size_t n = std::size_t(rgba.width) * rgba.height;
  for (std::size_t i = 0; i < n; ++i) {
    const double y = 0.299 * rgba.pixels[4 * i] + 0.587 * rgba.pixels[4 * i + 1] + 0.114 * rgba.pixels[4 * i + 2];
    sum += y;
    sum2 += y * y;
  }
  const double mean = sum / double(n);
  return std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean));
}

double meanAbsDiff(const Image8& a, const Image8& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
  return sum / double(a.pixels.size());
}

}  // namespace

TEST_CASE("Server video renders the scene and mirror hand and the client receives 480x480 JPEG frames", "[app][video]") {
  app::SceneOptions sceneOptions;
  sceneOptions.builtin = true;
  const app::LoadedScene scene = app::loadScene(sceneOptions);

  LatestValue<HandPose> poses;
  net::ServerConfig serverConfig;
  serverConfig.bind = net::parseEndpoint("127.0.0.1:0");
  serverConfig.renderer = [&](const HandPose& pose, haptics::ActuatorFrame& frame) {
    poses.publish(pose);
    frame = haptics::ActuatorFrame::silent(kFingerCount, pose.t_ns);
  };
  net::Server server(serverConfig);
  server.start();
  app::ServerVideoOptions videoOptions;
  videoOptions.validate = true;
  videoOptions.fps = 10.0;
  app::ServerVideo video(scene, poses, server, videoOptions);
  video.start();

  net::ClientConfig clientConfig;
  clientConfig.server = server.endpoint();
  clientConfig.wantVideo = true;
  net::Client client(clientConfig);
  client.connect();
  const auto out = test::outputDir("app_server_video");
  app::VideoFrameWriter writer(client.video(), out);

  // First frames without a hand, then the desktop hand's start pose above the scene centre.
  net::VideoFrame frame;
  std::uint64_t version = 0;
  Image8 withoutHand, withHand;
  const Clock& clock = SteadyClock::instance();
  app::DesktopHand hand;
  const std::int64_t start = clock.now_ns();
  std::uint64_t sequence = 0;
  while (clock.now_ns() - start < 2'000'000'000) {
    const bool handPhase = clock.now_ns() - start > 700'000'000;
    if (handPhase) {
      HandPose pose = hand.pose(false, clock.now_ns());
      pose.sequence = ++sequence;
      client.sendPose(pose);
    }
    writer.poll();
    if (client.video().readNewer(frame, version)) {
      const Image8 image = decodeJpeg(frame.jpeg, "received frame");
      REQUIRE(image.width == 480);
      REQUIRE(image.height == 480);
      (handPhase ? withHand : withoutHand) = image;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  client.disconnect();
  video.stop();
  server.stop();

  const app::ServerVideoStats stats = video.stats();
  const net::ClientStats clientStats = client.stats();
  std::printf("server video: %llu frames rendered, %llu sent, render %.1f ms, encode %.1f ms, %.0f bytes/frame "
              "(%zu fragments); client: %llu completed, %llu abandoned\n",
              (unsigned long long)stats.framesRendered, (unsigned long long)stats.framesSent, stats.meanRender_ms,
              stats.meanEncode_ms, stats.meanJpegBytes, net::videoFragmentCount(std::size_t(stats.meanJpegBytes)),
              (unsigned long long)clientStats.video.completed, (unsigned long long)clientStats.video.abandoned);
  CHECK(stats.validationMessages == 0);
  CHECK(stats.framesSent >= 4);
  CHECK(clientStats.video.completed >= 4);
  CHECK(clientStats.video.rejected == 0);
  CHECK(writer.written() >= 2);
  REQUIRE_FALSE(withoutHand.empty());
  REQUIRE_FALSE(withHand.empty());
  CHECK(lumaStdDev(withoutHand) > 10.0);  // the scene is visible, not a clear-colour frame
  CHECK(meanAbsDiff(withHand, withoutHand) > 0.3);  // the mirror hand appeared
  savePng(out / "with_hand.png", withHand);
}
