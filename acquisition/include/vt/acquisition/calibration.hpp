#pragma once
// World to pixel, p = f(P): a pinhole camera with two radial distortion terms, calibrated
// from planar robot/pixel correspondences by Zhang's method (homography initialisation,
// then Levenberg-Marquardt over intrinsics, extrinsics and k1, k2). Any thread may call.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "vt/acquisition/scan.hpp"

namespace vt::acq {

/// Intrinsics, radial distortion and pose (OpenCV conventions: x right, y down, z forward).
struct CameraModel {
  double fx = 1000, fy = 1000, cx = 0, cy = 0;
  double k1 = 0, k2 = 0;
  double p1 = 0, p2 = 0, k3 = 0;        // tangential and third radial term (a KnownCamera's; never fitted)
  std::array<double, 3> rvec{0, 0, 0};  // rotation world -> camera, axis * angle (rad)
  std::array<double, 3> t_m{0, 0, 1};   // translation world -> camera, metres

  /// Pixel of the world point (X, Y, Z) in metres, robot base frame.
  glm::dvec2 project(double x_m, double y_m, double z_m = 0.0) const noexcept;
  /// Pixel of an ideal (undistorted) normalised image point; used with the plane homography.
  glm::dvec2 distort(glm::dvec2 normalised) const noexcept;
  /// World (X, Y) on the plane Z = 0 seen at a pixel (the inverse of project at Z = 0).
  glm::dvec2 planePoint(glm::dvec2 pixel) const noexcept;
};

/// 3x3 rotation matrix (row-major) of an axis-angle vector (Rodrigues).
std::array<double, 9> rotationFromVector(const std::array<double, 3>& rvec) noexcept;
/// Axis-angle vector of a 3x3 rotation matrix (row-major).
std::array<double, 3> vectorFromRotation(const std::array<double, 9>& r) noexcept;

/// The fitted camera and how well it explains the marked points.
struct CalibrationResult {
  CameraModel camera;
  double rmsError_px = 0;
  double maxError_px = 0;
  std::vector<double> errors_px;  // per correspondence
  int iterations = 0;
  bool converged = false;
  int views = 1;                       // planar target views used
  /// Gaussian priors (mean, std) the fit used on fx fy cx cy k1 k2, where it used one.
  std::array<std::optional<std::array<double, 2>>, 6> priors{};
  std::array<double, 6> std{};         // standard errors of fx fy cx cy k1 k2 (priors included)
  bool given = false;                  // the camera came from scan.json's "camera", not a fit

  /// Whether intrinsic `parameter` (0..5: fx fy cx cy k1 k2) is well determined (small std).
  bool reliable(int parameter) const noexcept;
  /// Whether its value comes mostly from its prior (the data narrowed the prior by under 30 %).
  bool fromPrior(int parameter) const noexcept;
};

/// What the calibration may assume besides the points.
struct CalibrationPriors {
  double principalPointWeight = 1e-3;  // several views: weak pull (px per px) of cx, cy to the centre
  std::optional<std::array<double, 2>> focal_px;  // focal length (fx and fy): mean, std in pixels
};

/// Calibrates from >= 8 correspondences on the plane Z = 0 (the object surface) and optional
/// further views of a planar target (its own coordinates, Z = 0) seen by the same camera;
/// the returned pose is the object plane's. One view puts priors on cx, cy (image centre) and k2 (0).
/// `source` names the calibration file in errors (too few points, degenerate layout, no convergence).
CalibrationResult calibrateCamera(std::span<const Correspondence> points, int imageWidth, int imageHeight,
                                  const CalibrationPriors& priors, const std::string& source,
                                  std::span<const std::vector<Correspondence>> extraViews = {});

/// The camera of scan.json's "camera" and its reprojection errors on `points` (nothing fitted).
CalibrationResult givenCamera(const KnownCamera& camera, std::span<const Correspondence> points);

/// The calibration report as JSON text (camera, errors, per-point residuals).
std::string calibrationReportJson(const CalibrationResult& result, std::span<const Correspondence> points);

}  // namespace vt::acq
