#pragma once
// The desktop's input, read on GLFW's main thread apart from the frame rate: window events
// (buttons and keys arrive as events, so a tap shorter than a frame is never lost) and a step
// at 1 kHz that moves the hand and publishes its pose, stamped with the time it was read, into
// the touch pipeline's pose history. The mouse can be replaced by a script evaluated at each
// step's time: the tests' fixed sweep (--scripted-input) or a cursor script file (--cursor-script).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "modes/desktop_mode.hpp"
#include "modes/hand_control.hpp"
#include "vt/renderer/imgui_layer.hpp"
#include "vt/renderer/window_target.hpp"
#include "vt/scene/camera.hpp"

namespace vt::app {

/// Scripted runs pace frames like a 60 Hz display: frame N starts at N / 60 s (later when
/// rendering is slower); the --scripted-input sweep lasts (frames - 1) / 60 s.
inline constexpr double kScriptFrameRate_hz = 60.0;

/// A scripted mouse: keyframes of the cursor (fractions of the window), joined by minimum-jerk
/// moves, and the left button's state from each keyframe on (docs/app.md, "Cursor scripts").
struct CursorScript {
  struct Key {
    std::int64_t t_ns = 0;
    glm::vec2 cursor{0.5f};  // 0..1 of the window's width and height
    bool press = false;
  };
  std::vector<Key> keys;  // ascending times, the first at 0

  /// The cursor and button at `t_ns` after the start (the last keyframe holds after the end).
  Key at(std::int64_t t_ns) const;
  std::int64_t duration_ns() const { return keys.empty() ? 0 : keys.back().t_ns; }
};

/// Reads a cursor script: lines "t_s x y press" (or comma-separated; '#' starts a comment).
/// Throws vt::Error naming the file, the line and what is wrong.
CursorScript loadCursorScript(const std::string& path);

class DesktopInput {
 public:
  /// `script` (may be null) and everything else must outlive the input. Main thread.
  DesktopInput(const LoadedScene& scene, renderer::WindowTarget& window, const renderer::ImGuiLayer& ui,
               TouchPipeline& haptics, const DesktopOptions& options, const CursorScript* script, std::int64_t start_ns);

  /// One window event, as GLFW delivers it (main thread, from WindowTarget's listener).
  void event(const renderer::WindowEvent& e);
  /// Moves the hand to where the input is at `now_ns` and publishes its pose stamped `now_ns`.
  /// False when the user or the script ended the run (Esc, the script's end). Main thread.
  bool step(std::int64_t now_ns);
  /// The camera the user orbited (right-drag).
  const OrbitCamera& camera() const { return m_camera; }

 private:
  void scriptedSweep(std::int64_t since_ns);
  void applyKeys(std::int64_t now_ns);

  const LoadedScene& m_scene;
  renderer::WindowTarget& m_window;
  const renderer::ImGuiLayer& m_ui;
  TouchPipeline& m_haptics;
  const DesktopOptions& m_options;
  const CursorScript* m_script;
  std::int64_t m_start_ns;
  std::int64_t m_last_ns = 0;
  DesktopHand m_hand;
  OrbitCamera m_camera;
  // The mouse and keys as the events left them.
  glm::vec2 m_cursor_px{-1.0f};
  bool m_cursorMoved = false;
  bool m_left = false, m_leftTapped = false;  // held; pressed since the last step
  bool m_right = false;
  float m_scroll = 0.0f;
  glm::vec2 m_orbit_px{0.0f};
  std::array<bool, 6> m_moveKeys{};  // W A S D, up, down
  int m_turn = 0;                    // left/right arrow held: +1 / -1
  std::vector<int> m_pressedKeys;    // keys pressed since the last step (1-5, Q, Esc), in order
  bool m_resetPending = false;
  // Scripted sweep state.
  bool m_scriptOrbited = false, m_scriptCurled = false;
};

}  // namespace vt::app
