// vt::xr depth layers (XR_KHR_composition_layer_depth) against xrsim: submitted and accepted when
// offered, with plausible depth; colour only, as before, when the runtime does not offer them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "test_support.hpp"
#include "vt/scene/demo_scene.hpp"
#include "vt/scene/image.hpp"
#include "xr_fixture.hpp"

using vt::xr::SessionPhase;

namespace {

std::filesystem::path framePath(const std::filesystem::path& dir, int frame, const char* eye, const char* suffix) {
  char name[64];
  std::snprintf(name, sizeof(name), "frame_%06d_%s%s.png", frame, eye, suffix);
  return dir / name;
}

}  // namespace

TEST_CASE("xr submits depth layers that xrsim accepts and their depth places the table where it is") {
  const auto dir = vt::test::outputDir("xr_depth");
  vt::test::ScopedEnv scoped(vt::test::lookAtTableEnv(dir));
  const vt::xr::HeadsetOptions options = vt::test::fixedPlacement();
  const auto opened = vt::test::openValidatedHeadset(options);
  vt::xr::Headset& headset = *opened;
  CHECK(headset.depthLayers());
  const VkFormat format = headset.depthFormat();
  CHECK((format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D24_UNORM_S8_UINT || format == VK_FORMAT_D16_UNORM));
  {
    vt::renderer::Renderer renderer(headset.device());
    renderer.setScene(std::make_shared<const vt::Scene>(vt::makeDemoScene()));
    // xrEndFrame fails (and frame() throws) if xrsim rejects a depth info.
    CHECK(vt::test::runLoop(headset, renderer, 400) == SessionPhase::Exiting);
    CHECK(headset.framesRendered() >= 10);
  }
  for (const char* eye : {"left", "right"}) {
    INFO(eye);
    // xrsim read the released depth image back: window depth scaled to 0..65535.
    const vt::Image16 depth = vt::loadImage16(framePath(dir, 10, eye, "_depth"), 1);
    REQUIRE(depth.width == 256);
    REQUIRE(depth.height == 256);
    auto distance_m = [&](int x, int y) {
      const double d = depth.at(x, y) / 65535.0;
      return options.near_m * options.far_m / (options.far_m - d * (options.far_m - options.near_m));
    };
    // The view axis hits the table top (0.75 m high) from eyes at 1.6 m pitched 0.9 rad down:
    // 0.85 m / sin(0.9) = 1.09 m away (16-bit depth resolves ~2 cm there).
    CHECK(distance_m(128, 128) == Approx(0.85 / std::sin(0.9)).margin(0.08));
    // The table's near edge (low in the picture) is nearer than its middle, its far part
    // farther; above and below the table the sky keeps the clear depth 1.
    CHECK(depth.at(128, 200) < depth.at(128, 128));
    CHECK(depth.at(128, 128) < depth.at(128, 122));
    CHECK(depth.at(128, 20) == 65535);
    CHECK(depth.at(128, 250) == 65535);
    // Nothing is in front of the near plane.
    CHECK(std::count(depth.pixels.begin(), depth.pixels.end(), std::uint16_t(0)) == 0);
  }
  CHECK(headset.device()->validationMessageCount() == 0);
}

TEST_CASE("xr submits colour only when the runtime does not offer depth layers") {
  const auto dir = vt::test::outputDir("xr_no_depth");
  auto env = vt::test::lookAtTableEnv(dir);
  env.insert_or_assign("XRSIM_DEPTH_LAYERS", std::string("0"));
  vt::test::ScopedEnv scoped(env);
  const vt::xr::HeadsetOptions options = vt::test::fixedPlacement();
  const auto opened = vt::test::openValidatedHeadset(options);
  vt::xr::Headset& headset = *opened;
  CHECK_FALSE(headset.depthLayers());
  CHECK(headset.depthFormat() == VK_FORMAT_UNDEFINED);
  {
    vt::renderer::Renderer renderer(headset.device());
    renderer.setScene(std::make_shared<const vt::Scene>(vt::makeDemoScene()));
    CHECK(vt::test::runLoop(headset, renderer, 400) == SessionPhase::Exiting);
    CHECK(headset.framesRendered() >= 10);
  }
  CHECK(std::filesystem::exists(framePath(dir, 10, "left", "")));
  CHECK_FALSE(std::filesystem::exists(framePath(dir, 10, "left", "_depth")));
  CHECK(headset.device()->validationMessageCount() == 0);
}
