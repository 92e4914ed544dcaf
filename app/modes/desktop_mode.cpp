#include "modes/desktop_mode.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "modes/contact_markers.hpp"
#include "modes/frame_stats.hpp"
#include "modes/hand_control.hpp"
#include "modes/session_hud.hpp"
#include "ui/input_events.hpp"
#include "ui/video_window.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/stop.hpp"
#include "vt/renderer/imgui_layer.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/renderer/window_target.hpp"

namespace vt::app {
namespace {

constexpr float kMoveSpeed_mps = 0.15f;
constexpr float kTurnSpeed_radps = 1.2f;
constexpr float kScrollPress_m = 0.002f;  // per wheel notch
constexpr float kOrbit_radPerPx = 0.006f;

// The mouse and keys of one frame, from the window or from the test script.
struct FrameInput {
  bool cursorMoved = false;
  glm::vec2 cursor_px{0.0f};
  bool pressing = false;
  float scroll = 0.0f;
  glm::vec2 orbit_px{0.0f};  // right-drag delta
  glm::vec3 move{0.0f};      // WASD (x, z) and arrows up/down (y), -1..1
  float turn = 0.0f;         // arrows left/right
  int curlToggle = -1;       // keys 1-5
  bool reset = false;
  bool quit = false;
};

class WindowInput {
 public:
  explicit WindowInput(GLFWwindow* window) : m_window(window), m_events(window), m_controls(m_events) {}

  FrameInput read() {
    FrameInput in;
    const ImGuiIO& io = ImGui::GetIO();
    const bool uiMouse = io.WantCaptureMouse;  // keys: each event says whether the UI had them
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(m_window, &x, &y);
    const glm::vec2 cursor{float(x), float(y)};
    const bool right = glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    // Keys and clicks are events (a tap shorter than a frame still counts), the cursor a position.
    const ui::ControlKeys keys = m_controls.read();
    if (!uiMouse) {
      in.cursorMoved = cursor != m_lastCursor && !right;
      in.cursor_px = cursor;
      in.pressing = glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS || keys.clicked;
      in.scroll = io.MouseWheel;
      if (right && m_rightWasDown) in.orbit_px = cursor - m_lastCursor;
    }
    m_rightWasDown = right;
    m_lastCursor = cursor;
    in.move = keys.move;
    in.turn = keys.turn;
    in.curlToggle = keys.curlToggle;
    in.reset = keys.reset;
    in.quit = keys.quit;
    return in;
  }

 private:
  GLFWwindow* m_window;
  ui::InputEventQueue m_events;  // after the ImGuiLayer: chains to its callbacks
  ui::DesktopControls m_controls;
  glm::vec2 m_lastCursor{-1.0f};
  bool m_rightWasDown = false;
};

// The test script, paced like a 60 Hz display: frame N starts at N / 60 s (later when
// rendering is slower). The cursor sweeps across the middle of the view at a constant speed in
// time, from frame 0 to the last frame, pressing from frame 4 on, with the index... ring
// fingers straight and the view orbited a little (exercises every path). Poses thus arrive at
// 60 Hz or less while the hand moves steadily: what the haptic loop must turn into a continuous
// sweep. The last frame is at the end of the path however fast rendering was.
constexpr double kScriptFrameRate_hz = 60.0;

FrameInput scriptedInput(int frame, int frames, std::int64_t elapsed_ns, glm::vec2 size_px) {
  FrameInput in;
  const double duration_s = double(std::max(1, frames - 1)) / kScriptFrameRate_hz;
  const float s = frame >= frames - 1 ? 1.0f : float(std::min(1.0, double(elapsed_ns) * 1e-9 / duration_s));
  in.cursorMoved = true;
  in.cursor_px = size_px * glm::vec2(0.38f + 0.12f * s, 0.42f);
  in.pressing = frame >= 4;
  if (frame == 2) in.orbit_px = {20.0f, 0.0f};
  if (frame == 1) in.curlToggle = 4;  // little finger curled
  return in;
}

glm::vec3 rayDirection(const CameraView& view, glm::vec2 cursor_px, glm::vec2 size_px) {
  const glm::vec2 t = cursor_px / size_px;
  const glm::vec3 eye{view.tanLeft + t.x * (view.tanRight - view.tanLeft), view.tanUp - t.y * (view.tanUp - view.tanDown),
                      -1.0f};
  return glm::normalize(glm::mat3(view.T_world_eye) * eye);
}

}  // namespace

DesktopOptions readDesktopOptions(cli::Args& args) {
  DesktopOptions options;
  options.scene = readSceneOptions(args);
  options.sinks = readHapticSinks(args);
  options.hand = readHandViewOptions(args);
  std::tie(options.width, options.height) = args.sizeOr("size", {options.width, options.height});
  options.frames = args.intOr("frames", 0);
  options.screenshot = args.valueOr("screenshot", "");
  options.scripted = args.flag("scripted-input");
  options.hud = !args.flag("no-hud");
  options.overlay = args.flag("overlay");
  options.gloveCurls = args.flag("glove-curls");
  options.validate = args.flag("validate");
  options.mirror = !args.flag("no-mirror");
  if (options.frames < 0) fail(args.command(), ": --frames must be 0 (until closed) or more");
  if ((options.scripted || !options.screenshot.empty()) && options.frames == 0)
    fail(args.command(), ": --scripted-input and --screenshot need --frames N");
  return options;
}

bool haveDisplay() { return std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY"); }

int runDesktop(const DesktopOptions& options) {
  const LoadedScene scene = loadScene(options.scene);
  renderer::DeviceOptions deviceOptions;
  deviceOptions.validate = options.validate;
  renderer::addWindowExtensions(deviceOptions);
  auto device = renderer::Device::create(deviceOptions);
  log::info("desktop preview: ", scene.description, " on ", device->description());
  int exitCode = 0;
  {
    renderer::Renderer gpu(device);
    gpu.setScene(scene.scene);
    applyHandView(gpu, options.hand);
    renderer::WindowTarget window(device, {.width = options.width, .height = options.height});
    renderer::ImGuiLayer imgui(gpu, window);
    if (options.frames == 0) imgui.setSettingsFile(hudSettingsFile());  // runs of N frames are tests: fixed layout
    TouchSession haptics(scene, options.touchSpec());
    std::optional<ui::VideoWindow> video;  // client --video: the server's virtual camera
    if (options.remote && options.remote->wantVideo) video.emplace(imgui, haptics.client()->video());
    WindowInput windowInput(window.window());

    DesktopHand hand;
    OrbitCamera camera = scene.scene->camera;
    ui::HudStatus status;
    status.scene = scene.description;
    status.vulkanDevice = device->description();
    status.xrRuntime = options.xrStatus;
    status.recording = options.sinks.record;
    SessionHud hud(scene, options.haptic, options.remote.has_value(), std::move(status));
    hud.setOverlay(options.overlay);

    const Clock& clock = SteadyClock::instance();
    std::int64_t last_ns = clock.now_ns();
    const std::int64_t start_ns = last_ns;
    double frame_ms = 0.0;
    // Runs of N frames print their frame time (input to submitted frame, without the script's
    // pacing), after two warm-up frames as in `vtouching render`.
    constexpr int kWarmupFrames = 2;
    std::vector<double> work_ms;
    work_ms.reserve(std::size_t(std::max(0, options.frames)));
    for (int frame = 0; options.frames == 0 || frame < options.frames; ++frame) {
      if (options.scripted) clock.sleepUntil(start_ns + std::int64_t(double(frame) * 1e9 / kScriptFrameRate_hz));
      const std::int64_t begin_ns = clock.now_ns();
      window.pollEvents();
      // The input was read now: the pose below describes the hand at this time.
      const std::int64_t input_ns = clock.now_ns();
      if (window.shouldClose() || stopRequested()) break;
      const std::int64_t now_ns = input_ns;
      const float dt_s = std::min(0.1f, float(now_ns - last_ns) * 1e-9f);
      frame_ms = frame == 0 ? 0.0 : 0.9 * frame_ms + 0.1 * double(now_ns - last_ns) * 1e-6;
      last_ns = now_ns;

      imgui.beginFrame();
      const VkExtent2D extent = window.extent();
      const glm::vec2 size_px{float(std::max(1u, extent.width)), float(std::max(1u, extent.height))};
      const FrameInput in =
          options.scripted ? scriptedInput(frame, options.frames, input_ns - start_ns, size_px) : windowInput.read();
      if (in.quit) break;
      camera.yaw_rad -= in.orbit_px.x * kOrbit_radPerPx;
      camera.pitch_rad = std::clamp(camera.pitch_rad - in.orbit_px.y * kOrbit_radPerPx, -1.5f, -0.05f);
      const CameraView view = camera.view(size_px.x / size_px.y);
      if (in.reset) hand.reset();
      if (in.curlToggle >= 0) hand.toggleCurl(in.curlToggle);
      if (FingerCurls flexion; options.gloveCurls && haptics.gloveFlexion(flexion)) hand.setCurlTargets(flexion);
      // Keys move relative to the camera's heading so W is always "away from the viewer".
      const glm::vec3 forward = glm::normalize(glm::vec3(-std::sin(camera.yaw_rad), 0.0f, -std::cos(camera.yaw_rad)));
      const glm::vec3 right{-forward.z, 0.0f, forward.x};
      if (in.move != glm::vec3(0.0f) || in.turn != 0.0f) {
        hand.move((right * in.move.x - forward * in.move.z + glm::vec3(0.0f, in.move.y, 0.0f)) * kMoveSpeed_mps * dt_s,
                  in.turn * kTurnSpeed_radps * dt_s, *scene.haptic->collision);
      }
      hand.addPress(in.scroll * kScrollPress_m);
      if (in.cursorMoved) {
        hand.placeIndexTipOver(pickSurface(*scene.haptic->collision, view.position(), rayDirection(view, in.cursor_px, size_px)));
      }
      hand.update(options.scripted ? 1.0f : dt_s);
      const HandPose pose = hand.pose(in.pressing, input_ns);
      haptics.publishPose(pose, in.reset);  // a reset is a jump: the loop does not sweep across it
      haptics.noteDrawnHand(pose);          // this frame draws the hand as of the input time
      haptics.drain();

      hud.draw(haptics, frame_ms, options.hud);
      if (video) video->draw();
      imgui.endFrame();

      renderer::FrameDesc desc;
      desc.views = {view};
      desc.overlay = hud.settings().overlay;
      const HandPose drawn = visualProxy(pose, *scene.haptic->collision);
      renderer::appendHand(drawn, options.hand.style, desc);
      appendContactMarkers(haptics, drawn, *scene.haptic->collision, desc.contacts);
      const bool last = options.frames > 0 && frame == options.frames - 1;
      if (last && !options.screenshot.empty()) window.requestCapture();
      // A skipped frame (swapchain recreated) is retried so the capture is of a drawn frame.
      if (!gpu.render(window, desc) && last) --frame;
      if (options.frames > 0 && frame >= kWarmupFrames) work_ms.push_back(double(clock.now_ns() - begin_ns) * 1e-6);
    }
    if (!work_ms.empty()) {
      const FrameStats stats = summarizeFrameTimes(work_ms);
      std::printf("frame time %ux%u: mean %.2f ms, p95 %.2f ms over %zu frames\n", window.extent().width,
                  window.extent().height, stats.mean_ms, stats.p95_ms, work_ms.size());
    }
    if (!options.screenshot.empty() && options.frames > 0) {
      savePng(options.screenshot, window.takeCapture());
      std::printf("wrote %s\n", options.screenshot.c_str());
    }
    haptics.stop();
    if (options.sessionReport) options.sessionReport(haptics);
    gpu.waitIdle();
  }
  if (options.validate) {
    const auto messages = device->validationMessageCount();
    std::printf("validation messages: %llu\n", static_cast<unsigned long long>(messages));
    if (messages > 0) exitCode = 3;
  }
  return exitCode;
}

}  // namespace vt::app
