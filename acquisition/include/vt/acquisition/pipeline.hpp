#pragma once
// The whole acquisition: scan directory -> calibrated, aligned, binned, mapped, warped and
// cropped dataset entry. acquire() may be called from any thread; it runs lines on its own
// worker threads and calls onLineDone from them.
#include <array>
#include <filesystem>
#include <functional>
#include <optional>

#include "vt/acquisition/alignment.hpp"
#include "vt/acquisition/calibration.hpp"
#include "vt/acquisition/map.hpp"
#include "vt/acquisition/noise.hpp"
#include "vt/acquisition/scan.hpp"
#include "vt/acquisition/statistics.hpp"

namespace vt::acq {

struct WaveformGrid;

struct AcquireOptions {
  int jobs = 0;  // worker threads for lines; 0 = hardware concurrency
  std::optional<Compat> compat;  // overrides scan.json's "compat" (--compat)
  std::optional<std::array<double, 2>> focal_px;  // overrides scan.json's "focal_px" (--focal-px): mean, std
  bool keepSamples = false;  // keep every line's first pass (LineResult::firstPass) for measureWaveforms
  /// Called after each line (from a worker thread, serialised): lines done, lines total.
  std::function<void(std::size_t, std::size_t)> onLineDone;
};

/// The map of the passes along the other robot axis (a scan with lines in both directions).
struct AcrossMap {
  std::vector<LineResult> lines;
  TaxelStats stats;
  TaxelStats statsCorrected;  // noise-corrected (AcquireResult::noise), when the floor is known
  TaxelRaster map;  // same grid as AcquireResult::map
};

/// Everything the pipeline produced, in the final (warped, cropped) pixel grid.
struct AcquireResult {
  ScanConfig config;
  CalibrationResult calibration;
  std::vector<Correspondence> calibrationPoints;
  int axis = 1;                         // robot axis of the main map's passes (Y unless the scan has only X lines)
  std::vector<LineResult> lines;        // the main map's lines
  TaxelStats stats;                     // over the main map's taxel values, before normalisation
  NoiseFloor noise;                     // the accelerometer's, from its readings at rest (all lines)
  TaxelStats statsCorrected;            // stats with the noise's share removed, when noise.known
  Image8 photo;                         // RGB
  TaxelRaster map;                      // V in g + coverage, same size as photo
  std::optional<AcrossMap> across;      // passes along the other axis, when the scan has them
  std::optional<Image8> authorsMap;     // --compat reference: the map as the authors' run.py draws it (8-bit)
  std::array<double, 9> photoToOutput;  // original photo pixel -> final pixel (warp then crop)
  std::array<double, 2> mmPerPixel{0, 0};       // along final u and v, from the calibrated geometry
  std::array<double, 2> physicalSize_m{0, 0};   // from scan.json, else estimated
  int jobs = 0;                                 // AcquireOptions::jobs; writeDataset uses as many threads
};

/// Runs the method of docs/scan-format.md on a loaded scan.
AcquireResult acquire(const Scan& scan, const AcquireOptions& options = {});

/// Final pixel of a world point (X, Y on the object surface), through f, warp and crop.
glm::dvec2 worldToOutput(const AcquireResult& result, double x_m, double y_m) noexcept;

/// Unit direction, in map UV (u right, v up), in which the passes along robot `axis` cross
/// the final image at the centre of the scanned area.
glm::dvec2 scanDirectionUv(const AcquireResult& result, int axis) noexcept;

/// Writes OUT/NAME/{NAME.png, NAME_acc.png (16-bit), NAME_map.json, NAME_map.f32 (optional),
/// NAME_preview.png, NAME_calibration.json, waveforms/ when `waveforms` is given} as a whole
/// folder: built under a temporary name and moved into place, so a failure leaves any previous
/// OUT/NAME intact. An existing OUT/NAME is refused (vt::Error suggesting --force) unless `replace`.
/// The PNGs are compressed on up to `result.jobs` threads.
void writeDataset(const AcquireResult& result, const std::filesystem::path& outDir, bool writeFloatMap = true,
                  bool replace = false, const WaveformGrid* waveforms = nullptr);

}  // namespace vt::acq
