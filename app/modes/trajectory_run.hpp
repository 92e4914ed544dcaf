#pragma once
// Offscreen scripted runs (`vtouching render --trajectory`, and the demo when there is no
// display): the haptic loop driven by tickOnce on a manual clock, so the traces, the figure and
// the frames are the same on every run. Main thread only.
#include <filesystem>
#include <string>

#include "cli.hpp"
#include "modes/haptic_options.hpp"
#include "modes/scene_source.hpp"
#include "modes/touch_session.hpp"

namespace vt::app {

struct TrajectoryRunOptions {
  std::filesystem::path trajectory;
  std::filesystem::path outDir;
  SceneOptions scene;
  HapticOptions haptic;
  HapticSinks sinks{.glove = "none"};  // --record-csv/--record-wav/--record/--glove as in every mode
  int width = 960, height = 540;
  double fps = 30.0;    // frames rendered per second of trajectory time (0 = no frames)
  int every = 1;        // keep every N-th rendered frame as PNG
  bool validate = false;
  bool overlay = false;  // the vibration-map overlay on the plates
  bool progress = false; // a progress line on stderr about once a second (frames, rate, time left)
};

struct TrajectoryRunResult {
  int framesWritten = 0;
  std::uint64_t ticks = 0;
  std::uint64_t validationMessages = 0;
  std::filesystem::path tracesCsv, figurePng;
  float peakIntensity = 0.0f;
  bool stoppedEarly = false;  // the stop request (Ctrl-C) ended the run before the path's end
};

/// Runs the trajectory: writes frame_NNNNN.png, traces.csv, figure.png (the object touched most)
/// and figure_<object>.png for every touched object into outDir. Throws vt::Error.
TrajectoryRunResult runTrajectory(const TrajectoryRunOptions& options);

/// `vtouching render --trajectory FILE --out DIR [--size WxH] [--fps F] [--every N] [--overlay]
/// [--quiet] [--validate] [scene and haptic options]`: reads the options, runs, prints what it wrote. Returns the exit code.
int trajectoryCommand(cli::Args& args, const std::string& trajectory);

/// The example trajectory shipped with the assets (slides across the plates), or empty.
std::filesystem::path defaultTrajectory();

}  // namespace vt::app
