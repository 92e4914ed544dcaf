// vt::xr places the scene in front of the head (first located frame, recenter()), on xrsim
// without any look-at-table script: the table is in view and a re-centre brings it back.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "test_support.hpp"
#include "vt/scene/demo_scene.hpp"
#include "xr_fixture.hpp"

using vt::xr::SessionPhase;

namespace {

// Share of the lower centre of an eye image (middle third across, bottom 40 %) in the demo
// table's wood colours (brown: red over green over blue); the sky and the plates are not.
double woodInLowerCentre(const std::filesystem::path& png) {
  const vt::Image8 image = vt::loadImage8(png, 4);
  std::size_t wood = 0, all = 0;
  for (int y = image.height * 6 / 10; y < image.height; ++y) {
    for (int x = image.width / 3; x < image.width * 2 / 3; ++x, ++all) {
      const int r = image.at(x, y, 0), g = image.at(x, y, 1), b = image.at(x, y, 2);
      if (r > g && g > b && r - b > 40) ++wood;
    }
  }
  return double(wood) / double(all);
}

// xrsim for 80 frames, saving every 10th eye image, with a head that looks straight ahead,
// turns 90 degrees left between 0.3 s and 0.5 s (frames 27-45 at 90 Hz) and stays there.
std::map<std::string, std::string> headTurnEnv(const std::filesystem::path& dir) {
  std::ofstream(dir / "script.json") << R"({"keyframes": [
    {"t": 0.0, "head": {"position": [0, 1.6, 0], "orientation": [0, 0, 0, 1]}},
    {"t": 0.3, "head": {"orientation": [0, 0, 0, 1]}},
    {"t": 0.5, "head": {"orientation": [0, 0.7071068, 0, 0.7071068]}}]})";
  auto env = vt::test::xrsimEnv(dir, 80);
  env.insert_or_assign("XRSIM_SAVE_EVERY", std::string("10"));
  env.insert_or_assign("XRSIM_SCRIPT", (dir / "script.json").string());
  return env;
}

std::string leftEye(int frame) {
  char name[48];
  std::snprintf(name, sizeof name, "frame_%06d_left.png", frame);
  return name;
}

}  // namespace

TEST_CASE("xr scene placement: in front of the head along its yaw, at a table height in STAGE") {
  const vt::xr::HeadsetOptions options;
  const glm::mat4 standing = glm::translate(glm::mat4(1.0f), {0.0f, 1.6f, 0.0f});
  const glm::mat4 T = vt::xr::sceneInFrontOfHead(standing, true, options);
  CHECK(T[3].x == Approx(0.0f).margin(1e-6));
  CHECK(T[3].y == Approx(1.05f));  // a standing user's bench at elbow height: 0.55 m below eyes at 1.6 m
  CHECK(T[3].z == Approx(-0.45f));  // within forearm reach
  // Tall or tracked oddly high: no higher than a tall user's bench.
  CHECK(vt::xr::sceneInFrontOfHead(glm::translate(glm::mat4(1.0f), {0.0f, 2.5f, 0.0f}), true, options)[3].y ==
        Approx(options.tableMaxHeight_m));
  CHECK(T[3].z == Approx(-options.tableAhead_m));
  CHECK(T[0].x == Approx(1.0f));  // facing -Z: the scene as authored
  // Turned 90 degrees left and pitched down: ahead is -X, the scene's -Z points there.
  const glm::mat4 turned = glm::rotate(glm::rotate(standing, glm::radians(90.0f), {0.0f, 1.0f, 0.0f}), -0.7f,
                                       {1.0f, 0.0f, 0.0f});
  const glm::mat4 U = vt::xr::sceneInFrontOfHead(turned, true, options);
  CHECK(U[3].x == Approx(-options.tableAhead_m));
  CHECK(U[3].z == Approx(0.0f).margin(1e-5));
  CHECK(glm::vec3(U * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)).x == Approx(-1.0f));
  // Looking straight down: ahead is where the top of the head points.
  const glm::mat4 down = glm::rotate(standing, glm::radians(-90.0f), {1.0f, 0.0f, 0.0f});
  CHECK(vt::xr::sceneInFrontOfHead(down, true, options)[3].z == Approx(-options.tableAhead_m));
  // Seated: a desk's height; LOCAL (no floor): below the eyes whatever the height.
  const glm::mat4 seated = glm::translate(glm::mat4(1.0f), {0.0f, 1.2f, 0.0f});
  CHECK(vt::xr::sceneInFrontOfHead(seated, true, options)[3].y == Approx(options.tableMinHeight_m));
  CHECK(vt::xr::sceneInFrontOfHead(standing, false, options)[3].y == Approx(1.6f - options.tableBelowEyes_m));
}

TEST_CASE("xr without a script shows the table, and a re-centre after the head turned brings it back") {
  const auto dir = vt::test::outputDir("xr_placement");
  vt::test::ScopedEnv scoped(headTurnEnv(dir));
  const auto headset = vt::test::openValidatedHeadset();
  {
    vt::renderer::Renderer renderer(headset->device());
    renderer.setScene(std::make_shared<const vt::Scene>(vt::makeDemoScene()));
    int frames = 0;
    CHECK(vt::test::runLoop(*headset, renderer, 400, [&] {
            if (++frames == 55) headset->recenter();
          }) == SessionPhase::Exiting);
    renderer.waitIdle();
  }
  CHECK(headset->placements() == 2);
  const double before = woodInLowerCentre(dir / leftEye(10));
  const double turned = woodInLowerCentre(dir / leftEye(50));
  const double recentred = woodInLowerCentre(dir / leftEye(70));
  INFO("wood in the lower centre: " << before << " looking ahead, " << turned << " turned, " << recentred
                                    << " re-centred");
  CHECK(before > 0.3);
  CHECK(turned < 0.05);
  CHECK(recentred > 0.3);
  CHECK(headset->device()->validationMessageCount() == 0);
}

TEST_CASE("xr places the scene again when the runtime re-centres (reference space change pending)") {
  const auto dir = vt::test::outputDir("xr_runtime_recenter");
  // The runtime's re-centre comes after frame 55, once the head has turned.
  auto env = headTurnEnv(dir);
  env.insert_or_assign("XRSIM_RECENTER_AFTER_FRAMES", std::string("55"));
  vt::test::ScopedEnv scoped(env);
  const auto headset = vt::test::openValidatedHeadset();
  {
    vt::renderer::Renderer renderer(headset->device());
    renderer.setScene(std::make_shared<const vt::Scene>(vt::makeDemoScene()));
    CHECK(vt::test::runLoop(*headset, renderer, 400) == SessionPhase::Exiting);
    renderer.waitIdle();
  }
  CHECK(headset->placements() == 2);
  CHECK(woodInLowerCentre(dir / leftEye(50)) < 0.05);
  CHECK(woodInLowerCentre(dir / leftEye(70)) > 0.3);
}

TEST_CASE("xr hand poses after a re-centre begin a new pose-history segment even when nothing moved") {
  const auto dir = vt::test::outputDir("xr_recenter_jump");
  vt::test::ScopedEnv scoped(vt::test::xrsimEnv(dir, 40));  // the head and controllers hold still
  vt::PoseHistory poses;
  vt::xr::HeadsetOptions options;
  options.handOutputs[1] = &poses;
  const auto headset = vt::test::openValidatedHeadset(options);
  std::vector<std::uint32_t> segments;
  std::vector<glm::vec3> wrists;
  {
    vt::renderer::Renderer renderer(headset->device());
    renderer.setScene(std::make_shared<const vt::Scene>(vt::makeDemoScene()));
    int frames = 0;
    vt::test::runLoop(*headset, renderer, 200, [&] {
      vt::HandPose pose;
      std::uint32_t segment = 0;
      REQUIRE(poses.at(poses.published() - 1, pose, segment));
      segments.push_back(segment);
      wrists.push_back(pose.position[0]);
      if (++frames == 20) headset->recenter();
    });
    renderer.waitIdle();
  }
  REQUIRE(segments.size() >= 30);
  CHECK(headset->placements() == 2);
  // Frames 2..19 continue one segment; the pose after the re-centre starts another, in the same place.
  CHECK(segments[18] == segments[2]);
  CHECK(segments[20] != segments[18]);
  CHECK(segments[29] == segments[20]);
  CHECK(glm::length(wrists[20] - wrists[18]) < 1e-4f);
}
