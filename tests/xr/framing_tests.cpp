// What a standing user sees through xrsim: the scene placed at a standing user's bench (at the
// head's first located frame, in STAGE), the controller hand posed palm down with its fingers
// forward, both eyes checked against their goldens with the validation layer on.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "image_compare.hpp"
#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/scene/demo_scene.hpp"
#include "vt/scene/image.hpp"
#include "xr_fixture.hpp"

namespace {

// The renderer's clear colour (FrameDesc::clearColor, linear 0.55 0.62 0.70) as the sRGB eye
// images store it: where nothing of the scene is.
bool background(const vt::Image8& image, int x, int y) {
  return std::abs(image.at(x, y, 0) - 194) < 8 && std::abs(image.at(x, y, 1) - 206) < 8 &&
         std::abs(image.at(x, y, 2) - 219) < 8;
}

// Share of the scene (not background) in rows [y0, y1) of the middle third of the columns.
double sceneShare(const vt::Image8& image, double y0, double y1) {
  std::size_t scene = 0, all = 0;
  for (int y = int(y0 * image.height); y < int(y1 * image.height); ++y)
    for (int x = image.width / 3; x < image.width * 2 / 3; ++x, ++all) scene += !background(image, x, y);
  return double(scene) / double(all);
}

std::string eyeFile(int frame, const char* eye) {
  char name[48];
  std::snprintf(name, sizeof name, "frame_%06d_%s.png", frame, eye);
  return name;
}

}  // namespace

TEST_CASE("xr frames a standing user's table and poses the controller hand palm down, fingers forward", "[golden]") {
  const auto dir = vt::test::outputDir("xr_standing");
  // Eyes at 1.65 m looking down 50 degrees; the right controller held over the table's near
  // plates, tilted down 10 degrees; the left hand away (untracked).
  std::ofstream(dir / "script.json") << R"({"keyframes": [{"t": 0,
    "head": {"position": [0, 1.65, 0.05], "orientation": [-0.4226183, 0, 0, 0.9063078]},
    "left": {"tracked": false},
    "right": {"tracked": true, "grip": {"position": [0.06, 1.16, -0.30], "orientation": [-0.0871557, 0, 0, 0.9961947]},
              "buttons": {"trigger": 0.0, "squeeze": 0.0}}}]})";
  auto env = vt::test::xrsimEnv(dir, 12);
  env.insert_or_assign("XRSIM_SAVE_EVERY", std::string("10"));
  env.insert_or_assign("XRSIM_SCRIPT", (dir / "script.json").string());
  env.insert_or_assign("XRSIM_HAND_TRACKING", std::string("0"));
  vt::test::ScopedEnv scoped(env);
  auto history = std::make_unique<vt::PoseHistory>();
  vt::xr::HeadsetOptions options;  // placed at the head, STAGE
  options.handOutputs[1] = history.get();
  const auto headset = vt::test::openValidatedHeadset(options);
  {
    vt::renderer::Renderer renderer(headset->device());
    renderer.setScene(std::make_shared<const vt::Scene>(vt::makeDemoScene()));
    CHECK(vt::test::runLoop(*headset, renderer, 400, {}, history.get()) == vt::xr::SessionPhase::Exiting);
    renderer.waitIdle();
  }
  CHECK(headset->placements() == 1);

  // The hand: palm down (the back of the hand up), fingers away from the user, as the grip is held.
  vt::HandPose hand;
  REQUIRE(history->newest(hand));
  REQUIRE(hand.valid);
  const glm::quat palm = hand.orientation[std::size_t(vt::HandJoint::Palm)];
  const glm::vec3 backOfHand = palm * glm::vec3(0.0f, 1.0f, 0.0f), fingers = palm * glm::vec3(0.0f, 0.0f, -1.0f);
  INFO("back of the hand " << backOfHand.x << " " << backOfHand.y << " " << backOfHand.z << ", fingers " << fingers.x
                           << " " << fingers.y << " " << fingers.z);
  CHECK(backOfHand.y > 0.95f);
  CHECK(fingers.z < -0.95f);  // the scene faces the user: its -Z is away from them
  CHECK(hand.at(vt::HandJoint::IndexTip).z < hand.at(vt::HandJoint::Wrist).z - 0.1f);
  // The thumb of a right hand palm down is on the left.
  CHECK(hand.at(vt::HandJoint::ThumbTip).x < hand.at(vt::HandJoint::LittleTip).x - 0.04f);

  for (const char* eye : {"left", "right"}) {
    INFO(eye);
    const vt::Image8 image = vt::loadImage8(dir / eyeFile(10, eye), 4);
    // The table fills the middle of the view and most of its lower half, its far edge in view
    // with sky above it (before: the table in the upper part, the lower half empty).
    const double centre = sceneShare(image, 0.4, 0.75), lowerHalf = sceneShare(image, 0.5, 1.0);
    const double top = sceneShare(image, 0.0, 0.2);
    INFO("scene share: centre " << centre << ", lower half " << lowerHalf << ", top fifth " << top);
    CHECK(centre > 0.95);
    CHECK(lowerHalf > 0.5);
    CHECK(top < 0.05);
    vt::test::checkGolden(image, vt::str("xr_standing_", eye));
  }
  CHECK(headset->device()->validationMessageCount() == 0);
}
