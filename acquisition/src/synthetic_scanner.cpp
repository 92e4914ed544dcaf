// The simulated rig: trapezoidal robot passes sampled with jitter at the robot's rate, an
// accelerometer with its own rate and clock offset feeling the stylus ride over the surface,
// and a calibrated-camera photo of the object's albedo with radial distortion.
#include <charconv>
#include <cmath>
#include <numbers>
#include <random>

#include <nlohmann/json.hpp>

#include "parallel.hpp"
#include "vt/acquisition/map.hpp"
#include "vt/acquisition/scan.hpp"
#include "vt/acquisition/synthetic.hpp"
#include "vt/core/error.hpp"
#include "vt/core/output_file.hpp"
#include "vt/scene/image.hpp"

namespace vt::acq {
namespace {

constexpr double kWindowW = 0.45;

struct Motion {
  double s, v, a;  // distance along the pass, speed, acceleration (signs: along the pass)
};

// Trapezoidal profile: accelerate, cruise, decelerate over `travel` at `speed`/`accel`.
Motion trapezoid(double tau, double travel, double speed, double accel, double duration) noexcept {
  const double ramp = speed / accel, d = 0.5 * speed * ramp;
  if (tau <= 0) return {0, 0, 0};
  if (tau >= duration) return {travel, 0, 0};
  if (tau < ramp) return {0.5 * accel * tau * tau, accel * tau, accel};
  if (tau < duration - ramp) return {d + speed * (tau - ramp), speed, 0};
  const double rest = duration - tau;
  return {travel - 0.5 * accel * rest * rest, accel * rest, -accel};
}

// Look-at pose in OpenCV convention: image right ~ +Y, image down ~ +X on the table (the
// authors' rig: image right ~ -Y, down ~ -X).
CameraModel makeCamera(const SyntheticOptions& o, double cx_m, double cy_m, double extentX_m, double extentY_m) {
  const glm::dvec3 centre(cx_m, cy_m, 0.0);
  const glm::dvec3 eye = centre + glm::dvec3(-0.25, 0.11, 1.0) * o.cameraHeight_m;
  const glm::dvec3 z = glm::normalize(centre - eye);
  const glm::dvec3 right(0, o.authorsRig ? -1 : 1, 0);
  const glm::dvec3 x = glm::normalize(right - z * glm::dot(right, z));
  const glm::dvec3 y = glm::cross(z, x);
  const std::array<double, 9> R{x.x, x.y, x.z, y.x, y.y, y.z, z.x, z.y, z.z};
  CameraModel cam;
  const double dist = glm::length(centre - eye);
  // The requested scale at the centre, reduced if the object would not fit in 90% of the photo.
  const double fit = 0.9 * std::min(o.photoWidth * dist / extentY_m, o.photoHeight * dist / extentX_m);
  const double f = std::min(o.photoScale_px_per_mm * 1e3 * dist, fit);
  cam.fx = f;
  cam.fy = f * 1.003;
  cam.cx = o.photoWidth / 2.0 + 5.3;
  cam.cy = o.photoHeight / 2.0 - 3.7;
  cam.k1 = -0.06;
  cam.k2 = 0.015;
  cam.rvec = vectorFromRotation(R);
  const glm::dvec3 t = -glm::dvec3(glm::dot(x, eye), glm::dot(y, eye), glm::dot(z, eye));
  cam.t_m = {t.x, t.y, t.z};
  return cam;
}

// Plane homography world (X, Y, 1) in metres -> undistorted pixel.
std::array<double, 9> planeHomography(const CameraModel& c) {
  const auto R = rotationFromVector(c.rvec);
  const std::array<double, 9> rt{R[0], R[1], c.t_m[0], R[3], R[4], c.t_m[1], R[6], R[7], c.t_m[2]};
  return multiply3x3({c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1}, rt);
}

Image8 renderPhoto(const SyntheticTruth& truth) {
  const SyntheticOptions& o = truth.options;
  const CameraModel& c = truth.camera;
  Image8 photo(o.photoWidth, o.photoHeight, 3);
  for (int py = 0; py < o.photoHeight; ++py) {
    for (int px = 0; px < o.photoWidth; ++px) {
      float rgb[3] = {0, 0, 0};
      for (int sy = 0; sy < 2; ++sy) {
        for (int sx = 0; sx < 2; ++sx) {
          const glm::dvec2 p = c.planePoint({px - 0.25 + 0.5 * sx, py - 0.25 + 0.5 * sy});
          const double u = p.x - truth.objectX0_m, v = p.y - truth.objectY0_m;
          std::array<float, 3> a{0.3f, 0.24f, 0.18f};  // the table around the object
          if (u >= 0 && v >= 0 && u <= truth.surface.width_m && v <= truth.surface.height_m) a = truth.surface.albedo(u, v);
          for (int k = 0; k < 3; ++k) rgb[k] += 0.25f * a[std::size_t(k)];
        }
      }
      for (int k = 0; k < 3; ++k) photo.at(px, py, k) = std::uint8_t(std::clamp(rgb[k], 0.0f, 1.0f) * 255.0f + 0.5f);
    }
  }
  return photo;
}

void appendNumber(std::string& out, double value, int precision) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::fixed, precision);
  out.append(buf, r.ptr);
}

// One scan line: the robot axis its passes move along, its fixed (across) coordinate, the
// mapped window along it, travel, pass duration and when its first pass starts.
struct LinePlan {
  int axis;
  double across_m, window0_m, window1_m, travel_m, duration_s, start_s;
};

// Line k of the whole scan: first the lines along Y, then (acrossPasses) the lines along X.
LinePlan planLine(const SyntheticTruth& truth, int k) {
  const SyntheticOptions& o = truth.options;
  const int ny = int(truth.lineX_m.size());
  const double linePeriodY = o.passes * (truth.passDuration_s + o.dwell_s) + 1.5;
  if (k < ny) return {1, truth.lineX_m[std::size_t(k)], truth.windowY0_m, truth.windowY1_m, truth.travel_m,
                      truth.passDuration_s, 1.0 + k * linePeriodY};
  const double linePeriodX = o.passes * (truth.passDurationX_s + o.dwell_s) + 1.5;
  const double half = o.lineSpacing_m / 2;
  return {0, truth.lineY_m[std::size_t(k - ny)], truth.lineX_m.front() - half, truth.lineX_m.back() + half,
          truth.travelX_m, truth.passDurationX_s, 1.0 + ny * linePeriodY + (k - ny) * linePeriodX};
}

// One line's robot and accelerometer logs, as CSV text.
std::pair<std::string, std::string> simulateLine(const SyntheticTruth& truth, int line) {
  const SyntheticOptions& o = truth.options;
  const LinePlan plan = planLine(truth, line);
  std::mt19937_64 rng(o.seed * 0x9E3779B97F4A7C15ull + std::uint64_t(line) * 0xBF58476D1CE4E5B9ull + 1);
  std::uniform_real_distribution<double> robotJitter(-o.robotJitter_s, o.robotJitter_s);
  std::uniform_real_distribution<double> accelJitter(-o.accelJitter_s, o.accelJitter_s);
  std::normal_distribution<double> robotNoise(0.0, o.robotNoise_m), accelNoise(0.0, o.accelNoise_g);
  std::string robot = "pass,t_s,x_m,y_m,z_m\n", accel = "pass,t_s,ax_g,ay_g,az_g\n";
  const double h = 2e-6;  // finite-difference step for the surface's slope and curvature
  const double mapped = plan.window1_m - plan.window0_m, margin = (plan.travel_m - mapped) / 2;
  // Surface height at a position along the line (object coordinates).
  const auto height = [&](double along_m) {
    return plan.axis == 1 ? truth.surface.surfaceHeight_m(plan.across_m - truth.objectX0_m, along_m - truth.objectY0_m)
                          : truth.surface.surfaceHeight_m(along_m - truth.objectX0_m, plan.across_m - truth.objectY0_m);
  };
  for (int pass = 0; pass < o.passes; ++pass) {
    const double start = plan.start_s + pass * (plan.duration_s + o.dwell_s);
    const double begin = start - 0.4 * o.dwell_s, end = start + plan.duration_s + 0.4 * o.dwell_s;
    const double dir = (pass % 2 == 0) ? 1.0 : -1.0;
    const double from = (pass % 2 == 0) ? plan.window0_m - margin : plan.window1_m + margin;
    for (int k = 0;; ++k) {
      const double t = begin + k / o.robotRate_hz + robotJitter(rng);
      if (t > end) break;
      const Motion m = trapezoid(t - start, plan.travel_m, o.speed_m_s, o.acceleration_m_s2, plan.duration_s);
      const double along = from + dir * m.s + robotNoise(rng), across = plan.across_m + robotNoise(rng);
      robot += std::to_string(pass) + ',';
      appendNumber(robot, t, 6), robot += ',';
      appendNumber(robot, plan.axis == 1 ? across : along, 7), robot += ',';
      appendNumber(robot, plan.axis == 1 ? along : across, 7), robot += ",0.0000000\n";
    }
    for (int j = 0;; ++j) {
      const double t = begin + j / o.accelRate_hz + accelJitter(rng);
      if (t > end) break;
      const Motion m = trapezoid(t - start, plan.travel_m, o.speed_m_s, o.acceleration_m_s2, plan.duration_s);
      const double a = from + dir * m.s;
      const double h0 = height(a), hp = height(a + h), hm = height(a - h);
      // z = h(s(t)): z'' = h_ss s'^2 + h_s s''; the direction signs cancel in s'^2 and pair in h_s s''.
      const double zdd = (hp - 2 * h0 + hm) / (h * h) * m.v * m.v + (hp - hm) / (2 * h) * dir * m.a;
      accel += std::to_string(pass) + ',';
      appendNumber(accel, t - o.accelClockOffset_s, 6), accel += ',';
      appendNumber(accel, accelNoise(rng), 5), accel += ',';
      appendNumber(accel, accelNoise(rng), 5), accel += ',';
      appendNumber(accel, 1.0 + zdd / kStandardGravity_m_s2 + accelNoise(rng), 5), accel += '\n';
    }
  }
  return {std::move(robot), std::move(accel)};
}

}  // namespace

double SyntheticTruth::vibration_g(double x_m, double y_m) const noexcept {
  const double k = 2 * std::numbers::pi / surface.wavelength_m;
  const double v = options.speed_m_s;
  return (2 / std::numbers::pi) * surface.peakAmplitude_m * surface.roughness(x_m - objectX0_m, y_m - objectY0_m) * v *
         v * k * k / kStandardGravity_m_s2;
}

double SyntheticTruth::passStart_s(int line, int pass) const noexcept {
  return planLine(*this, line).start_s + pass * (passDuration_s + options.dwell_s);
}

double SyntheticTruth::stylusY_m(int line, int pass, double t_s) const noexcept {
  const Motion m = trapezoid(t_s - passStart_s(line, pass), travel_m, options.speed_m_s, options.acceleration_m_s2,
                             passDuration_s);
  const double margin = (travel_m - options.scanLength_m) / 2;
  return pass % 2 == 0 ? windowY0_m - margin + m.s : windowY1_m + margin - m.s;
}

std::array<double, 2> SyntheticTruth::cruise_s(int line, int pass) const noexcept {
  const double ramp = options.speed_m_s / options.acceleration_m_s2, start = passStart_s(line, pass);
  return {start + ramp, start + passDuration_s - ramp};
}

SyntheticTruth makeSyntheticTruth(const SyntheticOptions& options) {
  SyntheticTruth truth;
  truth.options = options;
  SyntheticOptions& o = truth.options;
  if (o.name.empty()) o.name = std::string(kindName(o.kind));
  if (o.lines < 1 || o.passes < 1 || o.scanLength_m <= 0 || o.lineSpacing_m <= 0 || o.speed_m_s <= 0 ||
      o.acceleration_m_s2 <= 0 || o.robotRate_hz <= 0 || o.accelRate_hz <= 0 || o.photoWidth < 16 || o.photoHeight < 16) {
    fail("synthetic scan '", o.name, "': sizes, rates and speeds must be positive");
  }
  if (o.robotJitter_s >= 0.5 / o.robotRate_hz || o.accelJitter_s >= 0.5 / o.accelRate_hz) {
    fail("synthetic scan '", o.name, "': jitter must stay below half a sample period");
  }
  truth.travel_m = o.scanLength_m / (2 * kWindowW);
  truth.travelX_m = o.lines * o.lineSpacing_m / (2 * kWindowW);
  const double ramp_m = o.speed_m_s * o.speed_m_s / (2 * o.acceleration_m_s2);
  if (ramp_m >= truth.travel_m / 2 || (o.acrossPasses && ramp_m >= truth.travelX_m / 2)) {
    fail("synthetic scan '", o.name, "': the ramps are longer than the pass");
  }
  truth.passDuration_s = truth.travel_m / o.speed_m_s + o.speed_m_s / o.acceleration_m_s2;
  truth.passDurationX_s = truth.travelX_m / o.speed_m_s + o.speed_m_s / o.acceleration_m_s2;
  const double overrun = o.acrossPasses ? std::max(truth.travel_m - o.scanLength_m, truth.travelX_m - o.lines * o.lineSpacing_m)
                                        : truth.travel_m - o.scanLength_m;
  const double margin = std::max(0.006, overrun / 2 + 0.001);
  const double width = o.lines * o.lineSpacing_m + 2 * margin, height = o.scanLength_m + 2 * margin;
  truth.objectX0_m = 0.30;
  truth.objectY0_m = -0.05;
  truth.surface = makeSurface(o.kind, width, height, o.speed_m_s);
  truth.windowY0_m = truth.objectY0_m + margin;
  truth.windowY1_m = truth.windowY0_m + o.scanLength_m;
  for (int i = 0; i < o.lines; ++i) truth.lineX_m.push_back(truth.objectX0_m + margin + (i + 0.5) * o.lineSpacing_m);
  if (o.acrossPasses) {
    const int across = std::max(1, int(std::lround(o.scanLength_m / o.lineSpacing_m)));
    for (int i = 0; i < across; ++i) truth.lineY_m.push_back(truth.windowY0_m + (i + 0.5) * o.scanLength_m / across);
  }
  truth.camera = makeCamera(o, truth.objectX0_m + width / 2, truth.objectY0_m + height / 2, width, height);
  return truth;
}

std::vector<std::vector<Correspondence>> syntheticTargetViews(const SyntheticTruth& truth) {
  const SyntheticOptions& o = truth.options;
  const CameraModel& cam0 = truth.camera;
  // The object plane's footprint of the photo: the target spans it, so its tilted views reach
  // the photo's corners, where k2 shows.
  glm::dvec2 lo{1e9, 1e9}, hi{-1e9, -1e9};
  for (const glm::dvec2 corner : {glm::dvec2(0, 0), glm::dvec2(o.photoWidth, 0), glm::dvec2(0, o.photoHeight),
                                  glm::dvec2(o.photoWidth, o.photoHeight)}) {
    const glm::dvec2 p = cam0.planePoint(corner);
    lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  const glm::dvec2 centre = 0.5 * (lo + hi);
  // Tilts about the target's centre (axis * angle, rad), in the object plane's frame.
  constexpr std::array<std::array<double, 3>, 6> kTilts{{{0.35, 0.0, 0.0}, {0.0, 0.35, 0.1}, {-0.3, -0.25, 0.0},
                                                        {0.25, -0.3, -0.1}, {-0.35, 0.1, 0.05}, {0.1, -0.35, 0.0}}};
  constexpr int kGrid = 11;
  std::mt19937_64 rng(o.seed + 91);
  std::normal_distribution<double> click(0.0, o.clickNoise_px);
  const auto R0 = rotationFromVector(cam0.rvec);
  std::vector<std::vector<Correspondence>> views;
  for (int v = 0; v < o.targetViews; ++v) {
    const auto& tilt = kTilts[std::size_t(v) % kTilts.size()];
    const double turn = 0.4 * double(v / int(kTilts.size()));  // further views: the same tilts, turned in plane
    CameraModel cam = cam0;
    cam.rvec = vectorFromRotation(multiply3x3(R0, multiply3x3(rotationFromVector(tilt), rotationFromVector({0, 0, turn}))));
    const auto R = rotationFromVector(cam.rvec);
    // The target's centre stays where the object plane's centre point was.
    for (std::size_t k = 0; k < 3; ++k) {
      cam.t_m[k] += (R0[3 * k] - R[3 * k]) * centre.x + (R0[3 * k + 1] - R[3 * k + 1]) * centre.y;
    }
    std::vector<Correspondence> view;
    for (int i = 0; i < kGrid; ++i) {
      for (int j = 0; j < kGrid; ++j) {
        const double x = lo.x + (hi.x - lo.x) * i / (kGrid - 1), y = lo.y + (hi.y - lo.y) * j / (kGrid - 1);
        const glm::dvec2 p = cam.project(x, y);
        if (!(p.x >= 0 && p.y >= 0 && p.x <= o.photoWidth - 1 && p.y <= o.photoHeight - 1)) continue;
        view.push_back({x, y, p.x + click(rng), p.y + click(rng)});
      }
    }
    views.push_back(std::move(view));
  }
  return views;
}

SyntheticTruth writeSyntheticScan(const SyntheticOptions& options, const std::filesystem::path& outDir, int jobs,
                                  bool replace) {
  SyntheticTruth truth = makeSyntheticTruth(options);
  const SyntheticOptions& o = truth.options;
  // Built whole under a temporary name: a failed run leaves no half scan that loads as valid.
  StagedFolder staged(outDir, replace);
  const std::filesystem::path& dir = staged.dir();
  std::error_code ec;
  std::filesystem::create_directories(dir / "lines", ec);
  if (ec) fail("cannot create scan directory '", dir.string(), "': ", ec.message());

  std::vector<LineFiles> files;
  for (int i = 0; i < o.lines; ++i) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "lines/line_%03d", i);
    files.push_back({std::string(stem) + "_robot.csv", std::string(stem) + "_accel.csv"});
  }
  for (std::size_t i = 0; i < truth.lineY_m.size(); ++i) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "lines/xline_%03d", int(i));
    files.push_back({std::string(stem) + "_robot.csv", std::string(stem) + "_accel.csv", 0});
  }
  detail::parallelFor(
      files.size(), jobs,
      [&](std::size_t i) {
        const auto [robot, accel] = simulateLine(truth, int(i));
        writeFileAtomically(dir / files[i].robot, robot);
        writeFileAtomically(dir / files[i].accel, accel);
      },
      [](std::size_t) {});
  savePng(dir / "photo.png", renderPhoto(truth));

  // Marked points: a grid over the scanned area (plus 3 mm), clicked with pixel noise.
  std::mt19937_64 rng(o.seed + 77);
  std::normal_distribution<double> click(0.0, o.clickNoise_px);
  std::string calib = "x_m,y_m,u_px,v_px\n";
  const double x0 = truth.lineX_m.front() - 0.003, x1 = truth.lineX_m.back() + 0.003;
  const double y0 = truth.windowY0_m - 0.003, y1 = truth.windowY1_m + 0.003;
  const int n = std::max(3, o.calibrationGrid);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = x0 + (x1 - x0) * i / (n - 1), y = y0 + (y1 - y0) * j / (n - 1);
      const glm::dvec2 p = truth.camera.project(x, y);
      appendNumber(calib, x, 6), calib += ',', appendNumber(calib, y, 6), calib += ',';
      appendNumber(calib, p.x + click(rng), 3), calib += ',', appendNumber(calib, p.y + click(rng), 3), calib += '\n';
    }
  }
  writeFileAtomically(dir / "calibration.csv", calib);
  std::vector<std::string> viewFiles;
  for (const auto& view : syntheticTargetViews(truth)) {
    std::string text = "x_m,y_m,u_px,v_px\n";
    for (const Correspondence& c : view) {
      appendNumber(text, c.x_m, 6), text += ',', appendNumber(text, c.y_m, 6), text += ',';
      appendNumber(text, c.u_px, 3), text += ',', appendNumber(text, c.v_px, 3), text += '\n';
    }
    viewFiles.push_back("calibration_view_" + std::to_string(viewFiles.size() + 1) + ".csv");
    writeFileAtomically(dir / viewFiles.back(), text);
  }

  // Rectify to a top view (image right = +Y, down = +X) at a known scale, then crop to the
  // scanned area; the operator's perspective transform, computed from the true camera.
  ScanConfig config;
  config.name = o.name;
  config.passesPerLine = o.passes;
  config.accelClockOffset_s = o.accelClockOffset_s;
  const double s = o.topViewScale_px_per_mm * 1e3;  // px per metre
  const int cropW = int(std::lround(o.scanLength_m * s)), cropH = int(std::lround(o.lines * o.lineSpacing_m * s));
  const int pad = 8;
  const double xa = truth.lineX_m.front() - o.lineSpacing_m / 2 - pad / s, ya = truth.windowY0_m - pad / s;
  const std::array<double, 9> topView{0, s, -s * ya, s, 0, -s * xa, 0, 0, 1};
  config.perspective = multiply3x3(topView, inverse3x3(planeHomography(truth.camera)));
  config.warpSize = {cropW + 2 * pad, cropH + 2 * pad};
  config.crop = std::array<int, 4>{pad, pad, cropW, cropH};
  config.physicalSize_m = std::array<double, 2>{o.scanLength_m, o.lines * o.lineSpacing_m};
  writeFileAtomically(dir / "scan.json", scanConfigJson(config, "photo.png", "calibration.csv", files, viewFiles));

  const CameraModel& c = truth.camera;
  nlohmann::json doc;
  doc["kind"] = std::string(kindName(o.kind));
  doc["camera"] = {{"fx", c.fx}, {"fy", c.fy}, {"cx", c.cx}, {"cy", c.cy}, {"k1", c.k1}, {"k2", c.k2},
                   {"rvec", c.rvec}, {"t_m", c.t_m}};
  doc["object_corner_m"] = {truth.objectX0_m, truth.objectY0_m};
  doc["object_size_m"] = {truth.surface.width_m, truth.surface.height_m};
  doc["window_y_m"] = {truth.windowY0_m, truth.windowY1_m};
  doc["speed_m_s"] = o.speed_m_s;
  doc["accel_clock_offset_s"] = o.accelClockOffset_s;
  doc["seed"] = o.seed;
  writeFileAtomically(dir / "truth.json", doc.dump(2) + "\n");
  staged.commit();
  return truth;
}

}  // namespace vt::acq
