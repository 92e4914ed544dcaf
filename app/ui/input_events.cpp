#include "ui/input_events.hpp"

#include <algorithm>
#include <array>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "vt/core/error.hpp"

namespace vt::ui {
namespace {

// GLFW callbacks are plain functions and the window's user pointer belongs to the WindowTarget:
// the queues are found by their window. Main thread only, like every GLFW callback.
std::array<InputEventQueue*, 4> g_queues{};
std::array<GLFWwindow*, 4> g_windows{};

InputEventQueue* queueOf(GLFWwindow* window) {
  for (std::size_t i = 0; i < g_windows.size(); ++i)
    if (g_windows[i] == window) return g_queues[i];
  return nullptr;
}

// Whether ImGui wants this input (a text field, a hovered panel): read on the main thread, at
// the event, as ImGui decided it in the last frame.
bool imguiWants(InputEvent::Source source) {
  if (ImGui::GetCurrentContext() == nullptr) return false;
  const ImGuiIO& io = ImGui::GetIO();
  return source == InputEvent::Source::Key ? io.WantCaptureKeyboard : io.WantCaptureMouse;
}

}  // namespace

InputEventQueue::InputEventQueue(GLFWwindow* window, const Clock& clock, std::size_t capacity)
    : m_window(window), m_clock(clock), m_ring(capacity) {
  if (window == nullptr) return;
  const auto slot = std::find(g_windows.begin(), g_windows.end(), nullptr);
  if (std::find(g_windows.begin(), g_windows.end(), window) != g_windows.end() || slot == g_windows.end())
    fail("input events: a queue already exists for this window (or too many windows)");
  g_queues[std::size_t(slot - g_windows.begin())] = this;
  *slot = window;
  m_previousKey = glfwSetKeyCallback(window, &InputEventQueue::onKey);
  m_previousButton = glfwSetMouseButtonCallback(window, &InputEventQueue::onMouseButton);
}

InputEventQueue::~InputEventQueue() {
  if (m_window == nullptr) return;
  // Put back what was there, unless ours was replaced meanwhile (then theirs stays).
  if (const auto current = glfwSetKeyCallback(m_window, m_previousKey); current != &InputEventQueue::onKey)
    glfwSetKeyCallback(m_window, current);
  if (const auto current = glfwSetMouseButtonCallback(m_window, m_previousButton); current != &InputEventQueue::onMouseButton)
    glfwSetMouseButtonCallback(m_window, current);
  for (std::size_t i = 0; i < g_windows.size(); ++i) {
    if (g_windows[i] == m_window) g_windows[i] = nullptr, g_queues[i] = nullptr;
  }
}

void InputEventQueue::onKey(GLFWwindow* window, int key, int scancode, int action, int mods) {
  InputEventQueue* queue = queueOf(window);
  if (queue == nullptr) return;
  if (queue->m_previousKey) queue->m_previousKey(window, key, scancode, action, mods);  // ImGui first
  if (action == GLFW_REPEAT || key < 0) return;
  queue->push({InputEvent::Source::Key, key, action == GLFW_PRESS, imguiWants(InputEvent::Source::Key),
               queue->m_clock.now_ns()});
}

void InputEventQueue::onMouseButton(GLFWwindow* window, int button, int action, int mods) {
  InputEventQueue* queue = queueOf(window);
  if (queue == nullptr) return;
  if (queue->m_previousButton) queue->m_previousButton(window, button, action, mods);
  queue->push({InputEvent::Source::MouseButton, button, action == GLFW_PRESS, imguiWants(InputEvent::Source::MouseButton),
               queue->m_clock.now_ns()});
}

void HeldKeys::apply(const InputEvent& event) noexcept {
  if (event.source != InputEvent::Source::Key || event.code < 0 || event.code >= kKeyCount) return;
  Key& k = m_keys[std::size_t(event.code)];
  if (event.pressed && !k.down && !event.toUi) {
    k.down = true;
    k.since_ns = event.t_ns;
  } else if (!event.pressed && k.down) {
    k.held_ns += std::max<std::int64_t>(0, event.t_ns - k.since_ns);
    k.down = false;
  }
}

bool HeldKeys::down(int key) const noexcept {
  return key >= 0 && key < kKeyCount && m_keys[std::size_t(key)].down;
}

DesktopControls::DesktopControls(InputEventQueue& events, const Clock& clock)
    : m_events(events), m_clock(clock), m_last_ns(clock.now_ns()) {}

ControlKeys DesktopControls::read() {
  ControlKeys out;
  InputEvent e;
  while (m_events.pop(e)) {
    m_held.apply(e);
    if (e.toUi || !e.pressed) continue;
    if (e.source == InputEvent::Source::MouseButton) {
      out.clicked |= e.code == GLFW_MOUSE_BUTTON_LEFT;
    } else if (e.code >= GLFW_KEY_1 && e.code <= GLFW_KEY_5) {
      if (m_toggles.size() < 16) m_toggles.push_back(e.code - GLFW_KEY_1);
    } else {
      out.reset |= e.code == GLFW_KEY_Q;
      out.quit |= e.code == GLFW_KEY_ESCAPE;
    }
  }
  const std::int64_t now = m_clock.now_ns();
  const double interval_s = std::max(1e-3, double(now - m_last_ns) * 1e-9);
  m_last_ns = now;
  const auto held = [&](int key) { return float(std::min(1.0, m_held.takeHeld_s(key, now) / interval_s)); };
  out.move.x = held(GLFW_KEY_D) - held(GLFW_KEY_A);
  out.move.y = held(GLFW_KEY_UP) - held(GLFW_KEY_DOWN);
  out.move.z = held(GLFW_KEY_S) - held(GLFW_KEY_W);
  out.turn = held(GLFW_KEY_LEFT) - held(GLFW_KEY_RIGHT);
  if (!m_toggles.empty()) {
    out.curlToggle = m_toggles.front();
    m_toggles.pop_front();
  }
  return out;
}

double HeldKeys::takeHeld_s(int key, std::int64_t now_ns) noexcept {
  if (key < 0 || key >= kKeyCount) return 0.0;
  Key& k = m_keys[std::size_t(key)];
  std::int64_t held = k.held_ns;
  if (k.down) {
    held += std::max<std::int64_t>(0, now_ns - k.since_ns);
    k.since_ns = std::max(k.since_ns, now_ns);
  }
  k.held_ns = 0;
  return double(held) * 1e-9;
}

}  // namespace vt::ui
