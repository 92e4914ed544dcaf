// scan.json: reading (every field checked, unknown fields rejected so typos surface) and writing.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "vt/acquisition/scan.hpp"
#include "vt/core/budgets.hpp"
#include "vt/core/error.hpp"
#include "vt/core/text_input.hpp"

namespace vt::acq {
namespace {

using nlohmann::json;

constexpr int kMinCalibrationPoints = 8;

double number(const json& doc, const char* key, double fallback, double lo, double hi, const std::string& source) {
  if (!doc.contains(key)) return fallback;
  const json& v = doc[key];
  if (!v.is_number()) fail(source, ": field '", key, "' must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi) fail(source, ": field '", key, "' = ", x, " out of range [", lo, ", ", hi, "]");
  return x;
}

int integer(const json& doc, const char* key, int fallback, int lo, int hi, const std::string& source) {
  if (!doc.contains(key)) return fallback;
  const json& v = doc[key];
  if (!v.is_number_integer()) fail(source, ": field '", key, "' must be an integer");
  const auto x = v.get<long long>();
  if (x < lo || x > hi) fail(source, ": field '", key, "' = ", x, " out of range [", lo, ", ", hi, "]");
  return int(x);
}

template <class T, std::size_t N>
std::array<T, N> numberArray(const json& v, const char* key, const std::string& source) {
  if (!v.is_array() || v.size() != N) fail(source, ": field '", key, "' must be an array of ", N, " numbers");
  std::array<T, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    if (!v[i].is_number()) fail(source, ": field '", key, "'[", i, "] must be a number");
    const double x = v[i].get<double>();
    if (!std::isfinite(x)) fail(source, ": field '", key, "'[", i, "] is not finite");
    if (std::is_integral_v<T> && std::abs(x) > 1e9) fail(source, ": field '", key, "'[", i, "] out of range");
    out[i] = T(x);
  }
  return out;
}

std::string text(const json& doc, const char* key, const std::string& source) {
  if (!doc.contains(key) || !doc[key].is_string() || doc[key].get<std::string>().empty()) {
    fail(source, ": field '", key, "' is missing or not a non-empty string");
  }
  return doc[key].get<std::string>();
}

json parseJson(std::string_view jsonText, const std::string& source) {
  checkJsonNesting(jsonText, source, budget::kJsonDepth);
  try {
    json doc = json::parse(jsonText);
    if (!doc.is_object()) fail(source, ": expected a JSON object");
    return doc;
  } catch (const json::exception& e) {  // parse errors and out-of-range numbers alike
    fail(source, ": invalid JSON: ", e.what());
  }
}

// A perspective matrix must map pixels to pixels: finite, invertible and not so badly conditioned
// that the warp turns into NaN or a single point. Scale-free (a homography's scale is arbitrary).
void checkPerspective(const std::array<double, 9>& m, const std::string& source) {
  double largest = 0.0;
  for (double x : m) largest = std::max(largest, std::abs(x));
  if (!(largest > 0.0) || !std::isfinite(largest)) fail(source, ": field 'perspective.matrix' is all zeros");
  std::array<double, 9> n{};
  for (std::size_t i = 0; i < 9; ++i) n[i] = m[i] / largest;
  const double det = n[0] * (n[4] * n[8] - n[5] * n[7]) - n[1] * (n[3] * n[8] - n[5] * n[6]) + n[2] * (n[3] * n[7] - n[4] * n[6]);
  if (!(std::abs(det) > 1e-12)) {
    fail(source, ": field 'perspective.matrix' is singular or nearly so (determinant ", det,
         " after scaling to a largest entry of 1): it must map the photo onto a plane");
  }
}

// Calibration needs points that span an area on the object and in the photo (not one line or
// point): the smaller principal spread (sqrt of the covariance's small eigenvalue) must exceed `least`.
double smallerSpread(const std::vector<Correspondence>& points, bool pixels) {
  double mx = 0, my = 0;
  for (const Correspondence& c : points) mx += pixels ? c.u_px : c.x_m, my += pixels ? c.v_px : c.y_m;
  mx /= double(points.size()), my /= double(points.size());
  double sxx = 0, syy = 0, sxy = 0;
  for (const Correspondence& c : points) {
    const double dx = (pixels ? c.u_px : c.x_m) - mx, dy = (pixels ? c.v_px : c.y_m) - my;
    sxx += dx * dx, syy += dy * dy, sxy += dx * dy;
  }
  const double n = double(points.size()), a = sxx / n, d = syy / n, b = sxy / n;
  const double small = 0.5 * (a + d) - std::sqrt(0.25 * (a - d) * (a - d) + b * b);
  return std::sqrt(std::max(0.0, small));
}

void checkCalibrationSpread(const std::vector<Correspondence>& points, const std::string& source) {
  if (!(smallerSpread(points, false) > 1e-4)) {
    fail(source, ": the calibration points do not span an area on the object (all on one line or point)");
  }
  if (!(smallerSpread(points, true) > 1.0)) {
    fail(source, ": the calibration points do not span an area in the photo (all on one line or point)");
  }
}

// "focal_px": F or [F, STD]: a prior on the focal length in pixels (STD default 2 % of F).
std::array<double, 2> focalPrior(const json& v, const std::string& source) {
  std::array<double, 2> f{0, 0};
  if (v.is_number()) f = {v.get<double>(), 0.02 * v.get<double>()};
  else f = numberArray<double, 2>(v, "focal_px", source);
  if (!(f[0] >= 1 && f[0] <= 1e6) || !(f[1] > 0 && f[1] <= f[0])) {
    fail(source, ": field 'focal_px' must be F or [F, STD] with F in [1, 1e6] px and 0 < STD <= F");
  }
  return f;
}

// "camera": {"fx", "fy", "cx", "cy", "distortion": [k1, k2, p1, p2, k3], "rvec": [3], "t_m": [3]}.
KnownCamera knownCamera(const json& v, const std::string& source) {
  static const std::set<std::string> keys{"fx", "fy", "cx", "cy", "distortion", "rvec", "t_m", "comment"};
  if (!v.is_object()) fail(source, ": field 'camera' must be an object (docs/scan-format.md)");
  for (const auto& [key, value] : v.items()) {
    if (!keys.count(key)) fail(source, ": unknown field 'camera.", key, "'");
  }
  for (const char* key : {"fx", "fy", "cx", "cy", "distortion", "rvec", "t_m"}) {
    if (!v.contains(key)) fail(source, ": field 'camera.", key, "' is missing");
  }
  KnownCamera c;
  c.fx = number(v, "fx", 0, 1, 1e6, source), c.fy = number(v, "fy", 0, 1, 1e6, source);
  c.cx = number(v, "cx", 0, -1e6, 1e6, source), c.cy = number(v, "cy", 0, -1e6, 1e6, source);
  c.distortion = numberArray<double, 5>(v["distortion"], "camera.distortion", source);
  c.rvec = numberArray<double, 3>(v["rvec"], "camera.rvec", source);
  c.t_m = numberArray<double, 3>(v["t_m"], "camera.t_m", source);
  for (double d : c.distortion) {
    if (std::abs(d) > 1e4) fail(source, ": field 'camera.distortion' out of range (|value| <= 1e4)");
  }
  if (!(c.t_m[2] > 0)) fail(source, ": field 'camera.t_m' must put the object in front of the camera (t_m[2] > 0)");
  return c;
}

}  // namespace

ScanConfig parseScanConfig(std::string_view jsonText, const std::string& source) {
  const json doc = parseJson(jsonText, source);
  static const std::set<std::string> known{
      "name", "photo", "calibration", "lines", "passes_per_line", "window_w", "accel_trim", "taxel_size_m",
      "stretch_px", "accel_axis", "gravity_g", "accel_clock_offset_s", "max_fit_residual_m", "min_window_samples",
      "principal_point_prior", "focal_px", "camera", "perspective", "crop", "physical_size_m", "compat",
      "calibration_views", "comment"};
  for (const auto& [key, value] : doc.items()) {
    if (!known.count(key)) fail(source, ": unknown field '", key, "' (see docs/scan-format.md)");
  }
  ScanConfig c;
  c.name = text(doc, "name", source);
  for (char ch : c.name) {
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-')) {
      fail(source, ": field 'name' may only hold letters, digits, '_' and '-' (it names output files)");
    }
  }
  c.passesPerLine = integer(doc, "passes_per_line", c.passesPerLine, 1, 1000, source);
  c.windowW = number(doc, "window_w", c.windowW, 0.05, 0.5, source);
  if (doc.contains("accel_trim")) {
    const auto trim = numberArray<int, 2>(doc["accel_trim"], "accel_trim", source);
    if (trim[0] < 0 || trim[1] < 0 || trim[0] > 1000 || trim[1] > 1000) fail(source, ": field 'accel_trim' out of range [0, 1000]");
    c.accelTrimStart = trim[0];
    c.accelTrimEnd = trim[1];
  }
  c.taxelSize_m = number(doc, "taxel_size_m", c.taxelSize_m, 1e-5, 0.1, source);
  c.stretch_px = number(doc, "stretch_px", c.stretch_px, 0.0, 100.0, source);
  if (doc.contains("accel_axis")) {
    const json& axis = doc["accel_axis"];
    const std::string name = axis.is_string() ? axis.get<std::string>() : "";
    if (name == "x") c.accelAxis = 0;
    else if (name == "y") c.accelAxis = 1;
    else if (name == "z") c.accelAxis = 2;
    else fail(source, ": field 'accel_axis' must be \"x\", \"y\" or \"z\"");
  }
  c.gravity_g = number(doc, "gravity_g", c.gravity_g, -10.0, 10.0, source);
  c.accelClockOffset_s = number(doc, "accel_clock_offset_s", c.accelClockOffset_s, -1e9, 1e9, source);
  c.maxFitResidual_m = number(doc, "max_fit_residual_m", c.maxFitResidual_m, 1e-7, 1.0, source);
  c.minWindowSamples = integer(doc, "min_window_samples", c.minWindowSamples, 2, 1000000, source);
  c.principalPointPrior = number(doc, "principal_point_prior", c.principalPointPrior, 0.0, 1e3, source);
  if (doc.contains("focal_px")) c.focal_px = focalPrior(doc["focal_px"], source);
  if (doc.contains("camera")) c.camera = knownCamera(doc["camera"], source);
  if (doc.contains("perspective")) {
    const json& p = doc["perspective"];
    if (!p.is_object() || !p.contains("matrix")) fail(source, ": field 'perspective' must be {\"matrix\": [9 numbers], \"size\": [w, h]}");
    c.perspective = numberArray<double, 9>(p["matrix"], "perspective.matrix", source);
    checkPerspective(*c.perspective, source);
    if (p.contains("size")) {
      c.warpSize = numberArray<int, 2>(p["size"], "perspective.size", source);
      if (c.warpSize[0] < 1 || c.warpSize[1] < 1 || c.warpSize[0] > budget::kImageSide_px ||
          c.warpSize[1] > budget::kImageSide_px || 1LL * c.warpSize[0] * c.warpSize[1] > budget::kImagePixels) {
        fail(source, ": field 'perspective.size' out of range: at most ", budget::kImageSide_px, " per side and ",
             budget::kImagePixels, " pixels");
      }
    }
  }
  if (doc.contains("crop")) {
    c.crop = numberArray<int, 4>(doc["crop"], "crop", source);
    if ((*c.crop)[0] < 0 || (*c.crop)[1] < 0 || (*c.crop)[2] < 1 || (*c.crop)[3] < 1) {
      fail(source, ": field 'crop' must be [x >= 0, y >= 0, width >= 1, height >= 1]");
    }
  }
  if (doc.contains("physical_size_m")) {
    c.physicalSize_m = numberArray<double, 2>(doc["physical_size_m"], "physical_size_m", source);
    if ((*c.physicalSize_m)[0] <= 0 || (*c.physicalSize_m)[1] <= 0) fail(source, ": field 'physical_size_m' must be positive");
  }
  if (doc.contains("compat")) {
    const json& v = doc["compat"];
    const std::string name = v.is_string() ? v.get<std::string>() : "";
    if (name == "paper") c.compat = Compat::Paper;
    else if (name == "reference") c.compat = Compat::Reference;
    else fail(source, ": field 'compat' must be \"paper\" or \"reference\"");
  }
  return c;
}

std::string scanConfigJson(const ScanConfig& c, const std::string& photo, const std::string& calibration,
                           const std::vector<LineFiles>& lines, const std::vector<std::string>& calibrationViews) {
  json doc;
  doc["name"] = c.name;
  doc["photo"] = photo;
  doc["calibration"] = calibration;
  if (!calibrationViews.empty()) doc["calibration_views"] = calibrationViews;
  json files = json::array();
  for (const LineFiles& f : lines) {
    files.push_back({{"robot", f.robot.generic_string()}, {"accel", f.accel.generic_string()}, {"axis", f.axis == 0 ? "x" : "y"}});
  }
  doc["lines"] = files;
  doc["passes_per_line"] = c.passesPerLine;
  doc["window_w"] = c.windowW;
  doc["accel_trim"] = {c.accelTrimStart, c.accelTrimEnd};
  doc["taxel_size_m"] = c.taxelSize_m;
  doc["stretch_px"] = c.stretch_px;
  doc["accel_axis"] = std::string(1, "xyz"[c.accelAxis]);
  doc["gravity_g"] = c.gravity_g;
  doc["accel_clock_offset_s"] = c.accelClockOffset_s;
  doc["max_fit_residual_m"] = c.maxFitResidual_m;
  doc["min_window_samples"] = c.minWindowSamples;
  doc["principal_point_prior"] = c.principalPointPrior;
  if (c.focal_px) doc["focal_px"] = *c.focal_px;
  if (c.camera) {
    const KnownCamera& k = *c.camera;
    doc["camera"] = {{"fx", k.fx}, {"fy", k.fy}, {"cx", k.cx}, {"cy", k.cy}, {"distortion", k.distortion}, {"rvec", k.rvec}, {"t_m", k.t_m}};
  }
  if (c.perspective) doc["perspective"] = {{"matrix", *c.perspective}, {"size", c.warpSize}};
  if (c.crop) doc["crop"] = *c.crop;
  if (c.physicalSize_m) doc["physical_size_m"] = *c.physicalSize_m;
  doc["compat"] = c.compat == Compat::Reference ? "reference" : "paper";
  return doc.dump(2) + "\n";
}

Scan loadScan(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) fail("scan directory '", dir.string(), "': not found");
  const auto jsonPath = dir / "scan.json";
  const std::string source = jsonPath.string();
  const std::string jsonText = readTextFile(jsonPath, "scan description");
  Scan scan;
  scan.dir = dir;
  scan.config = parseScanConfig(jsonText, source);
  const json doc = parseJson(jsonText, source);
  scan.photo = dir / text(doc, "photo", source);
  if (!std::filesystem::is_regular_file(scan.photo, ec)) fail(source, ": photo '", scan.photo.string(), "': file not found");
  const auto calibPath = dir / text(doc, "calibration", source);
  scan.calibration = parseCalibrationCsv(readTextFile(calibPath, "calibration points"), calibPath.string());
  if (scan.calibration.size() < std::size_t(kMinCalibrationPoints)) {
    fail(calibPath.string(), ": too few calibration points: ", scan.calibration.size(), " (need at least ",
         kMinCalibrationPoints, ")");
  }
  checkCalibrationSpread(scan.calibration, calibPath.string());
  if (doc.contains("calibration_views")) {
    const json& views = doc["calibration_views"];
    if (!views.is_array()) fail(source, ": field 'calibration_views' must be an array of calibration CSV files");
    for (std::size_t i = 0; i < views.size(); ++i) {
      if (!views[i].is_string()) fail(source, ": field 'calibration_views'[", i, "] must be a file name");
      const auto path = dir / views[i].get<std::string>();
      scan.calibrationViews.push_back(parseCalibrationCsv(readTextFile(path, "calibration view"), path.string()));
      if (scan.calibrationViews.back().size() < std::size_t(kMinCalibrationPoints)) {
        fail(path.string(), ": too few calibration points: ", scan.calibrationViews.back().size(), " (need at least ",
             kMinCalibrationPoints, ")");
      }
      checkCalibrationSpread(scan.calibrationViews.back(), path.string());
    }
  }
  if (!doc.contains("lines") || !doc["lines"].is_array() || doc["lines"].empty()) {
    fail(source, ": field 'lines' must be a non-empty array of {\"robot\": file, \"accel\": file}");
  }
  for (std::size_t i = 0; i < doc["lines"].size(); ++i) {
    const json& line = doc["lines"][i];
    const std::string where = str(source, ": lines[", i, "]");
    if (!line.is_object()) fail(where, " must be an object");
    LineFiles files{dir / text(line, "robot", where), dir / text(line, "accel", where)};
    if (line.contains("axis")) {
      const std::string axis = line["axis"].is_string() ? line["axis"].get<std::string>() : "";
      if (axis != "x" && axis != "y") fail(where, ": field 'axis' must be \"x\" or \"y\" (the robot axis the passes move along)");
      files.axis = axis == "x" ? 0 : 1;
    }
    if (!std::filesystem::is_regular_file(files.robot, ec)) fail(where, ": robot log '", files.robot.string(), "': file not found");
    if (!std::filesystem::is_regular_file(files.accel, ec)) {
      fail(where, ": accelerometer log '", files.accel.string(), "': file not found");
    }
    scan.lines.push_back(std::move(files));
  }
  return scan;
}

}  // namespace vt::acq
