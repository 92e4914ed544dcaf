#include "modes/desktop_input.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <GLFW/glfw3.h>

#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"

namespace vt::app {
namespace {

constexpr float kMoveSpeed_mps = 0.15f;
constexpr float kTurnSpeed_radps = 1.2f;
constexpr float kScrollPress_m = 0.002f;  // per wheel notch
constexpr float kOrbit_radPerPx = 0.006f;
constexpr std::size_t kMaxScriptKeys = 100'000;

// Minimum-jerk progress 0..1 over a move (zero velocity and acceleration at both ends).
double minimumJerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
}

glm::vec3 rayDirection(const CameraView& view, glm::vec2 cursor_px, glm::vec2 size_px) {
  const glm::vec2 t = cursor_px / size_px;
  const glm::vec3 eye{view.tanLeft + t.x * (view.tanRight - view.tanLeft), view.tanUp - t.y * (view.tanUp - view.tanDown),
                      -1.0f};
  return glm::normalize(glm::mat3(view.T_world_eye) * eye);
}

}  // namespace

CursorScript::Key CursorScript::at(std::int64_t t_ns) const {
  if (keys.empty()) return {};
  if (t_ns <= keys.front().t_ns) return keys.front();
  const auto next = std::upper_bound(keys.begin(), keys.end(), t_ns, [](std::int64_t t, const Key& k) { return t < k.t_ns; });
  if (next == keys.end()) return keys.back();
  const Key& a = *(next - 1);
  const Key& b = *next;
  const double s = minimumJerk(double(t_ns - a.t_ns) / double(b.t_ns - a.t_ns));
  return {t_ns, a.cursor + (b.cursor - a.cursor) * float(s), a.press};
}

CursorScript loadCursorScript(const std::string& path) {
  const std::string text = readInputFile(path, "cursor script", budget::kTextFileBytes);
  CursorScript script;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    double t_s = 0.0, x = 0.0, y = 0.0;
    int press = 0;
    if (!(fields >> t_s)) continue;  // blank or comment
    const std::string where = str(path, ": line ", number);
    if (!(fields >> x >> y >> press) || (press != 0 && press != 1))
      fail(where, ": expected 't_s x y press' (x, y: 0..1 of the window; press: 0 or 1)");
    if (!std::isfinite(t_s) || t_s < 0.0 || t_s > 3600.0) fail(where, ": time ", t_s, " s outside 0..3600");
    if (!(x >= 0.0 && x <= 1.0 && y >= 0.0 && y <= 1.0)) fail(where, ": cursor (", x, ", ", y, ") outside 0..1");
    const auto t_ns = std::int64_t(std::llround(t_s * 1e9));
    if (script.keys.empty() && t_ns != 0) fail(where, ": the first keyframe must be at time 0");
    if (!script.keys.empty() && t_ns <= script.keys.back().t_ns) fail(where, ": times must increase");
    if (script.keys.size() == kMaxScriptKeys) fail(where, ": more than ", kMaxScriptKeys, " keyframes");
    script.keys.push_back({t_ns, {float(x), float(y)}, press == 1});
  }
  if (script.keys.size() < 2) fail(path, ": a cursor script needs at least two keyframes");
  return script;
}

DesktopInput::DesktopInput(const LoadedScene& scene, renderer::WindowTarget& window, const renderer::ImGuiLayer& ui,
                           TouchPipeline& haptics, const DesktopOptions& options, const CursorScript* script,
                           std::int64_t start_ns)
    : m_scene(scene), m_window(window), m_ui(ui), m_haptics(haptics), m_options(options), m_script(script),
      m_start_ns(start_ns), m_camera(scene.scene->camera) {}

void DesktopInput::event(const renderer::WindowEvent& e) {
  using Kind = renderer::WindowEvent::Kind;
  const bool uiMouse = m_ui.wantsMouse(), uiKeys = m_ui.wantsKeyboard();
  switch (e.kind) {
    case Kind::Cursor: {
      const glm::vec2 cursor{float(e.x), float(e.y)};
      if (m_right && !uiMouse && m_cursor_px.x >= 0.0f) m_orbit_px += cursor - m_cursor_px;
      m_cursorMoved = m_cursorMoved || (!m_right && !uiMouse && cursor != m_cursor_px);
      m_cursor_px = cursor;
      break;
    }
    case Kind::Button:
      if (e.code == GLFW_MOUSE_BUTTON_LEFT) {
        const bool down = e.action == GLFW_PRESS && !uiMouse;
        m_leftTapped = m_leftTapped || down;
        m_left = down;
      } else if (e.code == GLFW_MOUSE_BUTTON_RIGHT) {
        m_right = e.action == GLFW_PRESS;
      }
      break;
    case Kind::Scroll:
      if (!uiMouse) m_scroll += float(e.y);
      break;
    case Kind::Key: {
      if (e.action == GLFW_REPEAT) break;
      const bool down = e.action == GLFW_PRESS;
      if (down && uiKeys) break;  // typing into a panel; releases always count
      constexpr int kMoves[] = {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_UP, GLFW_KEY_DOWN};
      for (std::size_t k = 0; k < m_moveKeys.size(); ++k)
        if (e.code == kMoves[k]) m_moveKeys[k] = down;
      if (e.code == GLFW_KEY_LEFT) m_turn = down ? 1 : 0;
      if (e.code == GLFW_KEY_RIGHT) m_turn = down ? -1 : 0;
      if (down) m_pressedKeys.push_back(e.code);
      break;
    }
    case Kind::Char:
      break;
  }
}

void DesktopInput::scriptedSweep(std::int64_t since_ns) {
  // The tests' sweep: the cursor crosses the middle of the view at a constant speed in time over
  // (frames - 1) / 60 s, pressing from 4/60 s on, with the little finger curled and the view
  // orbited a little early on (exercises every path).
  const auto [w, h] = m_window.windowSize();
  const glm::vec2 size_px{float(std::max(1, w)), float(std::max(1, h))};
  const double duration_s = double(std::max(1, m_options.frames - 1)) / kScriptFrameRate_hz;
  const auto s = float(std::min(1.0, double(since_ns) * 1e-9 / duration_s));
  m_cursor_px = size_px * glm::vec2(0.38f + 0.12f * s, 0.42f);
  m_cursorMoved = true;
  m_left = double(since_ns) * 1e-9 >= 4.0 / kScriptFrameRate_hz;
  if (!m_scriptCurled && double(since_ns) * 1e-9 >= 1.0 / kScriptFrameRate_hz) {
    m_scriptCurled = true;
    m_pressedKeys.push_back(GLFW_KEY_5);  // little finger curled
  }
  if (!m_scriptOrbited && double(since_ns) * 1e-9 >= 2.0 / kScriptFrameRate_hz) {
    m_scriptOrbited = true;
    m_orbit_px.x += 20.0f;
  }
}

void DesktopInput::applyKeys(std::int64_t now_ns) {
  for (int key : m_pressedKeys) {
    if (key >= GLFW_KEY_1 && key < GLFW_KEY_1 + kFingerCount) m_hand.toggleCurl(key - GLFW_KEY_1);
    if (key == GLFW_KEY_Q) {
      m_hand.reset();
      m_resetPending = true;
    }
  }
  // Keys move relative to the camera's heading so W is always "away from the viewer".
  const float dt_s = m_last_ns ? std::min(0.1f, float(now_ns - m_last_ns) * 1e-9f) : 0.0f;
  const glm::vec3 forward = glm::normalize(glm::vec3(-std::sin(m_camera.yaw_rad), 0.0f, -std::cos(m_camera.yaw_rad)));
  const glm::vec3 right{-forward.z, 0.0f, forward.x};
  const glm::vec3 move{float(m_moveKeys[3]) - float(m_moveKeys[1]), float(m_moveKeys[4]) - float(m_moveKeys[5]),
                       float(m_moveKeys[2]) - float(m_moveKeys[0])};
  if (move != glm::vec3(0.0f) || m_turn != 0) {
    m_hand.move((right * move.x - forward * move.z + glm::vec3(0.0f, move.y, 0.0f)) * kMoveSpeed_mps * dt_s,
                float(m_turn) * kTurnSpeed_radps * dt_s, *m_scene.haptic->collision);
  }
}

bool DesktopInput::step(std::int64_t now_ns) {
  const std::int64_t since_ns = now_ns - m_start_ns;
  if (m_options.scripted) scriptedSweep(since_ns);
  if (m_script) {
    if (since_ns > m_script->duration_ns()) return false;  // the script's end is the run's
    const auto [w, h] = m_window.windowSize();
    const CursorScript::Key key = m_script->at(since_ns);
    m_cursor_px = key.cursor * glm::vec2(float(std::max(1, w)), float(std::max(1, h)));
    m_cursorMoved = true;
    m_left = key.press;
  }
  for (int key : m_pressedKeys)
    if (key == GLFW_KEY_ESCAPE) return false;
  m_camera.yaw_rad -= m_orbit_px.x * kOrbit_radPerPx;
  m_camera.pitch_rad = std::clamp(m_camera.pitch_rad - m_orbit_px.y * kOrbit_radPerPx, -1.5f, -0.05f);
  m_orbit_px = glm::vec2(0.0f);
  applyKeys(now_ns);
  if (FingerCurls flexion; m_options.gloveCurls && m_haptics.gloveFlexion(flexion)) m_hand.setCurlTargets(flexion);
  m_hand.addPress(m_scroll * kScrollPress_m);
  m_scroll = 0.0f;
  if (m_cursorMoved && m_cursor_px.x >= 0.0f) {
    const auto [w, h] = m_window.windowSize();
    const glm::vec2 size_px{float(std::max(1, w)), float(std::max(1, h))};
    const CameraView view = m_camera.view(size_px.x / size_px.y);
    m_hand.placeIndexTipOver(
        pickSurface(*m_scene.haptic->collision, view.position(), rayDirection(view, m_cursor_px, size_px)));
    m_cursorMoved = false;
  }
  // Scripted runs snap the curls (the sweep is short); the mouse eases them over real time.
  m_hand.update(m_options.scripted ? 1.0f : (m_last_ns ? float(now_ns - m_last_ns) * 1e-9f : 0.0f));
  const bool pressing = m_left || m_leftTapped;
  m_leftTapped = false;
  m_haptics.publishPose(m_hand.pose(pressing, now_ns), m_resetPending);  // a reset is a jump: never swept across
  m_resetPending = false;
  m_pressedKeys.clear();
  m_last_ns = now_ns;
  return true;
}

}  // namespace vt::app
