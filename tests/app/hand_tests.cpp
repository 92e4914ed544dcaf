// The desktop hand and the visual proxy.
#include <catch2/catch.hpp>

#include "modes/contact_markers.hpp"
#include "modes/hand_control.hpp"
#include "vt/collision/collision_scene.hpp"
#include "vt/scene/demo_scene.hpp"

#include <glm/gtc/matrix_transform.hpp>

using namespace vt;

TEST_CASE("The desktop hand hovers over the picked point and presses into it", "[app][hand]") {
  auto scene = std::make_shared<const Scene>(makeDemoScene({.textureSize = 32}));
  const collision::CollisionScene world(scene);
  // Straight down onto the second plate (top at y = 0.006).
  const glm::vec3 hit = app::pickSurface(world, {-0.09f, 0.5f, 0.0f}, {0.0f, -1.0f, 0.0f});
  CHECK(hit.y == Approx(0.006f).margin(1e-4));
  CHECK(hit.x == Approx(-0.09f).margin(1e-4));
  // Missing everything falls back to the table plane y = 0.
  CHECK(app::pickSurface(world, {5.0f, 1.0f, 5.0f}, glm::normalize(glm::vec3(0.1f, -1.0f, 0.0f))).y == Approx(0.0f).margin(1e-5));

  app::DesktopHand hand;
  hand.placeIndexTipOver(hit);
  const HandPose hover = hand.pose(false, 0);
  const float r = hover.radius_m[std::size_t(HandJoint::IndexTip)];
  CHECK(hover.at(HandJoint::IndexTip).x == Approx(hit.x).margin(1e-4));
  CHECK(hover.at(HandJoint::IndexTip).y - r == Approx(hit.y + app::DesktopHand::kHover_m).margin(1e-4));
  const HandPose pressed = hand.pose(true, 0);
  CHECK(pressed.at(HandJoint::IndexTip).y - r == Approx(hit.y - app::DesktopHand::kClickPress_m).margin(1e-4));
  hand.addPress(0.004f);
  CHECK(hand.pose(true, 0).at(HandJoint::IndexTip).y - r == Approx(hit.y - 0.008f).margin(1e-4));
  hand.addPress(1.0f);
  CHECK(hand.press_m(true) == Approx(app::DesktopHand::kMaxPress_m));

  hand.toggleCurl(2);
  for (int i = 0; i < 100; ++i) hand.update(0.05f);
  CHECK(hand.curls()[2] > 0.85f);
  hand.reset();
  CHECK(hand.curls()[2] == 0.0f);
}

TEST_CASE("The visual proxy keeps pressed fingertips on the surface", "[app][hand]") {
  auto scene = std::make_shared<const Scene>(makeDemoScene({.textureSize = 32}));
  const collision::CollisionScene world(scene);
  app::DesktopHand hand;
  hand.placeIndexTipOver({-0.09f, 0.006f, 0.0f});
  hand.addPress(0.01f);
  const HandPose physical = hand.pose(true, 0);
  const HandPose drawn = app::visualProxy(physical, world);
  const auto tip = std::size_t(HandJoint::IndexTip);
  const float r = physical.radius_m[tip];
  CHECK(physical.position[tip].y - r < 0.006f - 0.01f);  // the physical tip is 14 mm deep
  CHECK(drawn.position[tip].y - r == Approx(0.006f).margin(2e-4));  // the drawn one rests on top
  CHECK(drawn.position[tip].x == Approx(physical.position[tip].x).margin(1e-4));
  // Nothing drawn sinks into any surface.
  for (int j = 0; j < kHandJointCount; ++j) {
    const auto c = world.sphereContact({drawn.position[std::size_t(j)], drawn.radius_m[std::size_t(j)]});
    CHECK((!c.hit() || c.depth_m < 1e-3f));
  }
  // A hand in the air is drawn where it is.
  const HandPose air = poseHand(glm::translate(glm::mat4(1.0f), {0.0f, 0.3f, 0.0f}), {});
  CHECK(app::visualProxy(air, world).position == air.position);
}

TEST_CASE("Keyboard motion stops at surfaces and Q still resets", "[app][hand]") {
  auto scene = std::make_shared<const Scene>(makeDemoScene({.textureSize = 32}));
  const collision::CollisionScene world(scene);
  const auto deepest = [&](const HandPose& pose) {  // over the index..little fingertips
    float d = 0.0f;
    for (int f = 1; f < kFingerCount; ++f) {
      const auto j = std::size_t(kFingertips[std::size_t(f)]);
      const auto c = world.sphereContact({pose.position[j], pose.radius_m[j]});
      if (c.hit()) d = std::max(d, c.depth_m);
    }
    return d;
  };
  app::DesktopHand hand;
  const HandPose start = hand.pose(false, 0);
  // The down arrow held for 2 s at 30 fps (0.15 m/s): 0.3 m down, more than the hand's height.
  for (int frame = 0; frame < 60; ++frame) hand.move({0.0f, -0.005f, 0.0f}, 0.0f, world);
  const HandPose down = hand.pose(false, 0);
  CHECK(down.at(HandJoint::Palm).y < start.at(HandJoint::Palm).y - 0.001f);  // it came down onto the plate
  CHECK(deepest(down) > app::DesktopHand::kClickPress_m - 0.0021f);            // and stopped within a 2 mm step
  CHECK(deepest(down) <= app::DesktopHand::kClickPress_m + 1e-4f);             // no deeper than a click
  const auto tip = std::size_t(HandJoint::IndexTip);
  CHECK(down.position[tip].y - down.radius_m[tip] > -app::DesktopHand::kClickPress_m - 1e-4f);  // above the tabletop
  // Sliding and turning while held down stays within the limit too.
  for (int frame = 0; frame < 60; ++frame) hand.move({0.004f, -0.005f, 0.002f}, 0.02f, world);
  CHECK(deepest(hand.pose(false, 0)) <= app::DesktopHand::kClickPress_m + 1e-4f);
  // Up always works.
  const float before = hand.pose(false, 0).at(HandJoint::Palm).y;
  hand.move({0.0f, 0.01f, 0.0f}, 0.0f, world);
  CHECK(hand.pose(false, 0).at(HandJoint::Palm).y == Approx(before + 0.01f).margin(1e-5));
  hand.reset();
  CHECK(hand.pose(false, 0).position == start.position);
}

TEST_CASE("Contact markers lie on the surface under the drawn fingertips that touch", "[app][hand]") {
  auto scene = std::make_shared<const Scene>(makeDemoScene({.textureSize = 32}));
  const collision::CollisionScene world(scene);
  app::DesktopHand hand;
  hand.placeIndexTipOver({-0.09f, 0.006f, 0.0f});  // the checker plate
  hand.addPress(0.005f);
  const HandPose drawn = app::visualProxy(hand.pose(true, 0), world);
  haptics::HapticConfig config;
  config.contacts = {{HandJoint::ThumbTip}, {HandJoint::IndexTip}};
  std::vector<haptics::ContactTrace> latest(2);
  latest[1].inContact = true;
  latest[1].intensity = 1.7f;  // clamped to the marker's 0..1
  std::vector<renderer::ContactMarker> markers;
  app::appendContactMarkers(latest, config, drawn, world, markers);
  REQUIRE(markers.size() == 1);  // the thumb trace does not touch
  const glm::vec3 tip = drawn.at(HandJoint::IndexTip);
  CHECK(markers[0].position_m.y == Approx(0.006f).margin(1e-4));  // on the plate's top
  CHECK(markers[0].position_m.x == Approx(tip.x).margin(1e-3));
  CHECK(markers[0].position_m.z == Approx(tip.z).margin(1e-3));
  CHECK(markers[0].normal.y == Approx(1.0f));
  CHECK(markers[0].intensity == 1.0f);
  // A hand lifted far from every surface gets no ring even while a trace still says it touches.
  markers.clear();
  const HandPose air = poseHand(glm::translate(glm::mat4(1.0f), {0.0f, 0.3f, 0.0f}), {});
  app::appendContactMarkers(latest, config, air, world, markers);
  CHECK(markers.empty());
}
