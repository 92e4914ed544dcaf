// Contact you can see: the hand's shadow on the table and the rings at contact points, checked
// against renders without them (validation layer on).
#include <cmath>

#include <catch2/catch.hpp>

#include "image_compare.hpp"
#include "render_fixture.hpp"
#include "vt/core/error.hpp"
#include "vt/renderer/demo_frame.hpp"
#include "vt/renderer/offscreen_target.hpp"
#include "vt/renderer/renderer.hpp"

using namespace vt;
using namespace vt::test;
using vt::renderer::ContactMarker;
using vt::renderer::FrameDesc;

namespace {

glm::vec2 project(const CameraView& view, glm::vec3 world) {
  const glm::vec4 clip = view.projection() * view.view() * glm::vec4(world, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return (ndc * 0.5f + 0.5f) * glm::vec2(kGoldenWidth, kGoldenHeight);
}

/// Mean luminance of the 3x3 pixels around `p`.
double meanLuminance(const Image8& image, glm::vec2 p) {
  double sum = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) sum += vt::test::luminance(image, int(p.x) + dx, int(p.y) + dy);
  return sum / 9.0;
}

struct Change {
  int pixels = 0;       // pixels that differ by more than 24 in some channel
  double total = 0.0;   // summed channel differences
};

/// How `image` differs from `base` within `radius` pixels of `centre`.
Change changeAround(const Image8& image, const Image8& base, glm::vec2 centre, int radius) {
  Change c;
  for (int y = int(centre.y) - radius; y <= int(centre.y) + radius; ++y) {
    for (int x = int(centre.x) - radius; x <= int(centre.x) + radius; ++x) {
      int diff = 0, largest = 0;
      for (int ch = 0; ch < 3; ++ch) {
        const int d = std::abs(int(image.at(x, y, ch)) - int(base.at(x, y, ch)));
        diff += d;
        largest = std::max(largest, d);
      }
      c.pixels += largest > 24;
      c.total += diff;
    }
  }
  return c;
}

}  // namespace

TEST_CASE("a contact ring appears at the contact point and grows with its intensity", "[renderer]") {
  const Scene scene = makeDemoScene({});
  FrameDesc none = renderer::makeDemoFrame(scene, kGoldenWidth, kGoldenHeight, false, false);
  none.hand.clear();  // nothing in front of the ring
  none.hands.clear();
  const glm::vec3 point{0.0f, 0.0f, 0.15f};  // on the table, between the plates and the viewer
  FrameDesc weak = none, strong = none;
  weak.contacts = {ContactMarker{point, {0.0f, 1.0f, 0.0f}, 0.2f}};
  strong.contacts = {ContactMarker{point, {0.0f, 1.0f, 0.0f}, 1.0f}};
  const auto images = renderFrames({none, weak, strong});
  const glm::vec2 centre = project(none.views[0], point);
  INFO("contact projects to " << centre.x << ", " << centre.y);
  const Change w = changeAround(images[1][0], images[0][0], centre, 20);
  const Change s = changeAround(images[2][0], images[0][0], centre, 20);
  INFO("weak ring: " << w.pixels << " px, strong ring: " << s.pixels << " px");
  CHECK(w.pixels > 10);
  CHECK(s.pixels > w.pixels * 3 / 2);  // larger
  CHECK(s.total > w.total * 1.5);      // and brighter
  // The ring is bluish-white on brown wood: at its rim the blue channel rises.
  const glm::vec2 rim = project(none.views[0], point + glm::vec3(0.9f * 0.03f, 0.0f, 0.0f));
  CHECK(images[2][0].at(int(rim.x), int(rim.y), 2) > images[0][0].at(int(rim.x), int(rim.y), 2) + 60);
  // Far from the contact nothing changed.
  CHECK(changeAround(images[2][0], images[0][0], {40.0f, 150.0f}, 10).pixels == 0);
}

TEST_CASE("too many contact markers are refused", "[renderer]") {
  auto device = validatingDevice();
  {
    renderer::Renderer r(device);
    renderer::OffscreenTarget target(device, 16, 16, 1);
    FrameDesc frame;
    frame.views = {CameraView{}};
    frame.contacts.resize(renderer::kMaxContactMarkers + 1);
    CHECK_THROWS_WITH(r.render(target, frame), Catch::Contains("contact markers"));
  }
  expectNoValidationMessages(*device);
}

TEST_CASE("the hand's shadow darkens the table under it, mono and stereo", "[renderer]") {
  const Scene scene = makeDemoScene({});
  const bool stereo = GENERATE(false, true);
  // Over the table's near left, middle and far right: shadows on different triangles of the
  // table top (the receiving and the plain pipeline must agree on depth over all of them).
  const glm::vec3 ball = GENERATE(glm::vec3(-0.3f, 0.15f, 0.2f), glm::vec3(0.02f, 0.15f, 0.12f), glm::vec3(0.35f, 0.15f, -0.1f));
  INFO((stereo ? "stereo" : "mono") << ", ball at " << ball.x << ", " << ball.y << ", " << ball.z);
  FrameDesc away = renderer::makeDemoFrame(scene, kGoldenWidth, kGoldenHeight, stereo, false);
  away.hands.clear();  // the ball is the only caster (the demo hand would hide the middle spot)
  // One sphere 15 cm above the table: its shadow falls along the light, beside it as seen from the camera.
  const glm::vec3 travel = scene.lightDirection;
  const glm::vec3 shadowCentre = ball + travel * (ball.y / -travel.y);
  FrameDesc casting = away;
  casting.hand = {{ball, ball, 0.02f, renderer::kHandColor}};
  away.hand = {{ball + glm::vec3(5.0f, 0.0f, 0.0f), ball + glm::vec3(5.0f, 0.0f, 0.0f), 0.02f, renderer::kHandColor}};
  const auto images = renderFrames({away, casting});
  for (std::size_t v = 0; v < away.views.size(); ++v) {
    const glm::vec2 p = project(away.views[v], shadowCentre);
    const double lit = meanLuminance(images[0][v], p), shadowed = meanLuminance(images[1][v], p);
    INFO("view " << v << " at " << p.x << ", " << p.y << ": lit " << lit << ", shadowed " << shadowed);
    CHECK(shadowed < 0.8 * lit);
    // The shadow is soft and bounded: well outside it the table is as lit as without the ball.
    const glm::vec2 outside = project(away.views[v], shadowCentre + glm::vec3(0.0f, 0.0f, 0.08f));
    CHECK(meanLuminance(images[1][v], outside) == Approx(meanLuminance(images[0][v], outside)).margin(1.0));
  }
}
