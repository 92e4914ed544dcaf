#include "modes/desktop_mode.hpp"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <thread>

#include <GLFW/glfw3.h>

#include "modes/contact_markers.hpp"
#include "modes/desktop_input.hpp"
#include "modes/frame_stats.hpp"
#include "modes/hand_control.hpp"
#include "modes/present_pacer.hpp"
#include "modes/touch_hud.hpp"
#include "ui/video_window.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/latest_value.hpp"
#include "vt/core/log.hpp"
#include "vt/core/realtime.hpp"
#include "vt/core/stop.hpp"
#include "vt/renderer/imgui_layer.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/renderer/window_target.hpp"

namespace vt::app {
namespace {

// The input thread reads the window at this rate whatever the frame rate (docs/app.md, "Input").
constexpr std::int64_t kInputPeriod_ns = 1'000'000;
constexpr int kInputThreadPriority = 15;  // below the haptic thread, above everything else
// Runs of N frames print their frame time after these warm-up frames, as `vtouching render`.
constexpr int kWarmupFrames = 2;

// What the render thread and the input (main) thread share.
struct Shared {
  LatestValue<OrbitCamera> camera;
  std::atomic<bool> quit{false};
};

struct RenderContext {
  const DesktopOptions& options;
  const LoadedScene& scene;
  renderer::Renderer& gpu;
  renderer::WindowTarget& window;
  renderer::ImGuiLayer& imgui;
  TouchPipeline& haptics;
  TouchHud& hud;
  ui::VideoWindow* video;
  Shared& shared;
  std::int64_t start_ns;
};

// The render thread: draws the newest hand the input published, the HUD, and measures how old
// that hand is when the frame reaches the window system (the display lag the haptic loop aligns
// to). Owns every use of the touch pipeline except publishPose (the input thread's).
void renderFrames(RenderContext c) {
  const DesktopOptions& options = c.options;
  const Clock& clock = SteadyClock::instance();
  const std::int64_t maxFpsPeriod_ns = options.maxFps > 0 ? std::int64_t(1e9 / options.maxFps) : 0;
  std::int64_t last_ns = clock.now_ns(), lastBegin_ns = 0;
  double frame_ms = 0.0;
  PresentPacer pacer;
  std::vector<double> work_ms;
  work_ms.reserve(std::size_t(std::max(0, options.frames)));
  for (int frame = 0; options.frames == 0 || frame < options.frames; ++frame) {
    // Scripted runs are paced like a 60 Hz display; --max-fps caps the frame rate.
    if (options.scripted) clock.sleepUntil(c.start_ns + std::int64_t(double(frame) * 1e9 / kScriptFrameRate_hz));
    if (maxFpsPeriod_ns > 0 && lastBegin_ns > 0) clock.sleepUntil(lastBegin_ns + maxFpsPeriod_ns);
    const std::int64_t begin_ns = clock.now_ns();
    lastBegin_ns = begin_ns;
    if (c.window.shouldClose() || stopRequested() || c.shared.quit.load()) break;
    frame_ms = frame == 0 ? 0.0 : 0.9 * frame_ms + 0.1 * double(begin_ns - last_ns) * 1e-6;
    last_ns = begin_ns;

    // The wait for a window image (tens of milliseconds on a busy X server) comes before the hand
    // is read: it would otherwise make the hand drawn that much older than planned.
    c.gpu.prepare(c.window);
    c.haptics.drain();
    c.imgui.beginFrame();
    c.hud.draw(c.haptics, frame_ms, options.hud);
    if (c.video) c.video->draw();
    c.imgui.endFrame();

    const VkExtent2D extent = c.window.extent();
    OrbitCamera camera = c.scene.scene->camera;
    c.shared.camera.read(camera);
    renderer::FrameDesc desc;
    desc.views = {camera.view(float(std::max(1u, extent.width)) / float(std::max(1u, extent.height)))};
    desc.overlay = c.hud.settings().overlay;
    // The newest hand the input thread published: drawn as it was read, not predicted.
    HandPose pose;
    const bool haveHand = c.haptics.poses().newest(pose) && pose.valid;
    const HandPose drawn = haveHand ? visualProxy(pose, *c.scene.haptic->collision) : pose;
    if (haveHand) {
      renderer::appendHand(drawn, options.hand.style, desc);
      appendContactMarkers(c.haptics, drawn, *c.scene.haptic->collision, desc.contacts);
    }
    const bool last = options.frames > 0 && frame == options.frames - 1;
    if (last && !options.screenshot.empty()) c.window.requestCapture();
    // Paced: presented at the planned lag (always after rendering, whose end is measured).
    const std::int64_t presentAt_ns =
        haveHand && options.pace ? pacer.presentAt(pose.t_ns, clock.now_ns(), c.haptics.feltDisplayLag_ns()) : 0;
    if (options.pace) c.window.presentAt(std::max<std::int64_t>(presentAt_ns, 1));
    // A skipped frame (swapchain recreated) is retried so the capture is of a drawn frame.
    const bool shown = c.gpu.render(c.window, desc);
    const std::int64_t shown_ns = c.window.lastPresented_ns();
    if (!shown && last) --frame;
    if (shown && haveHand) {
      // The display lag the haptic loop aligns to is the plan; a late frame shows as an offset.
      c.haptics.noteDrawnFrame(pose, shown_ns);
      // Unpaced (--no-frame-pacing), the end of rendering is unknown: the present's end stands for it.
      const std::int64_t ready_ns = options.pace ? c.window.lastRenderDone_ns() : shown_ns;
      pacer.observe(ready_ns - pose.t_ns, shown_ns - std::max(ready_ns, presentAt_ns));
      c.haptics.setDisplayLag(pacer.plan());
    }
    if (options.frames > 0 && frame >= kWarmupFrames) work_ms.push_back(double(shown_ns - begin_ns) * 1e-6);
  }
  if (!work_ms.empty()) {
    const FrameStats stats = summarizeFrameTimes(work_ms);
    std::printf("frame time %ux%u: mean %.2f ms, p95 %.2f ms over %zu frames\n", c.window.extent().width,
                c.window.extent().height, stats.mean_ms, stats.p95_ms, work_ms.size());
  }
  if (!options.screenshot.empty() && options.frames > 0) {
    savePng(options.screenshot, c.window.takeCapture());
    std::printf("wrote %s\n", options.screenshot.c_str());
  }
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
  options.cursorScript = args.valueOr("cursor-script", "");
  options.maxFps = args.doubleIn("max-fps", 0.0, 0.0, 1000.0);
  options.hud = !args.flag("no-hud");
  options.overlay = args.flag("overlay");
  options.gloveCurls = args.flag("glove-curls");
  options.validate = args.flag("validate");
  options.mirror = !args.flag("no-mirror");
  options.fixedTable = args.flag("fixed-table");
  options.pace = !args.flag("no-frame-pacing");
  if (options.frames < 0) fail(args.command(), ": --frames must be 0 (until closed) or more");
  if ((options.scripted || !options.screenshot.empty()) && options.frames == 0)
    fail(args.command(), ": --scripted-input and --screenshot need --frames N");
  if (options.scripted && !options.cursorScript.empty())
    fail(args.command(), ": --scripted-input and --cursor-script both script the mouse; give one");
  return options;
}

bool haveDisplay() { return std::getenv("DISPLAY") || std::getenv("WAYLAND_DISPLAY"); }

int runDesktop(const DesktopOptions& options) {
  const LoadedScene scene = loadScene(options.scene);
  std::optional<CursorScript> script;
  if (!options.cursorScript.empty()) script = loadCursorScript(options.cursorScript);
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
    TouchPipeline haptics(scene, options.touchSpec());
    std::optional<ui::VideoWindow> video;  // client --video: the server's virtual camera
    if (options.remote && options.remote->wantVideo) video.emplace(imgui, haptics.client()->video());

    ui::HudStatus status;
    status.scene = scene.description;
    status.vulkanDevice = device->description();
    status.xrRuntime = options.xrStatus;
    status.recording = options.sinks.record;
    TouchHud hud(scene, options.haptic, options.remote.has_value(), std::move(status));
    hud.setOverlay(options.overlay);

    // Input on this (GLFW's main) thread at 1 kHz, frames on a render thread: the hand's pose
    // does not depend on how fast frames are drawn, and every pose is stamped when it was read.
    Shared shared;
    shared.camera.publish(scene.scene->camera);
    const std::int64_t start_ns = SteadyClock::instance().now_ns();
    DesktopInput input(scene, window, imgui, haptics, options, script ? &*script : nullptr, start_ns);
    window.setEventListener([&input](const renderer::WindowEvent& e) { input.event(e); });
    std::exception_ptr renderFailure;
    std::thread renderThread([&] {
      try {
        renderFrames({options, scene, gpu, window, imgui, haptics, hud, video ? &*video : nullptr, shared, start_ns});
      } catch (...) {
        renderFailure = std::current_exception();
      }
      shared.quit.store(true);
    });
    requestRealtime("desktop input", kInputThreadPriority);
    const Clock& clock = SteadyClock::instance();
    for (std::int64_t next_ns = clock.now_ns(); !shared.quit.load(); next_ns += kInputPeriod_ns) {
      const std::int64_t now_ns = clock.now_ns();
      if (next_ns < now_ns - 10 * kInputPeriod_ns) next_ns = now_ns;  // descheduled: no burst to catch up
      window.waitEvents(double(std::max<std::int64_t>(0, next_ns - now_ns)) * 1e-9);
      if (window.shouldClose() || stopRequested()) break;
      if (!input.step(clock.now_ns())) break;  // Esc, or the cursor script's end
      shared.camera.publish(input.camera());
    }
    shared.quit.store(true);
    renderThread.join();
    window.setEventListener({});
    if (renderFailure) std::rethrow_exception(renderFailure);
    haptics.stop();
    if (options.runReport) options.runReport(haptics);
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
