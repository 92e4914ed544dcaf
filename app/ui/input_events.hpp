#pragma once
// Keys and mouse buttons as events, not polled states. GLFW's callbacks (run by glfwPollEvents
// on the main thread) stamp every press and release and queue it lock-free; the input code
// drains the queue at its own pace (the frame, or an input thread), so a tap shorter than a frame
// is never lost, and HeldKeys turns the events into how long each key was held. Polling
// glfwGetKey once per frame sees only the state at that instant: at 10 fps a 50 ms tap is missed
// half the time.
#include <array>
#include <cstdint>
#include <deque>

#include <glm/glm.hpp>

#include "vt/core/clock.hpp"
#include "vt/core/spsc_ring.hpp"

struct GLFWwindow;

namespace vt::ui {

/// One press or release (key repeats are not queued).
struct InputEvent {
  enum class Source : std::uint8_t { Key, MouseButton };
  Source source = Source::Key;
  int code = 0;           // GLFW_KEY_* or GLFW_MOUSE_BUTTON_*
  bool pressed = false;   // false: released
  bool toUi = false;      // the UI (ImGui) had the keyboard or mouse: not for the hand
  std::int64_t t_ns = 0;  // when the callback saw it (the clock given to the queue)
};

/// The queue of one window's input events: one producer (GLFW's callbacks, main thread), one
/// consumer (whichever thread drains it).
class InputEventQueue {
 public:
  /// Installs key and mouse-button callbacks on `window`, which call the ones installed before
  /// (ImGui's) first. Main thread; one queue per window; destroy it before the callbacks it
  /// chains to go (before the ImGuiLayer). A null window: events come only through push().
  explicit InputEventQueue(GLFWwindow* window, const Clock& clock = SteadyClock::instance(), std::size_t capacity = 256);
  /// Puts back the callbacks found at construction. Main thread.
  ~InputEventQueue();
  InputEventQueue(const InputEventQueue&) = delete;
  InputEventQueue& operator=(const InputEventQueue&) = delete;

  /// The oldest event not yet taken; false when there is none. The consumer thread only.
  bool pop(InputEvent& out) noexcept { return m_ring.pop(out); }
  /// Events refused because the consumer fell a whole queue behind.
  std::uint64_t dropped() const noexcept { return m_ring.dropped(); }
  /// Queues an event as the callbacks do (tests, scripted input). Producer thread only.
  void push(const InputEvent& event) noexcept { m_ring.push(event); }

 private:
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void onMouseButton(GLFWwindow* window, int button, int action, int mods);

  GLFWwindow* m_window;
  const Clock& m_clock;
  SpscRing<InputEvent> m_ring;
  void (*m_previousKey)(GLFWwindow*, int, int, int, int) = nullptr;
  void (*m_previousButton)(GLFWwindow*, int, int, int) = nullptr;
};

/// Which keys are down and for how long, from the events in the order they happened. One thread.
class HeldKeys {
 public:
  static constexpr int kKeyCount = 512;  // GLFW_KEY_LAST is 348
  /// Applies one key event (others are ignored). A press the UI took does not count; its release
  /// still ends a press that began for the hand.
  void apply(const InputEvent& event) noexcept;
  bool down(int key) const noexcept;
  /// Seconds `key` was held since the previous call for it (or since the start), up to now_ns:
  /// a tap between two calls counts for exactly its length.
  double takeHeld_s(int key, std::int64_t now_ns) noexcept;

 private:
  struct Key {
    bool down = false;
    std::int64_t since_ns = 0;  // pressed at, or last counted up to
    std::int64_t held_ns = 0;   // not yet taken
  };
  std::array<Key, kKeyCount> m_keys{};
};

/// The desktop controls over one interval, from the events in it (docs/app.md "Controls").
struct ControlKeys {
  glm::vec3 move{0.0f};   // share of the interval D-A (x), arrow up-down (y), S-W (z) were held: -1..1
  float turn = 0.0f;      // left-right arrows, -1..1
  int curlToggle = -1;    // keys 1-5: a finger to curl or straighten (further taps wait for the next read)
  bool reset = false;     // Q went down
  bool quit = false;      // Esc went down
  bool clicked = false;   // the left mouse button went down (a click shorter than the interval still presses)
};

/// Drains a window's InputEventQueue into the desktop controls: the input code calls read() at
/// its own rate. The queue's consumer thread only.
class DesktopControls {
 public:
  explicit DesktopControls(InputEventQueue& events, const Clock& clock = SteadyClock::instance());
  /// What happened since the previous read.
  ControlKeys read();

 private:
  InputEventQueue& m_events;
  const Clock& m_clock;
  HeldKeys m_held;
  std::deque<int> m_toggles;
  std::int64_t m_last_ns;
};

}  // namespace vt::ui
