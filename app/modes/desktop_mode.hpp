#pragma once
// The desktop preview: a GLFW window showing the scene and the hand, mouse/keyboard driving the
// hand, the haptic loop on its own thread feeding the glove sinks, and the HUD. Input is read on
// the main thread at 1 kHz, frames are drawn on a render thread (desktop_mode.cpp).
#include <functional>
#include <optional>
#include <string>

#include "modes/hand_view.hpp"
#include "modes/haptic_options.hpp"
#include "modes/touch_pipeline.hpp"
#include "modes/scene_source.hpp"

namespace vt::app {

struct DesktopOptions {
  SceneOptions scene;
  HapticOptions haptic;
  HapticSinks sinks;        // --glove, --record, --record-csv, --record-wav
  HandViewOptions hand;     // --hand mesh|skeleton, --hand-model FILE
  std::optional<net::ClientConfig> remote;  // client mode: the tactile server's session
  int width = 1280, height = 720;
  int frames = 0;           // --frames N: quit after N frames (0 = until closed)
  std::string screenshot;   // --screenshot FILE: the last frame (headset mode: mirror frame) as PNG
  bool scripted = false;    // --scripted-input: a fixed mouse path instead of the real mouse (tests)
  std::string cursorScript; // --cursor-script FILE: a scripted mouse (desktop_input.hpp); the run ends with it
  double maxFps = 0.0;      // --max-fps F: at most F frames per second (0 = as fast as rendered)
  bool pace = true;         // present each frame a planned lag after its input (--no-frame-pacing: at once)
  bool validate = false;    // --validate: Vulkan validation layer; non-zero exit on any message
  bool hud = true;          // --no-hud hides the panels
  bool overlay = false;     // --overlay: the vibration maps drawn over the objects from the start
  bool gloveCurls = false;  // --glove-curls: the glove's flexion sensors curl the fingers (not keys 1-5)
  bool mirror = true;       // headset mode: a desktop mirror window when a display exists (--no-mirror)
  bool fixedTable = false;  // headset mode: the table stays at its stage position, not placed before the head
  std::string xrStatus = "not used (desktop mode; vtouching --xr for a headset)";
  bool json = false;  // client mode: the end-of-session report as JSON
  std::function<void(const TouchPipeline&)> runReport;  // called once the touch pipeline stopped

  /// The touch pipeline these options describe: the live loop, or the remote server's stream.
  TouchPipelineSpec touchSpec() const {
    return {.sceneOptions = scene, .haptic = haptic, .sinks = sinks,
            .drive = remote ? TouchDrive::Remote : TouchDrive::LoopThread, .remote = remote};
  }
};

/// Reads the options `run` and `client` share: scene, sinks (--glove, --record...), --glove-curls,
/// --size, --frames, --screenshot, --scripted-input, --no-hud, --overlay, --validate, --no-mirror, --hand,
/// --hand-model; checks
/// them together (throws vt::Error naming the option).
DesktopOptions readDesktopOptions(cli::Args& args);

/// True when a window can be opened (DISPLAY or WAYLAND_DISPLAY set).
bool haveDisplay();

/// Runs the preview until Esc / window close / --frames. Returns the exit code (3 when
/// --validate saw validation messages). Throws vt::Error when setup fails.
int runDesktop(const DesktopOptions& options);

}  // namespace vt::app
