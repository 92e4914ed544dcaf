// Keys as events: a tap shorter than the interval between two reads is counted for its own
// length, digit taps queue up, and presses the UI took never move the hand. No window needed:
// the events go into the queue as GLFW's callbacks put them.
#include <catch2/catch.hpp>

#include <GLFW/glfw3.h>

#include "ui/input_events.hpp"
#include "vt/core/clock.hpp"

using vt::ui::InputEvent;

namespace {

constexpr std::int64_t kMs = 1'000'000;

InputEvent key(int code, bool pressed, std::int64_t t_ns, bool toUi = false) {
  return {InputEvent::Source::Key, code, pressed, toUi, t_ns};
}

}  // namespace

TEST_CASE("Input events: a 30 ms tap between two reads 200 ms apart moves the hand for 30 ms") {
  vt::ManualClock clock(1000 * kMs);
  vt::ui::InputEventQueue events(nullptr, clock);
  vt::ui::DesktopControls controls(events, clock);
  // A 5 fps frame: W tapped for 30 ms inside it. Polling at the frame would have seen nothing.
  events.push(key(GLFW_KEY_W, true, 1050 * kMs));
  events.push(key(GLFW_KEY_W, false, 1080 * kMs));
  clock.set(1200 * kMs);
  const vt::ui::ControlKeys first = controls.read();
  CHECK(first.move.z == Approx(-0.15f));  // held 30 of the 200 ms: the hand moves 30 ms' worth
  clock.set(1400 * kMs);
  CHECK(controls.read().move.z == 0.0f);  // counted once
  // Held across reads: each read gets its own share.
  events.push(key(GLFW_KEY_D, true, 1500 * kMs));
  clock.set(1600 * kMs);
  CHECK(controls.read().move.x == Approx(0.5f));
  clock.set(1800 * kMs);
  CHECK(controls.read().move.x == Approx(1.0f));
  events.push(key(GLFW_KEY_D, false, 1850 * kMs));
  clock.set(2000 * kMs);
  CHECK(controls.read().move.x == Approx(0.25f));
}

TEST_CASE("Input events: two digit taps in one frame curl two fingers, one per read, and Q and Esc are never missed") {
  vt::ManualClock clock;
  vt::ui::InputEventQueue events(nullptr, clock);
  vt::ui::DesktopControls controls(events, clock);
  events.push(key(GLFW_KEY_2, true, 10 * kMs));
  events.push(key(GLFW_KEY_2, false, 20 * kMs));
  events.push(key(GLFW_KEY_5, true, 30 * kMs));
  events.push(key(GLFW_KEY_5, false, 40 * kMs));
  events.push(key(GLFW_KEY_Q, true, 50 * kMs));
  events.push(key(GLFW_KEY_Q, false, 60 * kMs));
  events.push({InputEvent::Source::MouseButton, GLFW_MOUSE_BUTTON_LEFT, true, false, 70 * kMs});
  events.push({InputEvent::Source::MouseButton, GLFW_MOUSE_BUTTON_LEFT, false, false, 80 * kMs});
  clock.set(100 * kMs);
  const vt::ui::ControlKeys first = controls.read();
  CHECK(first.curlToggle == 1);  // index
  CHECK(first.reset);
  CHECK(first.clicked);          // a click shorter than the frame still presses
  CHECK_FALSE(first.quit);
  const vt::ui::ControlKeys second = controls.read();
  CHECK(second.curlToggle == 4);  // little, next read
  CHECK_FALSE(second.reset);
  CHECK(controls.read().curlToggle == -1);
  events.push(key(GLFW_KEY_ESCAPE, true, 120 * kMs));
  events.push(key(GLFW_KEY_ESCAPE, false, 121 * kMs));
  CHECK(controls.read().quit);
}

TEST_CASE("Input events: keys typed into the UI do not move the hand, and a release ends a hand press") {
  vt::ManualClock clock;
  vt::ui::InputEventQueue events(nullptr, clock);
  vt::ui::DesktopControls controls(events, clock);
  events.push(key(GLFW_KEY_A, true, 10 * kMs, true));  // typed into a text field
  events.push(key(GLFW_KEY_1, true, 20 * kMs, true));
  events.push(key(GLFW_KEY_ESCAPE, true, 30 * kMs, true));
  clock.set(100 * kMs);
  const vt::ui::ControlKeys typed = controls.read();
  CHECK(typed.move.x == 0.0f);
  CHECK(typed.curlToggle == -1);
  CHECK_FALSE(typed.quit);
  // Pressed for the hand, released while the UI had the keyboard: the press still ends.
  events.push(key(GLFW_KEY_W, true, 110 * kMs));
  events.push(key(GLFW_KEY_W, false, 150 * kMs, true));
  clock.set(200 * kMs);
  CHECK(controls.read().move.z == Approx(-0.4f));
  clock.set(300 * kMs);
  CHECK(controls.read().move.z == 0.0f);
}
