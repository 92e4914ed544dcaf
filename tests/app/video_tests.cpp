// The server's video stream end to end: ServerVideo renders the scene and the mirror hand on
// lavapipe, net::Server sends JPEG frames over loopback, net::Client reassembles them.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

#include <catch2/catch.hpp>

#include "app_test_helpers.hpp"
#include "image_compare.hpp"
#include "modes/desktop_mode.hpp"
#include "modes/hand_control.hpp"
#include "modes/scene_source.hpp"
#include "modes/server_video.hpp"
#include "modes/video_frames.hpp"
#include "test_support.hpp"
#include "ui/hud.hpp"
#include "ui/video_window.hpp"
#include "vt/core/clock.hpp"
#include "vt/net/client.hpp"
#include "vt/net/server.hpp"
#include "vt/renderer/imgui_layer.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/renderer/window_target.hpp"
#include "vt/scene/demo_scene.hpp"
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

  auto history = std::make_unique<PoseHistory>();
  PoseHistory& poses = *history;
  net::ServerConfig serverConfig;
  serverConfig.bind = net::parseEndpoint("127.0.0.1:0");
  serverConfig.frameSource = [&](const HandPose& pose, haptics::ActuatorFrame& frame) {
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

  PoseHistory clientPoses;  // the client's sender thread samples it at the stream's rate
  net::ClientConfig clientConfig;
  clientConfig.server = server.endpoint();
  clientConfig.wantVideo = true;
  clientConfig.poses = &clientPoses;
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
      clientPoses.publish(pose);
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

TEST_CASE("The server video draws a hand decoded from the network as the hand that was sent, and matches its golden",
          "[app][video][golden]") {
  // What the server's mirror hand receives: a pose through the wire (positions and the palm's
  // orientation only), published into the pose history the video renders from.
  app::SceneOptions sceneOptions;
  sceneOptions.builtin = true;
  const app::LoadedScene scene = app::loadScene(sceneOptions);
  app::DesktopHand hand;
  hand.move({0.0f, 0.02f, 0.0f}, 0.5f, *scene.haptic->collision);  // lifted a little and turned
  hand.setCurlTargets({0.6f, 0.1f, 0.4f, 0.7f, 0.9f});
  hand.update(10.0f);
  HandPose sent = hand.pose(false, 1'000'000'000);
  sent.sequence = 1;
  net::StreamContext context;
  context.sessionId = 7;
  context.epoch_ns = 0;
  context.actuatorCount = kFingerCount;
  context.radius_m = sent.radius_m;
  std::vector<std::uint8_t> bytes(net::kMaxDatagram);
  bytes.resize(net::encodeStream(net::Pose{1, sent}, 1, context, net::Direction::ClientToServer, bytes));
  context.receiving = net::Direction::ClientToServer;
  net::Packet packet;
  REQUIRE(net::decodeStream(bytes, context, packet) == net::DecodeStatus::Ok);
  const HandPose received = std::get<net::Pose>(packet.message).hand;

  net::ServerConfig serverConfig;
  serverConfig.bind = net::parseEndpoint("127.0.0.1:0");
  serverConfig.frameSource = [](const HandPose& pose, haptics::ActuatorFrame& frame) {
    frame = haptics::ActuatorFrame::silent(kFingerCount, pose.t_ns);
  };
  net::Server server(serverConfig);  // not started: the video is rendered here, not sent
  PoseHistory poses;
  app::ServerVideoOptions videoOptions;
  videoOptions.validate = true;
  app::ServerVideo video(scene, poses, server, videoOptions);
  poses.publish(sent);
  const Image8 ofSent = video.renderFrame();
  poses.publish(received);
  const Image8 ofReceived = video.renderFrame();
  HandPose palmOriented = received;  // what the video drew before: every joint as the palm
  palmOriented.orientation.fill(received.orientation[std::size_t(HandJoint::Palm)]);
  poses.publish(palmOriented);
  const Image8 ofPalmOriented = video.renderFrame();
  const auto out = test::outputDir("app_server_video_hand");
  savePng(out / "sent.png", ofSent);
  savePng(out / "received.png", ofReceived);
  // Only the palm's orientation travels: before the fingers' were derived from their joints,
  // every joint took the palm's and the skinned fingers broke into staggered blocks.
  const test::ImageDiff d = test::compareImages(ofReceived, ofSent);
  INFO("decoded hand vs sent hand: PSNR " << d.psnr_db << " dB, " << 100.0 * d.badFraction << " % pixels off");
  CHECK(d.psnr_db > 40.0);
  CHECK(d.badFraction < 0.001);
  const test::ImageDiff broken = test::compareImages(ofPalmOriented, ofSent);  // the check can fail
  INFO("palm-oriented joints vs sent hand: PSNR " << broken.psnr_db << " dB");
  CHECK(broken.psnr_db < 35.0);
  savePng(out / "palm_oriented.png", ofPalmOriented);
  test::checkGolden(ofReceived, "server_video_hand");
  CHECK(video.stats().validationMessages == 0);
}

TEST_CASE("The video window shows received frames in ImGui and follows a size change", "[.desktop][video]") {
  if (!app::haveDisplay()) VT_SKIP("no display (ctest runs this under xvfb-run)");
  std::shared_ptr<renderer::Device> device;
  {
    test::UiWindow ui(640, 560, "video test");
    device = ui.device;
    net::LatestVideoFrame frames;
    ui::VideoWindow videoWindow(*ui.imgui, frames);
    const auto publish = [&](int width, int height, std::array<std::uint8_t, 3> colour, std::uint32_t id) {
      Image8 image(width, height, 3);
      for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = colour[i % 3];
      net::VideoFrame frame{id, width, height, encodeJpeg(image, 90)};
      frames.publish(frame);
    };
    // Counts pixels within 30 levels of `colour` (JPEG and the sRGB round trip stay well inside).
    const auto count = [](const Image8& image, std::array<int, 3> colour) {
      int n = 0;
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
          n += std::abs(image.at(x, y, 0) - colour[0]) < 30 && std::abs(image.at(x, y, 1) - colour[1]) < 30 &&
               std::abs(image.at(x, y, 2) - colour[2]) < 30;
      return n;
    };
    const auto frame = [&](bool capture) { return ui.frame([&] { videoWindow.draw(); }, capture); };
    frame(false);
    publish(480, 480, {230, 40, 40}, 1);  // red
    frame(false);
    const Image8 red = frame(true);
    publish(480, 480, {40, 40, 230}, 2);  // blue, same size: the image is re-uploaded in place
    frame(false);
    const Image8 blue = frame(true);
    publish(240, 120, {40, 220, 40}, 3);  // green, another size: the image is rebuilt
    frame(false);
    const Image8 green = frame(true);
    CHECK(videoWindow.framesShown() == 3);
    CHECK(videoWindow.decodeFailures() == 0);
    // The window fits the frame, at most 35 % of the 560-pixel height: 196 x 196.
    CHECK(count(red, {230, 40, 40}) > 30000);
    CHECK(count(blue, {230, 40, 40}) < 1000);
    CHECK(count(blue, {40, 40, 230}) > 30000);
    CHECK(count(green, {40, 220, 40}) > 20000);  // 240 x 120 = 28800
    CHECK(count(green, {40, 40, 230}) < 1000);
    savePng(test::outputDir("app_video_window") / "green.png", green);
    std::vector<std::uint8_t> corrupt = {0xFF, 0xD8, 0xFF, 0xE0, 1, 2, 3};
    net::VideoFrame bad{4, 480, 480, corrupt};
    frames.publish(bad);
    frame(false);
    CHECK(videoWindow.decodeFailures() == 1);
  }
  CHECK(device->validationMessageCount() == 0);
}

// The desktop client at the default 1280x720 with the server's 480x480 video and the HUD: the
// video window docks in the bottom-right corner, below the right-hand panels, and covers neither
// the hand (at its start pose, under a centred mouse) nor another panel nor more than 5 % of a
// plate (the client shows the server's scene: the default one).
TEST_CASE("At 1280x720 the server video window leaves the hand and the HUD's panels uncovered", "[.desktop][video]") {
  if (!app::haveDisplay()) VT_SKIP("no display (ctest runs this under xvfb-run)");
  const app::LoadedScene scene = app::loadScene({});
  const glm::vec2 size_px{1280.0f, 720.0f};
  const CameraView view = scene.scene->camera.view(size_px.x / size_px.y);
  renderer::DeviceOptions deviceOptions;
  renderer::addWindowExtensions(deviceOptions);
  auto device = renderer::Device::create(deviceOptions);
  renderer::Renderer gpu(device);
  gpu.setScene(scene.scene);
  renderer::WindowTarget window(device, {.width = 1280, .height = 720, .title = "video layout test", .vsync = false});
  renderer::ImGuiLayer imgui(gpu, window);
  net::LatestVideoFrame frames;
  ui::VideoWindow videoWindow(imgui, frames);
  Image8 image(480, 480, 3);
  std::fill(image.pixels.begin(), image.pixels.end(), std::uint8_t(128));
  net::VideoFrame frame{1, 480, 480, encodeJpeg(image, 90)};
  frames.publish(frame);
  ui::HudSettings settings;  // the client's: help on, tactile settings the server's
  settings.editable = false;
  ui::HudStatus status;
  status.remote = true;
  const std::vector<float> history(60, 0.0f);
  std::vector<ui::HudContact> contacts(5);
  for (int f = 0; f < 5; ++f) contacts[std::size_t(f)].finger = f, contacts[std::size_t(f)].history = &history;
  std::vector<test::ScreenBox> panels;
  for (int i = 0; i < 4; ++i) {
    window.pollEvents();
    imgui.beginFrame();
    ui::drawHud(status, contacts, {}, settings);
    videoWindow.draw();
    imgui.endFrame();
    panels = test::visibleImGuiWindows();
    renderer::FrameDesc desc;
    desc.views = {view};
    while (!gpu.render(window, desc)) {
    }
  }
  gpu.waitIdle();
  REQUIRE(videoWindow.framesShown() == 1);
  const auto video = std::find_if(panels.begin(), panels.end(), [](const test::ScreenBox& b) { return b.name == "Server video"; });
  REQUIRE(video != panels.end());
  INFO("video window " << video->min.x << "," << video->min.y << " .. " << video->max.x << "," << video->max.y);
  CHECK(video->max.x == Approx(1272.0f));  // docked bottom-right, 8 px margin
  CHECK(video->max.y == Approx(712.0f));
  CHECK(video->max.y - video->min.y <= 0.35f * 720.0f + 60.0f);  // the frame at most 35 % of the height
  for (const test::ScreenBox& hand : test::desktopHandBoxes(scene, size_px)) {
    INFO(hand.name << " at " << hand.min.x << "," << hand.min.y << " .. " << hand.max.x << "," << hand.max.y);
    CHECK(video->overlap(hand) == 0.0f);
  }
  for (const test::ScreenBox& panel : panels) {
    if (&panel == &*video) continue;
    INFO(panel.name);
    CHECK(video->overlap(panel) == 0.0f);
  }
  // As for the HUD's panels (none today).
  for (const test::ScreenBox& plate : test::touchableObjectBoxes(*scene.scene, size_px)) {
    INFO(plate.name << ": " << 100.0f * video->overlap(plate) / plate.area() << " % under the video window");
    CHECK(video->overlap(plate) <= 0.05f * plate.area());
  }
}
