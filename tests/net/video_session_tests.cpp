#include <catch2/catch.hpp>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <thread>

#include "vt/net/client.hpp"
#include "vt/net/map_frame_source.hpp"
#include "vt/net/server.hpp"
#include "test_support.hpp"
#include "vt/scene/jpeg.hpp"

using namespace vt::net;
using vt::test::eventually;

namespace {

ServerConfig videoServer() {
  ServerConfig config;
  config.bind = parseEndpoint("127.0.0.1:0");
  auto source = std::make_shared<MapFrameSource>();
  config.frameSource = [source](const vt::HandPose& pose, vt::haptics::ActuatorFrame& frame) { source->render(pose, frame); };
  return config;
}

/// A 480x480 frame whose content depends on `k`: a diagonal gradient and a moving bar.
vt::Image8 syntheticFrame(int k) {
  vt::Image8 image(480, 480, 4);
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 480; ++x) {
      const bool bar = std::abs(x - 40 * k - 60) < 20;
      image.at(x, y, 0) = std::uint8_t((x + y) / 4);
      image.at(x, y, 1) = bar ? 230 : 30;
      image.at(x, y, 2) = std::uint8_t(y / 2);
      image.at(x, y, 3) = 255;
    }
  return image;
}

double meanAbsError(const vt::Image8& a, const vt::Image8& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
  return sum / double(a.pixels.size());
}

}  // namespace

TEST_CASE("The server streams JPEG frames to a client that asked and they arrive intact") {
  Server server(videoServer());
  server.start();
  ClientConfig config;
  config.server = server.endpoint();
  config.wantVideo = true;
  Client client(config);
  client.connect();
  REQUIRE(eventually([&] { return server.videoWanted(); }));

  std::uint64_t version = 0;
  for (int k = 0; k < 5; ++k) {
    const vt::Image8 sent = syntheticFrame(k);
    const auto jpeg = vt::encodeJpeg(sent, 85);
    REQUIRE(server.sendVideo(jpeg, sent.width, sent.height));
    VideoFrame frame;
    REQUIRE(eventually([&] { return client.video().readNewer(frame, version); }));
    CHECK(frame.jpeg == jpeg);
    CHECK(frame.width == 480);
    CHECK(frame.height == 480);
    const vt::Image8 received = vt::decodeJpeg(frame.jpeg, "received frame");
    REQUIRE(received.width == 480);
    CHECK(meanAbsError(received, sent) < 4.0);
    CHECK(meanAbsError(received, syntheticFrame(k + 2)) > 6.0);  // it is this frame, not another
  }
  CHECK(server.stats().videoFramesSent == 5);
  const ClientStats stats = client.stats();
  CHECK(stats.video.completed == 5);
  CHECK(stats.video.abandoned == 0);
  CHECK(stats.video.rejected == 0);
  client.disconnect();
  REQUIRE(eventually([&] { return !server.videoWanted(); }));
  CHECK_FALSE(server.sendVideo(vt::encodeJpeg(syntheticFrame(0), 85), 480, 480));
}

TEST_CASE("A client that did not ask for video gets none") {
  Server server(videoServer());
  server.start();
  ClientConfig config;
  config.server = server.endpoint();
  Client client(config);
  client.connect();
  REQUIRE(eventually([&] { return server.stats().clientConnected; }));
  CHECK_FALSE(server.videoWanted());
  CHECK_FALSE(server.sendVideo(vt::encodeJpeg(syntheticFrame(1), 85), 480, 480));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK(client.stats().videoFragments == 0);
  CHECK(client.video().version() == 0);
}

TEST_CASE("Video survives a lossy reordering link: lost fragments cost only their frames") {
  Server server(videoServer());
  server.start();
  ClientConfig config;
  config.server = server.endpoint();
  config.wantVideo = true;
  config.impairment.loss = 0.02;
  config.impairment.reorder = 0.2;
  config.impairment.seed = 7;
  Client client(config);
  client.connect();
  REQUIRE(eventually([&] { return server.videoWanted(); }));
  const vt::Image8 image = syntheticFrame(3);
  const auto jpeg = vt::encodeJpeg(image, 85);
  constexpr int kFrames = 30;
  for (int k = 0; k < kFrames; ++k) {
    REQUIRE(server.sendVideo(jpeg, 480, 480));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const VideoStats stats = client.stats().video;
  INFO("completed " << stats.completed << " abandoned " << stats.abandoned << " rejected " << stats.rejected);
  CHECK(stats.completed >= kFrames / 3);  // ~19 fragments a frame at 2 % loss: ~2/3 survive
  CHECK(stats.completed + stats.abandoned <= kFrames);
  VideoFrame frame;
  std::uint64_t version = 0;
  REQUIRE(client.video().readNewer(frame, version));
  CHECK(frame.jpeg == jpeg);
}
