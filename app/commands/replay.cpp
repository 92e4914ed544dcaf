// `vtouching replay FILE`: re-runs a recording's poses through a fresh haptic loop and checks
// that every actuator frame comes out the same; with --out DIR it also re-renders the run as an
// offscreen trajectory run does (frames or a video, traces, figures; docs/app.md).
#include <cstdio>
#include <memory>

#include "cli.hpp"
#include "modes/recording.hpp"
#include "modes/touch_pipeline.hpp"
#include "modes/trajectory_run.hpp"
#include "vt/core/error.hpp"

VT_COMMAND(replay) {
  bool quiet = false;
  vt::app::RunOutputOptions outputOptions = vt::app::readRunOutputOptions(args, "replay", quiet);
  outputOptions.progress = false;  // a recording's length is known only at its end
  const bool render = !outputOptions.outDir.empty();
  const auto files = args.positionals();
  args.finish();
  if (files.size() != 1) vt::fail("replay: expected one recording file");

  std::unique_ptr<vt::app::RunOutputs> outputs;
  std::int64_t first_ns = -1;
  vt::app::ReplayObserver observer;
  if (render) {
    observer.started = [&](const vt::app::LoadedScene& scene, vt::app::TouchPipeline& pipeline) {
      outputs = std::make_unique<vt::app::RunOutputs>(scene, pipeline.config(), outputOptions);
      pipeline.onTrace([&](const vt::haptics::ContactTrace& t) { outputs->trace(t); });
    };
    observer.ticked = [&](std::int64_t t_ns, vt::app::TouchPipeline& pipeline) {
      vt::HandPose pose;
      if (!pipeline.poses().newest(pose)) return;
      if (first_ns < 0) first_ns = t_ns;
      outputs->tick(t_ns - first_ns, pose, 0.0);
    };
  }
  std::filesystem::path csv;
  if (render) {
    std::error_code ec;
    std::filesystem::create_directories(outputOptions.outDir, ec);
    if (ec) vt::fail("replay: cannot create output folder '", outputOptions.outDir.string(), "': ", ec.message());
    csv = outputOptions.outDir / "actuator_frames.csv";
  }
  vt::app::refuseSharedRunOutputs(outputOptions, nullptr, csv);
  const vt::app::ReplayResult r = vt::app::replayRecording(files[0], csv, observer);
  std::printf("replayed %llu actuator frames (%llu poses, %llu contact records): %llu differ, max difference %.3g\n",
              static_cast<unsigned long long>(r.frames), static_cast<unsigned long long>(r.poses),
              static_cast<unsigned long long>(r.contacts), static_cast<unsigned long long>(r.mismatches),
              r.maxDifference);
  if (r.frames == 0) vt::fail("replay: ", files[0], ": the recording holds no actuator frames");
  if (outputs) {
    vt::app::TrajectoryRunResult written;
    outputs->finish("recording", files[0], written);
    if (!quiet) {
      std::printf("wrote %d frames%s%s, %s, %s, %s\n", written.framesWritten, outputOptions.video.empty() ? "" : " into ",
                  outputOptions.video.c_str(), csv.c_str(), written.tracesCsv.c_str(), written.figurePng.c_str());
    }
  }
  return r.mismatches == 0 ? 0 : 4;
}
