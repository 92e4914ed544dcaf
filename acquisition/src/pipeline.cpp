#include "vt/acquisition/pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "vt/acquisition/authors_map.hpp"
#include "vt/core/error.hpp"
#include "vt/core/log.hpp"
#include "vt/core/stop.hpp"
#include "parallel.hpp"

namespace vt::acq {
namespace {

// Lines are independent: each is parsed, fitted and binned on the worker pool.
std::vector<LineResult> processLines(const Scan& scan, const ScanConfig& config, const AcquireOptions& options) {
  const std::size_t total = scan.lines.size();
  std::vector<LineResult> results(total);
  std::mutex progressMutex;
  // Each worker places and sorts its lines' samples in the same buffers: no fresh memory (and
  // no page faults) per line unless the samples are kept.
  std::vector<LineBuffers> buffers(detail::workerCount(total, options.jobs));
  detail::parallelFor(
      total, options.jobs,
      [&](std::size_t i, std::size_t worker) {
        if (stopRequested()) return;  // Ctrl-C: the remaining lines are skipped, nothing is written
        const LineFiles& files = scan.lines[i];
        results[i] = processLine(loadLine(files, config), config, str(files.robot.string(), " (line ", i, ")"), files.axis,
                                 buffers[worker], options.keepSamples);
      },
      [&](std::size_t finished) {
        if (!options.onLineDone) return;
        std::lock_guard lock(progressMutex);
        options.onLineDone(finished, total);
      });
  return results;
}

Image8 cropImage(const Image8& src, const std::array<int, 4>& c) {
  Image8 dst(c[2], c[3], src.channels);
  for (int y = 0; y < c[3]; ++y)
    for (int x = 0; x < c[2]; ++x)
      for (int ch = 0; ch < src.channels; ++ch) dst.at(x, y, ch) = src.at(c[0] + x, c[1] + y, ch);
  return dst;
}

TaxelRaster cropRaster(const TaxelRaster& src, const std::array<int, 4>& c) {
  TaxelRaster dst{ImageF(c[2], c[3], 1), cropImage(src.coverage, c)};
  for (int y = 0; y < c[3]; ++y)
    for (int x = 0; x < c[2]; ++x) dst.value_g.at(x, y) = src.value_g.at(c[0] + x, c[1] + y);
  return dst;
}

// Mean robot (X, Y) of the main map's taxel centres.
glm::dvec2 scannedCentre(const AcquireResult& r) {
  glm::dvec2 sum{0, 0};
  std::size_t n = 0;
  for (const LineResult& line : r.lines) {
    for (const Taxel& t : line.taxels) {
      const auto w = line.world(0.5 * (t.y0_m + t.y1_m));
      sum += glm::dvec2(w[0], w[1]), ++n;
    }
  }
  return n ? sum / double(n) : sum;
}

// mm per final pixel along u and v: the inverse of the local Jacobian world(mm) -> pixel.
std::array<double, 2> estimateMmPerPixel(const AcquireResult& r) {
  if (r.lines.empty()) return {0, 0};
  const glm::dvec2 c = scannedCentre(r);
  const double x = c.x, y = c.y, h = 1e-3;
  const glm::dvec2 p = worldToOutput(r, x, y);
  const glm::dvec2 dx = (worldToOutput(r, x + h, y) - p), dy = (worldToOutput(r, x, y + h) - p);
  const glm::dmat2 J(dx, dy);  // columns: pixels per mm along X and along Y
  const glm::dmat2 inv = glm::inverse(J);  // column k: world mm per pixel step along u (k=0) or v (k=1)
  return {std::hypot(inv[0][0], inv[0][1]), std::hypot(inv[1][0], inv[1][1])};
}

// Statistics of a set of lines' taxel values.
TaxelStats lineStats(const std::vector<LineResult>& lines) {
  std::vector<double> values;
  for (const LineResult& line : lines)
    for (const Taxel& t : line.taxels) values.push_back(t.v_g);
  return computeStats(values);
}

}  // namespace

glm::dvec2 worldToOutput(const AcquireResult& result, double x_m, double y_m) noexcept {
  return applyHomography(result.photoToOutput, result.calibration.camera.project(x_m, y_m));
}

glm::dvec2 scanDirectionUv(const AcquireResult& result, int axis) noexcept {
  const glm::dvec2 c = scannedCentre(result), step = axis == 0 ? glm::dvec2(1e-3, 0) : glm::dvec2(0, 1e-3);
  const glm::dvec2 d = worldToOutput(result, c.x + step.x, c.y + step.y) - worldToOutput(result, c.x, c.y);
  // Pixels (right, down) to UV (right, up); pixels are square in the published layout.
  const glm::dvec2 uv{d.x, -d.y};
  const double n = glm::length(uv);
  return n > 0 ? uv / n : glm::dvec2(1, 0);
}

AcquireResult acquire(const Scan& scan, const AcquireOptions& options) {
  ScanConfig config = scan.config;
  if (options.compat) config.compat = *options.compat;
  // The authors' code draws each taxel 4 px to both sides of its line.
  if (config.compat == Compat::Reference) config.stretch_px = 4.0;
  if (options.focal_px) config.focal_px = options.focal_px;
  const std::string jsonName = (scan.dir / "scan.json").string();
  AcquireResult r;
  r.config = config;
  r.jobs = options.jobs;
  Image8 photo = loadImage8(scan.photo, 3);
  r.calibrationPoints = scan.calibration;
  if (config.camera) {
    r.calibration = givenCamera(*config.camera, scan.calibration);
  } else {
    const CalibrationPriors priors{config.principalPointPrior, config.focal_px};
    r.calibration = calibrateCamera(scan.calibration, photo.width, photo.height, priors, jsonName + " calibration",
                                    scan.calibrationViews);
  }
  log::debug("calibration: reprojection rms ", r.calibration.rmsError_px, " px, max ", r.calibration.maxError_px, " px");
  std::vector<LineResult> all = processLines(scan, config, options);
  if (stopRequested()) return r;  // interrupted: the caller writes nothing
  // The main map is the paper's direction (passes along Y); lines along X make the across map.
  const bool anyY = std::any_of(all.begin(), all.end(), [](const LineResult& l) { return l.axis == 1; });
  r.axis = anyY ? 1 : 0;
  r.noise = estimateNoiseFloor(all);  // one sensor: the rest readings of every line, both directions
  std::vector<LineResult> other;
  for (LineResult& line : all) (line.axis == r.axis ? r.lines : other).push_back(std::move(line));
  r.stats = lineStats(r.lines);
  if (r.stats.count == 0) fail(jsonName, ": no taxels were produced");
  if (r.noise.known) r.statsCorrected = noiseCorrectedStats(r.lines, r.noise.sigma_g);
  r.map = rasteriseTaxels(r.lines, r.calibration.camera, photo.width, photo.height, config.stretch_px);
  if (config.compat == Compat::Reference) {
    r.authorsMap = authorsMap(r.lines, r.calibration.camera, photo.width, photo.height, config.perspective, config.warpSize,
                              config.crop);
  }
  if (!other.empty()) {
    AcrossMap across{std::move(other), {}, {}};
    across.stats = lineStats(across.lines);
    if (across.stats.count == 0) fail(jsonName, ": no taxels were produced by the lines along X");
    if (r.noise.known) across.statsCorrected = noiseCorrectedStats(across.lines, r.noise.sigma_g);
    across.map = rasteriseTaxels(across.lines, r.calibration.camera, photo.width, photo.height, config.stretch_px);
    r.across = std::move(across);
  }
  r.photoToOutput = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (config.perspective) {
    const int w = config.warpSize[0] > 0 ? config.warpSize[0] : photo.width;
    const int h = config.warpSize[1] > 0 ? config.warpSize[1] : photo.height;
    photo = warpImage(photo, *config.perspective, w, h);
    r.map = warpRaster(r.map, *config.perspective, w, h);
    if (r.across) r.across->map = warpRaster(r.across->map, *config.perspective, w, h);
    r.photoToOutput = *config.perspective;
  }
  if (config.crop) {
    const auto& c = *config.crop;
    if (c[0] + c[2] > photo.width || c[1] + c[3] > photo.height) {
      fail(jsonName, ": field 'crop' [", c[0], ", ", c[1], ", ", c[2], ", ", c[3], "] exceeds the ", photo.width, "x",
           photo.height, " (warped) photo");
    }
    photo = cropImage(photo, c);
    r.map = cropRaster(r.map, c);
    if (r.across) r.across->map = cropRaster(r.across->map, c);
    r.photoToOutput = multiply3x3({1, 0, -double(c[0]), 0, 1, -double(c[1]), 0, 0, 1}, r.photoToOutput);
  }
  r.photo = std::move(photo);
  r.mmPerPixel = estimateMmPerPixel(r);
  for (double mm : r.mmPerPixel) {
    if (!std::isfinite(mm) || mm <= 0.0) {
      fail(jsonName, ": the calibrated geometry gives ", r.mmPerPixel[0], " x ", r.mmPerPixel[1],
           " mm/px (degenerate 'perspective' matrix or calibration points)");
    }
  }
  r.physicalSize_m = config.physicalSize_m
                         ? *config.physicalSize_m
                         : std::array<double, 2>{r.photo.width * r.mmPerPixel[0] * 1e-3, r.photo.height * r.mmPerPixel[1] * 1e-3};
  return r;
}

}  // namespace vt::acq
