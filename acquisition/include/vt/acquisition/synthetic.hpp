#pragma once
// The synthetic scanner: a simulated robot, accelerometer and camera over procedural objects
// modelled on the paper's eight, writing a scan directory plus the ground truth tests need.
// Any thread may call these functions; generation is deterministic for a given seed.
#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vt/acquisition/calibration.hpp"

namespace vt::acq {

/// One g: the synthetic accelerometer logs in g, as the paper's does.
inline constexpr double kStandardGravity_m_s2 = 9.80665;

/// The paper's objects (their roughness and look, not their exact patterns).
enum class SyntheticKind {
  PatternBoard,
  ReliefCeramicTile,
  PlasticGrid,
  SmoothCeramicTile,
  NotebookCover,
  GiftBox,
  RedEnvelope,
  PlasticCuttingBoard,
};

/// Names as used on the command line and as dataset folder names ("pattern_board", ...).
std::span<const std::string_view> syntheticKindNames() noexcept;
/// The name of one kind.
std::string_view kindName(SyntheticKind kind) noexcept;
/// Parses a kind name; throws vt::Error listing the valid names.
SyntheticKind parseSyntheticKind(std::string_view name);

/// A procedural object: surface amplitude of its fine texture and its colour, in object
/// coordinates (u along robot X, v along robot Y, metres from the object's corner).
struct SyntheticSurface {
  SyntheticKind kind = SyntheticKind::PatternBoard;
  double width_m = 0.1, height_m = 0.1;  // extent along X and Y
  double wavelength_m = 0.0005;          // fine texture period along Y
  double peakAmplitude_m = 1e-4;         // amplitude where roughness = 1

  /// Roughness in [0,1] (the pattern the stylus feels).
  double roughness(double u_m, double v_m) const noexcept;
  /// Surface height: roughness-modulated fine texture.
  double surfaceHeight_m(double u_m, double v_m) const noexcept;
  /// Display (sRGB-encoded) albedo in [0,1].
  std::array<float, 3> albedo(double u_m, double v_m) const noexcept;
};

/// Makes the surface of a kind for an object of the given size (peak vibration chosen per kind).
SyntheticSurface makeSurface(SyntheticKind kind, double width_m, double height_m, double speed_m_s);

/// Everything the simulation needs; defaults give the paper's 100 x 100 mm, 50-line scan.
struct SyntheticOptions {
  SyntheticKind kind = SyntheticKind::PatternBoard;
  std::string name;                  // default: the kind name
  double scanLength_m = 0.1;         // constant-velocity window along Y (the mapped length)
  int lines = 50;
  double lineSpacing_m = 0.002;
  int passes = 8;
  double speed_m_s = 0.02;
  double acceleration_m_s2 = 0.4;
  double dwell_s = 0.1;              // pause between passes
  double robotRate_hz = 125;
  double robotJitter_s = 0.0008;     // uniform +- on each robot timestamp
  double robotNoise_m = 5e-6;        // position noise (repeatability)
  double accelRate_hz = 500;
  double accelJitter_s = 0.0001;
  double accelNoise_g = 0.01;
  double accelClockOffset_s = 12.5;  // robot time = accelerometer time + offset
  int photoWidth = 640, photoHeight = 480;
  double cameraHeight_m = 0.36;
  double photoScale_px_per_mm = 2.9;  // at the object's centre: lines 2 mm apart ~ 2 * stretch px
  double topViewScale_px_per_mm = 2.5;
  int calibrationGrid = 5;           // n x n marked points
  bool acrossPasses = false;         // also scan lines along X (one per lineSpacing_m over the mapped length), after the Y lines
  int targetViews = 0;               // extra photos of a planar target in tilted poses (calibration_views)
  bool authorsRig = false;           // camera turned so +Y runs right to left in the photo, as in the authors'
                                     // rig (their run.py draws a taxel from its end column to its start column)
  double clickNoise_px = 0.15;
  std::uint64_t seed = 1;
};

/// What the simulation knows and the pipeline must recover.
struct SyntheticTruth {
  SyntheticOptions options;
  SyntheticSurface surface;
  CameraModel camera;
  double objectX0_m = 0, objectY0_m = 0;  // object corner in robot coordinates
  double windowY0_m = 0, windowY1_m = 0;  // the mapped (constant-velocity) span along Y
  std::vector<double> lineX_m;
  double travel_m = 0, passDuration_s = 0;
  std::vector<double> lineY_m;            // the across lines (passes along X), when acrossPasses
  double travelX_m = 0, passDurationX_s = 0;

  /// Noise-free expected taxel value |a - 1 g| at a robot-frame point, in g.
  double vibration_g(double x_m, double y_m) const noexcept;
  /// Robot-clock time at which pass `pass` of line `line` starts moving.
  double passStart_s(int line, int pass) const noexcept;
  /// True stylus Y at robot time t during that pass.
  double stylusY_m(int line, int pass, double t_s) const noexcept;
  /// Robot-clock interval of constant velocity (between the ramps) of that pass.
  std::array<double, 2> cruise_s(int line, int pass) const noexcept;
};

/// Computes the ground truth (camera, geometry) without writing anything.
SyntheticTruth makeSyntheticTruth(const SyntheticOptions& options);

/// `options.targetViews` views of a flat target (an 11 x 11 grid, its own coordinates, Z = 0)
/// seen by the scan's camera in tilted poses around the object's centre, covering the photo;
/// points outside the photo are left out, the rest clicked with `clickNoise_px` noise.
std::vector<std::vector<Correspondence>> syntheticTargetViews(const SyntheticTruth& truth);

/// Simulates the scan and writes it to `dir` (scan.json, photo.png, calibration.csv,
/// calibration_view_N.csv per target view, lines/*.csv, truth.json) as a whole folder; `jobs` threads generate lines (0 = hardware
/// concurrency). A non-empty existing `dir` is refused unless `replace`.
SyntheticTruth writeSyntheticScan(const SyntheticOptions& options, const std::filesystem::path& dir, int jobs = 0,
                                  bool replace = false);

}  // namespace vt::acq
