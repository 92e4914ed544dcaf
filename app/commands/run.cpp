// `vtouching run` (also `vtouching` alone): the desktop preview; `--xr` for the headset; with no
// display the offscreen demo (the example trajectory) instead.
#include <cstdio>

#include "cli.hpp"
#include "modes/desktop_mode.hpp"
#include "modes/headset_mode.hpp"
#include "modes/run_report.hpp"
#include "modes/trajectory_run.hpp"
#include "vt/core/error.hpp"

VT_COMMAND(run) {
  vt::app::DesktopOptions options = vt::app::readDesktopOptions(args);
  const bool xr = args.flag("xr");
  const bool xrRequired = args.flag("xr-required");
  options.haptic = vt::app::readHapticOptions(args);
  const std::string demoOut = args.valueOr("demo-out", "vtouching-demo");
  const bool json = args.flag("json");
  args.finish();
  // The end-of-run report: the consistency meter, the loop's timing, the outputs.
  options.runReport = [json](const vt::app::TouchPipeline& pipeline) {
    vt::app::printReport(vt::app::runReportJson(pipeline), json);
  };

  if (xr || xrRequired) {
    if (const auto code = vt::app::runHeadset(options)) return *code;
    if (xrRequired) return 5;
    std::fprintf(stderr, "vtouching: continuing in desktop mode\n");
    options.xrStatus = "no headset (see the message at start-up)";
  }
  if (!vt::app::haveDisplay()) {
    std::printf("vtouching: no display (DISPLAY and WAYLAND_DISPLAY are unset): running the offscreen demo into %s/\n",
                demoOut.c_str());
    std::fflush(stdout);
    vt::app::TrajectoryRunOptions demo;
    demo.trajectory = vt::app::defaultTrajectory();
    if (demo.trajectory.empty()) vt::fail("run: no display and no example trajectory (assets/trajectories/slide.csv) found");
    demo.outDir = demoOut;
    demo.command = "run";
    demo.scene = options.scene;
    demo.haptic = options.haptic;
    demo.sinks = options.sinks;
    demo.overlay = options.overlay;
    demo.fps = 5.0;
    const vt::app::TrajectoryRunResult r = vt::app::runTrajectory(demo);
    std::printf("offscreen demo: %d frames, %s, %s\n", r.framesWritten, r.tracesCsv.c_str(), r.figurePng.c_str());
    return 0;
  }
  return vt::app::runDesktop(options);
}
