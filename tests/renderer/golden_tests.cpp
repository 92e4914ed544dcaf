// Golden images of the demo scene (tests/golden/*.png, 320x180), rendered on lavapipe with the
// validation layer on. Regenerate with scripts/approve-goldens.sh after an intended change.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include <catch2/catch.hpp>

#include "image_compare.hpp"
#include "render_fixture.hpp"
#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/demo_frame.hpp"

using namespace vt;
using namespace vt::test;

TEST_CASE("golden mono demo scene", "[renderer][golden]") {
  const auto images = renderDemo({}, false, false);
  REQUIRE(images.size() == 1);
  checkGolden(images[0], "render_mono");
}

TEST_CASE("golden stereo demo scene left and right", "[renderer][golden]") {
  const auto images = renderDemo({}, true, false);
  REQUIRE(images.size() == 2);
  checkGolden(images[0], "render_stereo_left");
  checkGolden(images[1], "render_stereo_right");
}

TEST_CASE("golden vibration overlay demo scene", "[renderer][golden]") {
  const auto images = renderDemo({}, false, true);
  REQUIRE(images.size() == 1);
  checkGolden(images[0], "render_overlay");
}

TEST_CASE("golden contact ring under the demo hand", "[renderer][golden]") {
  // The demo frame (the hand's shadow falls on the second plate) plus a ring where the index
  // fingertip would touch the checker plate.
  renderer::FrameDesc frame = renderer::makeDemoFrame(makeDemoScene({}), kGoldenWidth, kGoldenHeight, false, false);
  frame.contacts = {{{-0.075f, 0.006f, 0.02f}, {0.0f, 1.0f, 0.0f}, 0.7f}};
  checkGolden(renderFrames({frame})[0][0], "render_contact");
}

// Both hands close up, palms down over the table, fingers curled differently: the skinned mesh
// (right, and the mirrored left) or the primitives of `--hand skeleton`.
static renderer::FrameDesc closeUpHands(renderer::HandStyle style) {
  renderer::FrameDesc frame;
  OrbitCamera camera;
  camera.target = {0.0f, 0.05f, 0.0f};
  camera.distance_m = 0.32f;
  camera.pitch_rad = -0.6f;
  camera.yaw_rad = 0.25f;
  frame.views = {camera.view(float(kGoldenWidth) / float(kGoldenHeight))};
  for (const bool left : {false, true}) {
    const float side = left ? -1.0f : 1.0f;
    const glm::mat4 T_world_palm = glm::rotate(glm::translate(glm::mat4(1.0f), {0.06f * side, 0.06f, 0.02f}), -0.25f,
                                               glm::vec3(1.0f, 0.0f, 0.0f));
    const FingerCurls curls = left ? FingerCurls{0.0f, 0.0f, 0.0f, 0.0f, 0.0f} : FingerCurls{0.3f, 0.05f, 0.6f, 0.7f, 0.75f};
    renderer::appendHand(poseHand(T_world_palm, curls, left), style, frame, left);
  }
  return frame;
}

TEST_CASE("golden skinned hands close up", "[renderer][golden][hand]") {
  const renderer::FrameDesc frame = closeUpHands(renderer::HandStyle::Mesh);
  REQUIRE(frame.hands.size() == 2);
  CHECK(frame.hand.empty());
  checkGolden(renderFrame(frame).at(0), "hands_mesh");
}

TEST_CASE("golden skeleton hands close up", "[renderer][golden][hand]") {
  const renderer::FrameDesc frame = closeUpHands(renderer::HandStyle::Skeleton);
  CHECK(frame.hands.empty());
  CHECK(frame.hand.size() == 2 * 50);  // 26 joints + 24 bones per hand
  checkGolden(renderFrame(frame).at(0), "hands_skeleton");
}

TEST_CASE("golden skeleton view of the demo scene", "[renderer][golden][hand]") {
  const auto images = renderDemo({}, false, false, renderer::HandStyle::Skeleton);
  checkGolden(images.at(0), "render_mono_skeleton");
}

TEST_CASE("golden comparison fails for a changed scene", "[renderer][golden]") {
  // variant 1 inverts the plates' second colours: the comparison must notice.
  const auto changed = renderDemo({.variant = 1}, false, false);
  const Image8 golden = loadImage8(sourceDir() / "tests/golden/render_mono.png", 4);
  const ImageDiff d = compareImages(changed[0], golden);
  INFO("PSNR " << d.psnr_db << " dB, max error " << d.maxError << ", bad pixels " << 100.0 * d.badFraction << "%");
  CHECK_FALSE(withinTolerance(d));
  CHECK(d.maxError > 100);
}

TEST_CASE("golden comparison metrics", "[renderer][golden]") {
  Image8 a(8, 4, 4);
  for (auto& p : a.pixels) p = 100;
  Image8 b = a;
  CHECK(compareImages(a, b).psnr_db == 99.0);
  CHECK(withinTolerance(compareImages(a, b)));
  b.at(3, 2, 1) = 200;  // one pixel, one channel off by 100
  const ImageDiff d = compareImages(a, b);
  CHECK(d.maxError == 100);
  CHECK(d.badFraction == Approx(1.0 / 32.0));
  // mse = 100^2 / (32 * 3)
  CHECK(d.psnr_db == Approx(10.0 * std::log10(255.0 * 255.0 * 96.0 / 10000.0)));
  CHECK_FALSE(withinTolerance(d));
  CHECK_THROWS_AS(compareImages(a, Image8(4, 4, 4)), Error);
}
