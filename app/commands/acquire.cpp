// `vtouching acquire`: a scan directory -> a dataset entry in the published layout, or
// (with --synthetic) a simulated scan directory to feed it.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>

#include "cli.hpp"
#include "vt/acquisition/pipeline.hpp"
#include "vt/core/stop.hpp"
#include "vt/acquisition/synthetic.hpp"
#include "vt/acquisition/waveforms.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/output_file.hpp"

namespace {

void drawProgress(std::size_t done, std::size_t total) {
  constexpr int kWidth = 40;
  const int filled = int(kWidth * done / std::max<std::size_t>(total, 1));
  std::fprintf(stderr, "\racquire [%.*s%*s] %zu/%zu lines", filled, "########################################",
               kWidth - filled, "", done, total);
  if (done == total) std::fputc('\n', stderr);
  std::fflush(stderr);
}

// Output images (the photo, the rectified top view) stay inside the image budget.
void checkImageBudget(double width_px, double height_px, const char* what) {
  if (width_px > vt::budget::kImageSide_px || height_px > vt::budget::kImageSide_px ||
      width_px * height_px > double(vt::budget::kImagePixels)) {
    vt::fail("acquire --synthetic: the ", what, " would be ", std::lround(width_px), "x", std::lround(height_px),
             " pixels, over the limit of ", vt::budget::kImageSide_px, " per side and ", vt::budget::kImagePixels,
             " pixels (docs/RELIABILITY.md)");
  }
}

int writeSynthetic(vt::cli::Args& args, const std::string& kind, const std::string& out, bool quiet, bool force) {
  vt::acq::SyntheticOptions o;
  o.kind = vt::acq::parseSyntheticKind(kind);
  o.name = args.valueOr("name", "");
  o.scanLength_m = args.doubleIn("length-mm", o.scanLength_m * 1e3, 1.0, 1000.0) * 1e-3;
  o.lines = args.intIn("lines", o.lines, 1, 2000);
  o.passes = args.intIn("passes", o.passes, 1, 100);
  o.seed = std::uint64_t(args.intIn("seed", int(o.seed), 0, std::numeric_limits<int>::max()));
  o.accelNoise_g = args.doubleIn("noise-g", o.accelNoise_g, 0.0, 10.0);
  o.topViewScale_px_per_mm = args.doubleIn("scale", o.topViewScale_px_per_mm, 0.1, 100.0);
  o.acrossPasses = args.flag("both-directions");
  o.authorsRig = args.flag("authors-rig");
  o.targetViews = args.intIn("target-views", o.targetViews, 0, 24);
  const auto [w, h] = args.sizeOr("photo", {o.photoWidth, o.photoHeight});
  o.photoWidth = w, o.photoHeight = h;
  const int jobs = args.intIn("jobs", 0, 0, 256);
  args.finish();
  checkImageBudget(w, h, "photo");
  checkImageBudget(o.scanLength_m * 1e3 * o.topViewScale_px_per_mm, o.lines * o.lineSpacing_m * 1e3 * o.topViewScale_px_per_mm,
                   "top view (--length-mm and --lines times --scale)");
  const auto truth = vt::acq::writeSyntheticScan(o, out, jobs, force);
  if (!quiet) {
    std::printf("synthetic %s scan: %d lines x %d passes, %.0f x %.0f mm -> %s\n", kind.c_str(), o.lines, o.passes,
                o.scanLength_m * 1e3, o.lines * o.lineSpacing_m * 1e3, out.c_str());
  }
  return 0;
}

// --focal-px F or F,STD: a prior on the focal length in pixels (STD default 2 % of F).
std::array<double, 2> parseFocal(const std::string& text) {
  const auto comma = text.find(',');
  char* end = nullptr;
  const double f = std::strtod(text.c_str(), &end);
  double sd = 0.02 * f;
  bool ok = end != text.c_str() && (comma == std::string::npos ? *end == '\0' : end == text.c_str() + comma);
  if (ok && comma != std::string::npos) {
    const char* at = text.c_str() + comma + 1;
    sd = std::strtod(at, &end);
    ok = end != at && *end == '\0';
  }
  if (!ok || !(f >= 1 && f <= 1e6) || !(sd > 0 && sd <= f)) {
    vt::fail("acquire: --focal-px must be F or F,STD (pixels, F in [1, 1e6], 0 < STD <= F), got '", text, "'");
  }
  return {f, sd};
}

}  // namespace

VT_COMMAND(acquire) {
  const auto out = args.value("out");
  const bool quiet = args.flag("quiet");
  const bool force = args.flag("force");  // replace an existing output folder
  if (const auto kind = args.value("synthetic")) {
    if (!out) vt::fail("acquire --synthetic: --out SCAN_DIR is required");
    return writeSynthetic(args, *kind, *out, quiet, force);
  }
  const int jobs = args.intOr("jobs", 0);
  const bool floatMap = !args.flag("no-float-map");
  const auto compat = args.value("compat");
  const auto focal = args.value("focal-px");
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
  vt::refuseExisting(std::filesystem::path(*out) / scan.config.name, force);  // before the work, not after
  vt::acq::AcquireOptions options;
  options.jobs = jobs;
  options.keepSamples = waveforms;  // measureWaveforms cuts from them
  if (focal) options.focal_px = parseFocal(*focal);
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
  // The waveforms go inside the staged object folder: a failure while writing them leaves the
  // previous object as it was, and --no-waveforms with --force leaves no stale waveforms/.
  const auto grid = waveforms ? std::optional(vt::acq::measureWaveforms(result, waveformOptions)) : std::nullopt;
  vt::acq::writeDataset(result, *out, floatMap, force, grid ? &*grid : nullptr);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!quiet) {
    std::size_t taxels = 0;
    for (const auto& line : result.lines) taxels += line.taxels.size();
    std::printf("%s: %zu lines, %zu taxels, calibration rms %.3f px (max %.3f px)\n", result.config.name.c_str(),
                result.lines.size(), taxels, result.calibration.rmsError_px, result.calibration.maxError_px);
    std::printf("  V_scale %.3f g  V_mean %.3f g  V_std %.3f g\n", result.stats.scale, result.stats.mean, result.stats.std);
    if (result.noise.known) {
      const auto& c = result.statsCorrected;
      std::printf("  noise floor %.4f g (%zu readings at rest); noise-corrected V_scale %.3f g  V_mean %.3f g  V_std %.3f g\n",
                  result.noise.sigma_g, result.noise.samples, c.scale, c.mean, c.std);
    } else {
      std::printf("  noise floor unknown (%zu readings at rest, need %zu): no noise-corrected statistics\n",
                  result.noise.samples, vt::acq::kMinRestSamples);
    }
    std::printf("  %dx%d px, %.3f x %.3f mm/px -> %s/%s/ (%.2f s)\n", result.photo.width, result.photo.height,
                result.mmPerPixel[0], result.mmPerPixel[1], out->c_str(), result.config.name.c_str(), seconds);
  }
  return 0;
}
