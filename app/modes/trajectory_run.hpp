#pragma once
// Offscreen scripted runs (`vtouching render --trajectory`, and the demo when there is no
// display): the haptic loop driven by tickOnce on a manual clock, so the traces, the figure and
// the frames are the same on every run. Main thread only.
#include <filesystem>
#include <memory>
#include <string>

#include "cli.hpp"
#include "modes/hand_view.hpp"
#include "modes/haptic_options.hpp"
#include "modes/scene_source.hpp"
#include "modes/touch_pipeline.hpp"

namespace vt::app {

/// What an offscreen run writes beside the haptic output: frames (PNGs or one video),
/// traces.csv/json and the touch figures.
struct RunOutputOptions {
  std::filesystem::path outDir;
  int width = 960, height = 540;
  double fps = 30.0;    // frames rendered per second of run time (0 = no frames)
  int every = 1;        // keep every N-th rendered frame
  bool validate = false;
  bool overlay = false;  // the vibration-map overlay on the plates
  bool progress = false; // a progress line on stderr about once a second (frames, rate, time left)
  std::filesystem::path video;  // non-empty: the kept frames are encoded into this file by ffmpeg, no PNGs
  HandViewOptions hand;         // --hand, --hand-model
  const char* command = "render";  // names the command in errors
};

/// Refuses (before anything runs) a run whose outputs name one file twice: --video, the files
/// --out DIR holds (traces.csv, traces.json, figure.png, and `extra` such as the replay's
/// actuator_frames.csv) and the recordings of `sinks` (may be null).
void refuseSharedRunOutputs(const RunOutputOptions& options, const HapticSinks* sinks,
                            const std::filesystem::path& extra = {});

struct TrajectoryRunOptions : RunOutputOptions {
  std::filesystem::path trajectory;
  SceneOptions scene;
  HapticOptions haptic;
  HapticSinks sinks{.glove = "none"};  // --record-csv/--record-wav/--record/--glove as in every mode
};

struct TrajectoryRunResult {
  int framesWritten = 0;
  std::uint64_t ticks = 0;
  std::uint64_t validationMessages = 0;
  std::filesystem::path tracesCsv, figurePng;
  float peakIntensity = 0.0f;
  bool stoppedEarly = false;  // the stop request (Ctrl-C) ended the run before the path's end
};

/// The frames, traces and figures of an offscreen run fed tick by tick (a trajectory, a replayed
/// recording). Main thread only.
class RunOutputs {
 public:
  /// Creates the folder, the renderer (fps > 0) and ffmpeg (video); throws vt::Error naming what failed.
  RunOutputs(const LoadedScene& scene, const haptics::HapticConfig& config, const RunOutputOptions& options);
  ~RunOutputs();
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;
  /// One contact trace: a traces.csv row and a figure sample.
  void trace(const haptics::ContactTrace& t);
  /// After the tick at `t_ns` (from 0): renders `pose` when a frame is due; `done` (0..1) for the progress line.
  void tick(std::int64_t t_ns, const HandPose& pose, double done);
  /// Writes traces.json (`sourceKind`: "trajectory" or "recording", naming `source`), the
  /// figures, closes the video; fills the result's files and counts.
  void finish(const std::string& sourceKind, const std::string& source, TrajectoryRunResult& result);

 private:
  struct State;
  std::unique_ptr<State> m_state;
};

/// Reads --out (outDir empty when absent), --size, --fps, --every, --overlay, --hand, --hand-model, --validate, --video
/// and --quiet (progress off, log at warnings) for `command`; fails at once when --video is
/// given and ffmpeg is absent.
RunOutputOptions readRunOutputOptions(cli::Args& args, const char* command, bool& quiet);

/// Runs the trajectory: writes frame_NNNNN.png, traces.csv, figure.png (the object touched most)
/// and figure_<object>.png for every touched object into outDir. Throws vt::Error.
TrajectoryRunResult runTrajectory(const TrajectoryRunOptions& options);

/// `vtouching render --trajectory FILE --out DIR [--size WxH] [--fps F] [--every N] [--overlay]
/// [--quiet] [--validate] [--video FILE.mp4] [scene and haptic options]`: reads the options, runs, prints what it wrote. Returns the exit code.
int trajectoryCommand(cli::Args& args, const std::string& trajectory);

/// The example trajectory shipped with the assets (slides across the plates), or empty.
std::filesystem::path defaultTrajectory();

}  // namespace vt::app
