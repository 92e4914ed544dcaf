#include "modes/headset_mode.hpp"

#include <cstdio>
#include <thread>

#include "modes/hand_control.hpp"
#include "vt/core/log.hpp"
#include "vt/renderer/renderer.hpp"
#include "vt/xr/haptic_sink.hpp"
#include "vt/xr/headset.hpp"

namespace vt::app {

std::optional<int> runHeadset(const DesktopOptions& options) {
  const LoadedScene scene = loadScene(options.scene);
  HapticSession haptics(scene, options.scene, options.haptic, options.glove, options.record);
  xr::HeadsetOptions headsetOptions;
  headsetOptions.validate = options.validate;
  headsetOptions.handOutputs = {nullptr, &haptics.poses()};  // the right hand touches
  xr::Headset::OpenResult opened = xr::Headset::open(headsetOptions);
  if (!opened.headset) {
    std::fprintf(stderr, "vtouching: %s\n", opened.message.c_str());
    return std::nullopt;
  }
  xr::Headset& headset = *opened.headset;
  std::printf("headset mode: %s, %s, %s\n", headset.runtimeName().c_str(), headset.inputSource().c_str(),
              scene.description.c_str());
  int exitCode = 0;
  {
    renderer::Renderer gpu(headset.device());
    gpu.setScene(scene.scene);
    xr::XrHapticSink controllerHaptics(headset, 1);
    std::uint64_t frames = 0;
    bool exitRequested = false;
    for (;;) {
      const xr::SessionPhase phase = headset.pollEvents();
      if (phase == xr::SessionPhase::Exiting) break;
      if (phase == xr::SessionPhase::LossPending) {
        std::fprintf(stderr, "vtouching: the OpenXR session was lost; leaving headset mode\n");
        exitCode = 1;
        break;
      }
      if (phase == xr::SessionPhase::Idle) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        continue;
      }
      HandPose pose;
      const bool havePose = haptics.poses().read(pose);
      headset.frame([&](int, const CameraView& view, renderer::RenderTarget& target) {
        renderer::FrameDesc desc;
        desc.views = {view};
        if (havePose) {
          renderer::appendHandPrimitives(visualProxy(pose, *scene.haptic->collision), {0.85f, 0.62f, 0.5f, 1.0f},
                                         desc.hand);
        }
        gpu.render(target, desc);
      });
      haptics.notePublishedPose();
      haptics.drain();
      controllerHaptics.apply(haptics.lastFrame());
      if (options.frames > 0 && ++frames >= std::uint64_t(options.frames) && !exitRequested) {
        headset.requestExit();
        exitRequested = true;
      }
    }
    haptics.stop();
    controllerHaptics.apply(haptics::ActuatorFrame::silent(haptics.lastFrame().actuatorCount, 0));
    gpu.waitIdle();
    std::printf("headset mode: %llu frames rendered, %llu controller pulses\n",
                static_cast<unsigned long long>(headset.framesRendered()),
                static_cast<unsigned long long>(controllerHaptics.pulses()));
  }
  if (options.validate && headset.device()->validationMessageCount() > 0) exitCode = 3;
  return exitCode;
}

}  // namespace vt::app
