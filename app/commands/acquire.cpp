// `vtouching acquire`: a scan directory -> a dataset entry in the published layout, or
// (with --synthetic) a simulated scan directory to feed it.
#include <unistd.h>

#include <chrono>
#include <cstdio>

#include "cli.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/core/stop.hpp"
#include "vt/acquisition/synthetic.hpp"
#include "vt/acquisition/waveforms.hpp"
#include "vt/core/error.hpp"

namespace {

void drawProgress(std::size_t done, std::size_t total) {
  constexpr int kWidth = 40;
  const int filled = int(kWidth * done / std::max<std::size_t>(total, 1));
  std::fprintf(stderr, "\racquire [%.*s%*s] %zu/%zu lines", filled, "########################################",
               kWidth - filled, "", done, total);
  if (done == total) std::fputc('\n', stderr);
  std::fflush(stderr);
}

int writeSynthetic(vt::cli::Args& args, const std::string& kind, const std::string& out, bool quiet) {
  vt::acq::SyntheticOptions o;
  o.kind = vt::acq::parseSyntheticKind(kind);
  o.name = args.valueOr("name", "");
  o.scanLength_m = args.doubleOr("length-mm", o.scanLength_m * 1e3) * 1e-3;
  o.lines = args.intOr("lines", o.lines);
  o.passes = args.intOr("passes", o.passes);
  o.seed = std::uint64_t(args.intOr("seed", int(o.seed)));
  o.accelNoise_g = args.doubleOr("noise-g", o.accelNoise_g);
  o.topViewScale_px_per_mm = args.doubleOr("scale", o.topViewScale_px_per_mm);
  o.acrossPasses = args.flag("both-directions");
  const auto [w, h] = args.sizeOr("photo", {o.photoWidth, o.photoHeight});
  o.photoWidth = w, o.photoHeight = h;
  const int jobs = args.intOr("jobs", 0);
  args.finish();
  if (o.lines > 2000 || o.passes > 100 || o.scanLength_m > 1.0) vt::fail("acquire --synthetic: scan too large (lines <= 2000, passes <= 100, length <= 1000 mm)");
  const auto truth = vt::acq::writeSyntheticScan(o, out, jobs);
  if (!quiet) {
    std::printf("synthetic %s scan: %d lines x %d passes, %.0f x %.0f mm -> %s\n", kind.c_str(), o.lines, o.passes,
                o.scanLength_m * 1e3, o.lines * o.lineSpacing_m * 1e3, out.c_str());
  }
  return 0;
}

}  // namespace

VT_COMMAND(acquire,
           "acquire SCAN_DIR --out DATASET_DIR [--jobs N] [--quiet] [--no-float-map] [--compat paper|reference]\n"
           "             [--no-waveforms] [--waveform-ms MS]\n"
           "             vtouching acquire --synthetic KIND --out SCAN_DIR [--lines N] [--length-mm L] [--passes N]"
           " [--seed N] [--noise-g G] [--photo WxH] [--scale PX_PER_MM] [--name NAME] [--both-directions]",
           "robot + accelerometer logs + photo -> pixel-aligned vibration map (or simulate a scan)") {
  const auto out = args.value("out");
  const bool quiet = args.flag("quiet");
  if (const auto kind = args.value("synthetic")) {
    if (!out) vt::fail("acquire --synthetic: --out SCAN_DIR is required");
    return writeSynthetic(args, *kind, *out, quiet);
  }
  const int jobs = args.intOr("jobs", 0);
  const bool floatMap = !args.flag("no-float-map");
  const auto compat = args.value("compat");
  const bool waveforms = !args.flag("no-waveforms");
  vt::acq::WaveformOptions waveformOptions;
  waveformOptions.duration_s = args.doubleOr("waveform-ms", 0.0) * 1e-3;
  const auto positional = args.positionals();
  args.finish();
  if (positional.size() != 1) vt::fail("acquire: expected one SCAN_DIR (see vtouching help)");
  if (!out) vt::fail("acquire: --out DATASET_DIR is required");
  if (jobs < 0 || jobs > 256) vt::fail("acquire: --jobs must be in 0..256");

  const auto start = std::chrono::steady_clock::now();
  const vt::acq::Scan scan = vt::acq::loadScan(positional[0]);
  vt::acq::AcquireOptions options;
  options.jobs = jobs;
  if (compat) {
    if (*compat != "paper" && *compat != "reference") vt::fail("acquire: --compat must be 'paper' or 'reference'");
    options.compat = *compat == "reference" ? vt::acq::Compat::Reference : vt::acq::Compat::Paper;
  }
  if (!quiet && isatty(STDERR_FILENO)) options.onLineDone = drawProgress;
  const vt::acq::AcquireResult result = vt::acq::acquire(scan, options);
  if (vt::stopRequested()) {
    // The one shutdown path: an interrupted acquisition writes nothing and says so.
    std::fprintf(stderr, "vtouching: acquire: interrupted; nothing written to %s\n", out->c_str());
    return 130;
  }
  vt::acq::writeDataset(result, *out, floatMap);
  if (waveforms) {
    vt::acq::writeWaveforms(vt::acq::measureWaveforms(result, waveformOptions),
                            std::filesystem::path(*out) / result.config.name / "waveforms");
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!quiet) {
    std::size_t taxels = 0;
    for (const auto& line : result.lines) taxels += line.taxels.size();
    std::printf("%s: %zu lines, %zu taxels, calibration rms %.3f px (max %.3f px)\n", result.config.name.c_str(),
                result.lines.size(), taxels, result.calibration.rmsError_px, result.calibration.maxError_px);
    std::printf("  V_scale %.3f g  V_mean %.3f g  V_std %.3f g\n", result.stats.scale, result.stats.mean, result.stats.std);
    std::printf("  %dx%d px, %.3f x %.3f mm/px -> %s/%s/ (%.2f s)\n", result.photo.width, result.photo.height,
                result.mmPerPixel[0], result.mmPerPixel[1], out->c_str(), result.config.name.c_str(), seconds);
  }
  return 0;
}
