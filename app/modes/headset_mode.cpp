#include "modes/headset_mode.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <thread>
#include <vector>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "modes/contact_markers.hpp"
#include "modes/frame_stats.hpp"
#include "modes/hand_control.hpp"
#include "modes/touch_hud.hpp"
#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/stop.hpp"
#include "vt/renderer/imgui_layer.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/renderer/window_target.hpp"
#include "vt/scene/image.hpp"
#include "vt/xr/haptic_sink.hpp"
#include "vt/xr/headset.hpp"

namespace vt::app {
namespace {

constexpr std::int64_t kExitWait_ns = 2'000'000'000;

// The left eye's pose with its vertical field of view, widened or narrowed to the window's aspect
// (an eye's frustum is asymmetric and squarer than a desktop window).
CameraView mirrorView(CameraView eye, VkExtent2D extent) {
  const float halfWidth = 0.5f * (eye.tanUp - eye.tanDown) * float(extent.width) / float(std::max(1u, extent.height));
  const float centre = 0.5f * (eye.tanLeft + eye.tanRight);
  eye.tanLeft = centre - halfWidth;
  eye.tanRight = centre + halfWidth;
  return eye;
}

// Asks for the window's Vulkan extensions when a mirror is wanted and possible; else says why not.
bool requestMirrorExtensions(const DesktopOptions& options, xr::HeadsetOptions& headsetOptions) {
  if (!options.mirror) return false;
  if (!haveDisplay()) {
    log::info("headset mode: no mirror window (no display)");
    return false;
  }
  try {
    renderer::DeviceOptions window;
    renderer::addWindowExtensions(window);
    headsetOptions.vulkanInstanceExtensions = window.instanceExtensions;
    headsetOptions.vulkanDeviceExtensions = window.deviceExtensions;
    return true;
  } catch (const Error& e) {
    log::info("headset mode: no mirror window (", e.what(), ")");
    return false;
  }
}

// The desktop mirror on the headset's device; null (with one info line) when it cannot be made.
std::unique_ptr<renderer::WindowTarget> openMirror(const DesktopOptions& options, xr::Headset& headset) {
  if (!headset.extraVulkanExtensions()) {
    log::info("headset mode: no mirror window (the OpenXR runtime's Vulkan lacks the window extensions)");
    return nullptr;
  }
  try {
    return std::make_unique<renderer::WindowTarget>(
        headset.device(), renderer::WindowOptions{.width = options.width, .height = options.height,
                                                  .title = "V-Touching headset mirror", .vsync = false});
  } catch (const Error& e) {
    log::info("headset mode: no mirror window (", e.what(), ")");
    return nullptr;
  }
}

}  // namespace

std::optional<int> runHeadset(const DesktopOptions& options) {
  const LoadedScene scene = loadScene(options.scene);
  TouchPipeline haptics(scene, options.touchSpec());
  xr::HeadsetOptions headsetOptions;
  headsetOptions.validate = options.validate;
  // --fixed-table: where the stage puts it (a lab's physical table), not placed before the head.
  headsetOptions.placeAtHead = !options.fixedTable;
  headsetOptions.handOutputs = {nullptr, &haptics.poses()};  // the right hand touches
  // --glove-curls: with a VIVE tracker on the glove, its flexion curls the tracked hand's fingers.
  if (options.gloveCurls) headsetOptions.gloveCurls = haptics.gloveFlexionChannel();
  const bool wantMirror = requestMirrorExtensions(options, headsetOptions);
  xr::Headset::OpenResult opened = xr::Headset::open(headsetOptions);
  if (!opened.headset) {
    std::fprintf(stderr, "vtouching: %s\n", opened.message.c_str());
    return std::nullopt;
  }
  xr::Headset& headset = *opened.headset;
  std::printf("headset mode: %s, %s, %s\n", headset.runtimeName().c_str(), headset.inputSource().c_str(),
              scene.description.c_str());
  std::fflush(stdout);  // scripts and logs see the session start when it happens
  int exitCode = 0;
  {
    renderer::Renderer gpu(headset.device());
    gpu.setScene(scene.scene);
    applyHandView(gpu, options.hand);
    std::unique_ptr<renderer::WindowTarget> mirror = wantMirror ? openMirror(options, headset) : nullptr;
    // The HUD goes on the mirror, for whoever watches the session at the desk.
    std::unique_ptr<renderer::ImGuiLayer> imgui = mirror ? std::make_unique<renderer::ImGuiLayer>(gpu, *mirror) : nullptr;
    if (imgui && options.frames == 0) imgui->setSettingsFile(hudSettingsFile());  // runs of N frames are tests
    ui::HudStatus status;
    status.scene = scene.description;
    status.vulkanDevice = headset.device()->description();
    std::string inputSource = headset.inputSource();
    status.xrRuntime = headset.runtimeName() + ", " + inputSource;
    status.recording = options.sinks.record;
    TouchHud hud(scene, options.haptic, options.remote.has_value(), std::move(status), false);
    hud.setOverlay(options.overlay);
    const Clock& clock = SteadyClock::instance();
    std::int64_t lastMirror_ns = clock.now_ns();
    double mirrorFrame_ms = 0.0;
    std::uint64_t mirrorFrames = 0;
    bool mirrorCaptured = false;  // the last mirror frame was drawn (a skipped one has no capture)
    // Every frame reaches the controllers (PCM needs all the blocks); they send once per display frame.
    auto& controllerHaptics = static_cast<xr::XrHapticSink&>(haptics.attach(std::make_unique<xr::XrHapticSink>(headset, 1)));
    std::uint64_t frames = 0;
    // Between successive rendered frames: the frame time when stepped, the display period when
    // paced (scripts/gpu-check.sh reads the summary).
    std::vector<double> frameIntervals_ms;
    frameIntervals_ms.reserve(options.frames > 0 ? std::size_t(options.frames) : 0);
    std::int64_t lastFrame_ns = 0;
    bool exitRequested = false;
    std::int64_t exitRequested_ns = 0;
    bool recenterKeyDown = false;
    for (;;) {
      const xr::SessionPhase phase = headset.pollEvents();
      if (phase == xr::SessionPhase::Exiting) break;
      // One shutdown path: Ctrl-C / SIGTERM end the session the OpenXR way (xrRequestExitSession,
      // then xrEndSession on STOPPING), bounded in case the runtime never gets there.
      if (stopRequested() && !exitRequested) {
        headset.requestExit();
        exitRequested = true;
      }
      if (exitRequested && exitRequested_ns == 0) exitRequested_ns = clock.now_ns();
      if (exitRequested && clock.now_ns() - exitRequested_ns > kExitWait_ns) {
        std::fprintf(stderr, "vtouching: the OpenXR runtime did not end the session within 2 s; leaving anyway\n");
        break;
      }
      if (phase == xr::SessionPhase::LossPending) {
        std::fprintf(stderr, "vtouching: the OpenXR session was lost; leaving headset mode\n");
        exitCode = 1;
        break;
      }
      if (phase == xr::SessionPhase::Idle) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        continue;
      }
      renderer::FrameDesc desc;
      desc.overlay = hud.settings().overlay;
      desc.ui = false;  // the eyes have no HUD
      std::optional<CameraView> leftEye;
      headset.frame([&](int eye, const CameraView& view, renderer::RenderTarget& target) {
        // The hand as located for this frame's display time (the input was updated for it).
        const HandPose pose = headset.displayHand(1);
        if (eye == 0 && pose.valid) {
          const HandPose drawn = visualProxy(pose, *scene.haptic->collision);
          renderer::appendHand(drawn, options.hand.style, desc);
          appendContactMarkers(haptics, drawn, *scene.haptic->collision, desc.contacts);
          haptics.noteDrawnFrame(pose, pose.t_ns);  // located for this frame's display time
        }
        desc.views = {view};
        gpu.render(target, desc);
        if (eye == 0) leftEye = view;
      });
      if (leftEye) {
        const std::int64_t now_ns = clock.now_ns();
        if (lastFrame_ns != 0) frameIntervals_ms.push_back(double(now_ns - lastFrame_ns) * 1e-6);
        lastFrame_ns = now_ns;
      }
      if (mirror) {
        // After xrEndFrame, so the mirror never holds the runtime's swapchain images.
        if (leftEye) {
          const std::int64_t now_ns = clock.now_ns();
          mirrorFrame_ms = mirrorFrames == 0 ? 0.0 : 0.9 * mirrorFrame_ms + 0.1 * double(now_ns - lastMirror_ns) * 1e-6;
          lastMirror_ns = now_ns;
          imgui->beginFrame();
          hud.draw(haptics, mirrorFrame_ms, options.hud);
          imgui->endFrame();
          desc.ui = true;
          desc.views = {mirrorView(*leftEye, mirror->extent())};
          if (!options.screenshot.empty()) mirror->requestCapture();  // the last one is saved
          mirrorCaptured = gpu.render(*mirror, desc);
          if (mirrorCaptured) ++mirrorFrames;
        }
        mirror->pollEvents();
        // R in the mirror: the table in front of the head again (as the runtime's own re-centre).
        const bool recenterKey = glfwGetKey(mirror->window(), GLFW_KEY_R) == GLFW_PRESS &&
                                 !ImGui::GetIO().WantCaptureKeyboard;
        if (recenterKey && !recenterKeyDown) {
          headset.recenter();
          log::info("headset mode: re-centred the table in front of the head");
        }
        recenterKeyDown = recenterKey;
        if (mirror->shouldClose() && !exitRequested) {
          headset.requestExit();  // closing the mirror leaves headset mode
          exitRequested = true;
        }
      }
      if (const std::string now = headset.inputSource(); now != inputSource) {
        // Runtimes bind profiles at the first xrSyncActions or later (InteractionProfileChanged).
        inputSource = now;
        log::info("headset mode: input ", inputSource);
        hud.setXrStatus(headset.runtimeName() + ", " + inputSource);
      }
      haptics.drain();
      // The haptic side's hand is asked of the runtime for the moment its output is felt.
      headset.setHandLookahead(haptics.feltLatency_ns());
      if (options.frames > 0 && ++frames >= std::uint64_t(options.frames) && !exitRequested) {
        headset.requestExit();
        exitRequested = true;
      }
    }
    haptics.stop();  // the controllers' vibration ends with the session
    if (options.runReport) options.runReport(haptics);
    gpu.waitIdle();
    std::printf("headset mode: %llu frames rendered, %llu controller pulses\n",
                static_cast<unsigned long long>(headset.framesRendered()),
                static_cast<unsigned long long>(controllerHaptics.pulses()));
    if (!frameIntervals_ms.empty()) {
      const FrameStats intervals = summarizeFrameTimes(frameIntervals_ms);
      std::printf("headset mode: frame interval mean %.2f ms, p95 %.2f ms, p99 %.2f ms over %zu frames\n",
                  intervals.mean_ms, intervals.p95_ms, intervals.p99_ms, frameIntervals_ms.size());
    }
    if (mirror) {
      std::printf("headset mode: mirror window %ux%u, %llu frames\n", mirror->extent().width, mirror->extent().height,
                  static_cast<unsigned long long>(mirrorFrames));
      if (!options.screenshot.empty() && mirrorCaptured) {
        savePng(options.screenshot, mirror->takeCapture());
        std::printf("wrote %s\n", options.screenshot.c_str());
      }
    }
  }
  if (options.validate) {
    const auto messages = headset.device()->validationMessageCount();
    std::printf("validation messages: %llu\n", static_cast<unsigned long long>(messages));
    if (messages > 0) exitCode = 3;
  }
  return exitCode;
}

}  // namespace vt::app
