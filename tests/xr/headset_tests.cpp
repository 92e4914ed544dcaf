// vt::xr against xrsim: stereo rendering into runtime swapchains, lifecycle paths, fallbacks.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/offscreen_target.hpp"
#include "vt/scene/demo_scene.hpp"
#include "xr_fixture.hpp"

using vt::xr::SessionPhase;

namespace {

std::string frameName(int frame, const char* eye) {
  char name[48];
  std::snprintf(name, sizeof(name), "frame_%06d_%s.png", frame, eye);
  return name;
}

double meanAbsDiff(const vt::Image8& a, const vt::Image8& b) {
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); i += 4)
    for (int c = 0; c < 3; ++c) sum += std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c]));
  return sum / double(a.pixels.size() / 4 * 3);
}

vt::xr::HeadsetOptions validated() {
  vt::xr::HeadsetOptions options;
  options.validate = true;
  return options;
}

std::shared_ptr<const vt::Scene> demoScene() { return std::make_shared<const vt::Scene>(vt::makeDemoScene()); }

}  // namespace

TEST_CASE("xr draws the demo scene into xrsim swapchains as two eyes matching offscreen renders of the same views") {
  const auto dir = vt::test::outputDir("xr_stereo");
  vt::test::ScopedEnv scoped(vt::test::lookAtTableEnv(dir));
  const vt::xr::HeadsetOptions options = vt::test::fixedPlacement();
  const auto opened = vt::test::openValidatedHeadset(options);
  vt::xr::Headset& headset = *opened;
  CHECK(headset.runtimeName().find("xrsim") != std::string::npos);
  {
    vt::renderer::Renderer renderer(headset.device());
    renderer.setScene(demoScene());
    CHECK(vt::test::runLoop(headset, renderer, 400) == SessionPhase::Exiting);
    CHECK(headset.framesRendered() >= 10);
    renderer.waitIdle();

    // The same eyes rendered offscreen: the head at 1.6 m, pitched down, eyes 64 mm apart,
    // tan(half fov) = 1; the scene origin sits at options.T_stage_world.
    vt::renderer::OffscreenTarget offscreen(headset.device(), 256, 256, 1);
    std::array<vt::Image8, 2> captured;
    for (int eye = 0; eye < 2; ++eye) {
      vt::CameraView view;
      const glm::mat4 T_stage_head =
          glm::rotate(glm::translate(glm::mat4(1.0f), {0.0f, 1.6f, 0.0f}), vt::test::kTablePitch_rad, glm::vec3(1.0f, 0.0f, 0.0f));
      const glm::mat4 T_stage_eye = glm::translate(T_stage_head, {eye == 0 ? -0.032f : 0.032f, 0.0f, 0.0f});
      view.T_world_eye = glm::inverse(options.T_stage_world) * T_stage_eye;
      view.tanLeft = view.tanDown = -1.0f;
      view.tanRight = view.tanUp = 1.0f;
      view.near_m = options.near_m;
      view.far_m = options.far_m;
      vt::renderer::FrameDesc frame;
      frame.views = {view};
      renderer.render(offscreen, frame);
      const vt::Image8 expected = offscreen.readback();
      captured[std::size_t(eye)] = vt::loadImage8(dir / frameName(10, eye == 0 ? "left" : "right"), 4);
      vt::savePng(dir / vt::str("expected_", eye == 0 ? "left" : "right", ".png"), expected);
      INFO("eye " << eye);
      CHECK(meanAbsDiff(captured[std::size_t(eye)], expected) < 1.0);
    }
    // The eyes see the table from 64 mm apart: clearly different pictures.
    CHECK(meanAbsDiff(captured[0], captured[1]) > 2.0);
  }
  CHECK(headset.device()->validationEnabled());
  CHECK(headset.device()->validationMessageCount() == 0);
}

TEST_CASE("xr session ends cleanly when the app requests exit") {
  const auto dir = vt::test::outputDir("xr_request_exit");
  vt::test::ScopedEnv scoped(vt::test::xrsimEnv(dir, 0));
  auto opened = vt::xr::Headset::open(validated());
  REQUIRE(opened.headset);
  vt::renderer::Renderer renderer(opened.headset->device());
  renderer.setScene(demoScene());
  CHECK(vt::test::runLoop(*opened.headset, renderer, 6) == SessionPhase::Running);
  opened.headset->requestExit();
  CHECK(vt::test::runLoop(*opened.headset, renderer, 10) == SessionPhase::Exiting);
  renderer.waitIdle();
  CHECK(opened.headset->device()->validationMessageCount() == 0);
}

TEST_CASE("xr session restarts when the runtime makes it READY again after stopping") {
  const auto dir = vt::test::outputDir("xr_restart");
  auto env = vt::test::xrsimEnv(dir, 6);
  env.insert_or_assign("XRSIM_RESTARTS", std::string("1"));
  vt::test::ScopedEnv scoped(env);
  auto opened = vt::xr::Headset::open(validated());
  REQUIRE(opened.headset);
  vt::renderer::Renderer renderer(opened.headset->device());
  renderer.setScene(demoScene());
  CHECK(vt::test::runLoop(*opened.headset, renderer, 100) == SessionPhase::Exiting);
  // Two runs of 6 frames, each with its first frame not shown (still SYNCHRONIZED).
  CHECK(opened.headset->framesRendered() == 10);
  renderer.waitIdle();
  CHECK(opened.headset->device()->validationMessageCount() == 0);
}

TEST_CASE("xr reports session loss and instance loss and a reopened headset runs again") {
  for (const char* instanceLoss : {"0", "1"}) {
    INFO("instance loss " << instanceLoss);
    const auto dir = vt::test::outputDir(vt::str("xr_loss_", instanceLoss));
    {
      auto env = vt::test::xrsimEnv(dir, 0);
      env.insert_or_assign("XRSIM_LOSE_AFTER_FRAMES", std::string("4"));
      env.insert_or_assign("XRSIM_LOSE_INSTANCE", std::string(instanceLoss));
      vt::test::ScopedEnv scoped(env);
      auto opened = vt::xr::Headset::open(validated());
      REQUIRE(opened.headset);
      vt::renderer::Renderer renderer(opened.headset->device());
      renderer.setScene(demoScene());
      // Vibrating after every frame: the call that meets the lost session must not throw.
      vt::xr::Headset& headset = *opened.headset;
      CHECK(vt::test::runLoop(headset, renderer, 50, [&] { headset.vibrate(1, 0.5f, 160.0f, 11'000'000); }) ==
            SessionPhase::LossPending);
      CHECK(opened.headset->framesRendered() == 3);
      renderer.waitIdle();
      CHECK(opened.headset->device()->validationMessageCount() == 0);
    }
    // The clean restart: everything destroyed, then opened again.
    vt::test::ScopedEnv scoped(vt::test::xrsimEnv(dir, 5));
    auto reopened = vt::xr::Headset::open(validated());
    REQUIRE(reopened.headset);
    vt::renderer::Renderer renderer(reopened.headset->device());
    renderer.setScene(demoScene());
    CHECK(vt::test::runLoop(*reopened.headset, renderer, 50) == SessionPhase::Exiting);
    CHECK(reopened.headset->framesRendered() == 4);
    renderer.waitIdle();
    CHECK(reopened.headset->device()->validationMessageCount() == 0);
  }
}

TEST_CASE("xr falls back with one clear line when there is no runtime, no HMD or a refused session") {
  const auto dir = vt::test::outputDir("xr_fallback");
  {
    vt::test::ScopedEnv scoped({{"XR_RUNTIME_JSON", (dir / "missing_runtime.json").string()}});
    // Nothing else reaches stderr (the loader's own error lines are silenced): the app prints
    // opened.message as the one line.
    std::fflush(stderr);
    const int savedStderr = dup(2);
    const int capture = ::open((dir / "stderr.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(capture, 2);
    const auto opened = vt::xr::Headset::open(validated());
    std::fflush(stderr);
    dup2(savedStderr, 2);
    close(savedStderr);
    close(capture);
    CHECK(std::filesystem::file_size(dir / "stderr.txt") == 0);
    CHECK_FALSE(opened.headset);
    CHECK(opened.reason == vt::xr::Unavailable::NoRuntime);
    CHECK(opened.message.find("no OpenXR runtime") != std::string::npos);
    CHECK(opened.message.find('\n') == std::string::npos);
  }
  const std::pair<const char*, vt::xr::Unavailable> cases[] = {
      {"no-hmd", vt::xr::Unavailable::NoHmd}, {"refuse-session", vt::xr::Unavailable::SessionRefused}};
  for (const auto& [failure, reason] : cases) {
    auto env = vt::test::xrsimEnv(dir, 0);
    env.insert_or_assign("XRSIM_FAILURE", std::string(failure));
    vt::test::ScopedEnv scoped(env);
    const auto opened = vt::xr::Headset::open(validated());
    INFO(failure << ": " << opened.message);
    CHECK_FALSE(opened.headset);
    CHECK(opened.reason == reason);
    CHECK(opened.message.find(vt::xr::describe(reason)) != std::string::npos);
    CHECK(opened.message.find("xrsim") != std::string::npos);
  }
}

TEST_CASE("xr enables extra Vulkan extensions through the runtime and drops them when refused") {
  const auto dir = vt::test::outputDir("xr_extra_extensions");
  vt::test::ScopedEnv scoped(vt::test::xrsimEnv(dir, 0));
  vt::xr::HeadsetOptions options = validated();
  options.vulkanDeviceExtensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};  // what a mirror window needs
  {
    auto opened = vt::xr::Headset::open(options);
    INFO(opened.message);
    REQUIRE(opened.headset);
    CHECK(opened.headset->extraVulkanExtensions());
  }
  // A device extension no driver has: the headset still opens (without the extras) and renders.
  options.vulkanDeviceExtensions.push_back("VK_VT_no_such_extension");
  auto opened = vt::xr::Headset::open(options);
  INFO(opened.message);
  REQUIRE(opened.headset);
  CHECK_FALSE(opened.headset->extraVulkanExtensions());
  vt::renderer::Renderer renderer(opened.headset->device());
  renderer.setScene(demoScene());
  CHECK(vt::test::runLoop(*opened.headset, renderer, 6) == SessionPhase::Running);
  CHECK(opened.headset->framesRendered() > 0);
  renderer.waitIdle();
  CHECK(opened.headset->device()->validationMessageCount() == 0);
}
