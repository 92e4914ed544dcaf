#pragma once
// The scan format (docs/scan-format.md): scan.json, the photo, calibration correspondences
// and per line a robot log and an accelerometer log. Loaders throw vt::Error naming the
// file, the line/field and the problem. Any thread may call these functions.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vt::acq {

/// Which method the pipeline follows (docs/scan-format.md, "--compat reference").
enum class Compat : std::uint8_t {
  Paper,      // the paper's Sec. III, with whole bins over each line (the default)
  Reference,  // the authors' published code, point by point
};

/// A camera calibrated elsewhere (scan.json "camera"): OpenCV's model, pose of the object plane.
struct KnownCamera {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::array<double, 5> distortion{};  // k1, k2, p1, p2, k3
  std::array<double, 3> rvec{}, t_m{};
};

/// Every constant of the method, as read from scan.json (defaults = the paper's values).
struct ScanConfig {
  std::string name;                      // object name, used for output file names
  int passesPerLine = 8;                 // back-and-forth passes over each line
  double windowW = 0.45;                 // w: the constant-velocity window is Ybar +- w*l
  int accelTrimStart = 1;                // j1 = argmin_j |t_j - t_i1| + accelTrimStart
  int accelTrimEnd = 1;                  // j2 = argmin_j |t_j - t_i2| - accelTrimEnd
  double taxelSize_m = 0.001;            // bin size along a line: one taxel per bin
  double stretch_px = 3.0;               // each taxel is drawn this far to both sides of its line
  int accelAxis = 2;                     // 0 = ax, 1 = ay, 2 = az (vertical)
  double gravity_g = 1.0;                // baseline subtracted before |.|
  double accelClockOffset_s = 0.0;       // robot time = accelerometer time + offset
  double maxFitResidual_m = 0.0005;      // a window farther than this from a line is not constant velocity
  int minWindowSamples = 4;              // fewer robot samples in the window: no constant-velocity phase
  double principalPointPrior = 1e-3;     // weak pull of (cx,cy) towards the image centre (px per px)
  std::optional<std::array<double, 2>> focal_px;  // prior on the focal length: mean, std (px)
  std::optional<KnownCamera> camera;     // use this camera instead of calibrating
  std::optional<std::array<double, 9>> perspective;  // row-major 3x3, photo pixel -> output pixel
  std::array<int, 2> warpSize{0, 0};     // output size of the perspective warp (0 = photo size)
  std::optional<std::array<int, 4>> crop;  // x, y, width, height in the warped image
  std::optional<std::array<double, 2>> physicalSize_m;  // width, height the final image covers
  Compat compat = Compat::Paper;         // "compat": "paper" | "reference"
};

/// One calibration point: robot coordinates on the object surface and its pixel in the photo.
struct Correspondence {
  double x_m = 0, y_m = 0;
  double u_px = 0, v_px = 0;
};

/// The two log files of one scan line and the robot axis its passes move along (0 = X, 1 = Y).
struct LineFiles {
  std::filesystem::path robot;
  std::filesystem::path accel;
  int axis = 1;
};

/// A scan directory, validated: config, photo path, calibration points and line files.
struct Scan {
  std::filesystem::path dir;
  ScanConfig config;
  std::filesystem::path photo;
  std::vector<Correspondence> calibration;
  /// Further views of a planar target (its own x_m, y_m, Z = 0) photographed by the same camera.
  std::vector<std::vector<Correspondence>> calibrationViews;
  std::vector<LineFiles> lines;
};

/// Samples of one pass in one log: time and three values (X/Y/Z in m, or ax/ay/az in g).
struct PassSeries {
  std::vector<double> t_s;
  std::vector<std::array<double, 3>> v;
};

/// Column names of a log, used in error messages ("x_m", "y_m", "z_m" or "ax_g", ...).
using LogColumns = std::array<std::string_view, 3>;
/// Value columns of a robot log.
inline constexpr LogColumns kRobotColumns{"x_m", "y_m", "z_m"};
/// Value columns of an accelerometer log.
inline constexpr LogColumns kAccelColumns{"ax_g", "ay_g", "az_g"};

/// Parses a log CSV (`pass,t_s,c0,c1,c2`, optional header line) into passes 0..N-1; rejects
/// bad numbers, NaN/inf, gaps in pass indices, non-monotonic or overlapping timestamps.
std::vector<PassSeries> parseLogCsv(std::string_view text, const std::string& source, const LogColumns& columns);

/// Parses a log .npy array (N x 5, '<f8' or '<f4', either order; rows as in the CSV) with
/// the same checks. A log file whose name ends in .npy is read this way (docs/scan-format.md).
std::vector<PassSeries> parseLogNpy(std::string_view bytes, const std::string& source, const LogColumns& columns);

/// A log as .npy bytes (N x 5 float64, rows pass, t_s, c0, c1, c2), as parseLogNpy reads.
std::string formatLogNpy(const std::vector<PassSeries>& passes);

/// Parses scan.json text; `source` names the file in errors.
ScanConfig parseScanConfig(std::string_view jsonText, const std::string& source);

/// Serialises a config as scan.json text (with the photo, calibration, line and extra
/// calibration view file names).
std::string scanConfigJson(const ScanConfig& config, const std::string& photo, const std::string& calibration,
                           const std::vector<LineFiles>& lines, const std::vector<std::string>& calibrationViews = {});

/// Parses calibration CSV text (`x_m,y_m,u_px,v_px`, optional header).
std::vector<Correspondence> parseCalibrationCsv(std::string_view text, const std::string& source);

/// Reads and validates SCAN_DIR/scan.json and everything it names (logs are parsed later, per line).
Scan loadScan(const std::filesystem::path& dir);

/// The robot and accelerometer passes of one line, checked against the config (pass count).
struct LineLogs {
  std::vector<PassSeries> robot;
  std::vector<PassSeries> accel;
};
/// Reads and parses both logs of one line.
LineLogs loadLine(const LineFiles& files, const ScanConfig& config);

/// Reads a whole file into a string; throws naming `what` and the path.
std::string readTextFile(const std::filesystem::path& path, std::string_view what);

}  // namespace vt::acq
